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

// Times this close are the same time: a display time of k/90 s and the frame the clock
// times in whole nanoseconds, a time in seconds and the XrTime it came from.
inline constexpr double kSameTimeS = 1e-6;

inline double frame_time_s(std::int64_t frame) {
    return clock_seconds(frame * kFramePeriodNs);
}

// The period of another display rate in whole nanoseconds, as that one is at 90 Hz.
inline std::int64_t frame_period_ns(double rate_hz) {
    return static_cast<std::int64_t>(1e9 / rate_hz);
}

// The display rates a run or the simulated runtime may show, and the most a frame may come
// early or late at a rate: under a third of a period keeps frames in order.
inline constexpr double kMinDisplayHz = 20.0;
inline constexpr double kMaxDisplayHz = 240.0;
inline double max_frame_jitter_ms(double rate_hz) {
    return 1e3 / (3.0 * rate_hz);
}

// How early (-) or late (+) display frame `frame` (from 1) is shown: uniform within
// +-jitter_ns, from the frame's number and `seed` alone (a splitmix64 hash), so any frame's
// time can be worked out again and runs repeat. The first frame is on time. The headless
// runner and the simulated runtime share it, so both show frames at the very same times.
inline std::int64_t frame_jitter_ns(std::int64_t frame, std::int64_t jitter_ns,
                                    std::uint64_t seed) {
    if (jitter_ns <= 0 || frame <= 1) return 0;
    const auto mix = [](std::uint64_t x) {
        x += 0x9e3779b97f4a7c15ULL;
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
        return x ^ (x >> 31);
    };
    const double u = static_cast<double>(mix(seed ^ mix(static_cast<std::uint64_t>(frame))) >> 11) *
                     0x1.0p-53;  // uniform in [0, 1)
    return std::llround((2.0 * u - 1.0) * static_cast<double>(jitter_ns));
}

// Whether a scene of `duration_s` is over once a frame at scene time `t_s` has played: it
// plays up to the frame at or just past its end, at any display rate and with any jitter.
// The tolerance keeps a duration of a whole number of frames (1.1 s at 90 Hz: 99) from
// gaining one through rounding.
inline bool scene_over(double t_s, double duration_s) {
    return t_s >= duration_s - kSameTimeS;
}

}  // namespace physhand
