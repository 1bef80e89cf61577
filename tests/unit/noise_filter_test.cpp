#include "noise_filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../physics/test_scenes.h"

namespace physhand {
namespace {

using testing::Noisy;

constexpr double kDt = 1 / 90.0;
constexpr double kAcceleration = 1.0;

// A clean hand moving and closing: every sample comes out exactly as it went in.
TEST(NoiseFilter, PassesCleanTrackingThroughExactly) {
    NoiseFilter f;
    f.reset(testing::right_hand(Vec3(0, 1, 0), 0.0));
    for (int frame = 1; frame < 270; ++frame) {
        const double t = frame * kDt;
        const HandPose in =
            testing::right_hand(Vec3(0.2 * std::sin(3.0 * t), 1.0 + 0.1 * std::sin(5.0 * t), 0.0),
                                0.5 - 0.5 * std::cos(4.0 * t));
        const HandPose out = f.apply(in, kDt, kAcceleration);
        for (std::size_t j = 0; j < kJointCount; ++j)
            ASSERT_EQ(out.joints[j].position, in.joints[j].position) << "frame " << frame;
    }
    EXPECT_LT(f.noise(), 0.25e-3);
}

// A still hand under 3 mm of noise: the noise is measured, and most of it taken out.
TEST(NoiseFilter, MeasuresNoiseAndTakesMostOfItOut) {
    const HandPose still = testing::right_hand(Vec3(0, 1, 0), 0.3);
    Noisy noisy(0.003);
    NoiseFilter f;
    f.reset(still);
    double in_sq = 0.0, out_sq = 0.0;
    int counted = 0;
    for (int frame = 1; frame < 450; ++frame) {
        const HandPose in = noisy(still);
        const HandPose out = f.apply(in, kDt, kAcceleration);
        if (frame < 180) continue;  // the estimate settles over its memory
        for (std::size_t j = 0; j < kJointCount; ++j) {
            in_sq += (in.joints[j].position - still.joints[j].position).squaredNorm();
            out_sq += (out.joints[j].position - still.joints[j].position).squaredNorm();
            ++counted;
        }
    }
    EXPECT_NEAR(f.noise(), 0.003, 0.0005);
    const double in_rms = std::sqrt(in_sq / counted), out_rms = std::sqrt(out_sq / counted);
    EXPECT_LT(out_rms, 0.5 * in_rms) << in_rms << " -> " << out_rms;
}

// A deliberate squeeze under 3 mm of noise: fingers that start closing at 0.2 m/s are never
// more than 50 ms behind (measured on the mean of the closing joints, where the noise
// averages out), and have caught up half a second later.
TEST(NoiseFilter, FollowsASqueezeWithinFiftyMilliseconds) {
    const HandPose still = testing::right_hand(Vec3(0, 1, 0), 0.3);
    Noisy noisy(0.003);
    NoiseFilter f;
    f.reset(still);
    for (int frame = 1; frame < 180; ++frame) f.apply(noisy(still), kDt, kAcceleration);
    const Vec3 squeeze(0.2, 0.0, 0.0);
    double most_behind_s = 0.0;
    for (int frame = 1; frame <= 45; ++frame) {
        const double t = frame * kDt;
        HandPose truth = still;
        for (std::size_t j = 6; j < kJointCount; ++j) truth.joints[j].position += squeeze * t;
        const HandPose out = f.apply(noisy(truth), kDt, kAcceleration);
        double trailing = 0.0;
        for (std::size_t j = 6; j < kJointCount; ++j)
            trailing += (truth.joints[j].position - out.joints[j].position).x();
        trailing /= kJointCount - 6;
        most_behind_s = std::max(most_behind_s, trailing / squeeze.x());
        if (frame == 45) {
            EXPECT_LT(std::abs(trailing), 0.001) << "after 0.5 s";
        }
    }
    EXPECT_LT(most_behind_s, 0.05);
}

TEST(NoiseFilter, OffPassesTheGhostThrough) {
    NoiseFilter f;
    const HandPose still = testing::right_hand(Vec3(0, 1, 0), 0.3);
    f.reset(still);
    Noisy noisy(0.003);
    for (int frame = 1; frame < 100; ++frame) {
        const HandPose in = noisy(still);
        const HandPose out = f.apply(in, kDt, 0.0);
        ASSERT_EQ(out.joints[3].position, in.joints[3].position);
    }
}

}  // namespace
}  // namespace physhand
