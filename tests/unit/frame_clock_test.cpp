#include "frame_clock.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

namespace physhand {
namespace {

// The frames a scene plays at `rate_hz`: up to the first that is over.
int frames_played(double duration_s, double rate_hz = kFrameRateHz, std::int64_t jitter_ns = 0,
                  std::uint64_t seed = 0) {
    int f = 1;
    while (!scene_over(
        clock_seconds(f * frame_period_ns(rate_hz) + frame_jitter_ns(f, jitter_ns, seed)),
        duration_s)) {
        ++f;
    }
    return f;
}

TEST(SceneOver, PlaysUpToTheFrameAtOrJustPastTheEnd) {
    EXPECT_EQ(frames_played(1.0), 90);
    EXPECT_EQ(frames_played(1.005), 91);
    EXPECT_EQ(frames_played(0.001), 1);
    EXPECT_EQ(frames_played(1.0, 144.0), 144);
    EXPECT_EQ(frames_played(1.0, 20.0), 20);
}

TEST(SceneOver, AWholeNumberOfFramesGainsNoneThroughRounding) {
    // 1.1 * 90 is 99.00000000000001 in doubles, 8.3 * 90 747.0000000000001, and frame 99 in
    // whole nanoseconds 1.09999999 s.
    EXPECT_EQ(frames_played(1.1), 99);
    EXPECT_EQ(frames_played(8.3), 747);
}

TEST(SceneOver, AJitteredSceneLastsItsDurationGiveOrTakeAFrame) {
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
        const int frames = frames_played(2.0, 90.0, 3'000'000, seed);
        EXPECT_GE(frames, 180);
        EXPECT_LE(frames, 181);
    }
}

TEST(FrameJitter, IsWithinItsBoundRepeatableAndLeavesTheFirstFrameOnTime) {
    EXPECT_EQ(frame_jitter_ns(1, 2'000'000, 5), 0);
    EXPECT_EQ(frame_jitter_ns(7, 0, 5), 0);
    std::int64_t lowest = 0, highest = 0;
    for (std::int64_t f = 2; f < 2000; ++f) {
        const std::int64_t j = frame_jitter_ns(f, 2'000'000, 5);
        EXPECT_EQ(j, frame_jitter_ns(f, 2'000'000, 5));
        EXPECT_LE(std::abs(j), 2'000'000);
        lowest = std::min(lowest, j);
        highest = std::max(highest, j);
    }
    // Spread over the whole range, both ways.
    EXPECT_LT(lowest, -1'900'000);
    EXPECT_GT(highest, 1'900'000);
    EXPECT_NE(frame_jitter_ns(10, 2'000'000, 5), frame_jitter_ns(10, 2'000'000, 6));
}

}  // namespace
}  // namespace physhand
