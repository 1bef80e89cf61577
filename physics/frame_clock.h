#pragma once

#include <cmath>
#include <cstdint>

namespace physhand {

// Displayed frames at 90 Hz, timed as an OpenXR runtime reports them: whole nanoseconds.
// Frame k (k >= 1) is shown at k * kFramePeriodNs after the scene starts. The headless
// runner and the simulated runtime share this clock so that the physics-only path and the
// path through the layer see the very same times.
inline constexpr std::int64_t kFramePeriodNs = 11'111'111;
inline constexpr double kFrameRateHz = 90.0;

// Seconds of a nanosecond count, computed one way everywhere so equal clocks agree bit for bit.
inline double clock_seconds(std::int64_t ns) {
    return static_cast<double>(ns) * 1e-9;
}

inline double frame_time_s(std::int64_t frame) {
    return clock_seconds(frame * kFramePeriodNs);
}

// The frames a scene of `duration_s` plays, 1..N: enough 90 Hz frames to cover it. The
// tolerance keeps a duration of a whole number of frames (1.1 s: 99) from gaining one
// through rounding.
inline int scene_frame_count(double duration_s) {
    return static_cast<int>(std::ceil(duration_s * kFrameRateHz - 1e-9));
}

}  // namespace physhand
