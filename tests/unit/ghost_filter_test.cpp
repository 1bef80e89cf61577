#include "ghost_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../physics/test_scenes.h"

namespace physhand {
namespace {

constexpr double kDt = 1 / 90.0;
constexpr GhostSmoothing kOn{1.0, 3500.0};

HandPose hand_at(const Vec3& wrist, double curl = 0.2) {
    return testing::right_hand(wrist, curl);
}

TEST(GhostFilter, OffPassesTheGhostThrough) {
    GhostFilter f;
    f.reset(hand_at(Vec3::Zero()));
    const HandPose moved = hand_at(Vec3(0.1, 0, 0));
    const HandPose out = f.apply(moved, kDt, GhostSmoothing{});
    for (std::size_t j = 0; j < kJointCount; ++j) {
        EXPECT_EQ(out.joints[j].position, moved.joints[j].position);
        EXPECT_EQ(out.joints[j].orientation.coeffs(), moved.joints[j].orientation.coeffs());
    }
}

// A still hand under 2 mm of noise: the filtered joints move far less frame to frame.
TEST(GhostFilter, StillHandLosesMostOfItsNoise) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 0.002);
    const HandPose still = hand_at(Vec3(0, 1, 0));
    GhostFilter f;
    f.reset(still);
    HandPose previous_in = still, previous_out = still;
    double in_sq = 0.0, out_sq = 0.0;
    for (int frame = 0; frame < 900; ++frame) {
        HandPose noisy = still;
        for (Pose& p : noisy.joints) p.position += Vec3(noise(rng), noise(rng), noise(rng));
        const HandPose out = f.apply(noisy, kDt, kOn);
        for (std::size_t j = 0; j < kJointCount; ++j) {
            in_sq += (noisy.joints[j].position - previous_in.joints[j].position).squaredNorm();
            out_sq += (out.joints[j].position - previous_out.joints[j].position).squaredNorm();
        }
        previous_in = noisy;
        previous_out = out;
    }
    EXPECT_LT(std::sqrt(out_sq / in_sq), 0.5);
}

// A hand moving at 0.5 m/s is followed within a tenth of a millimetre once the filter has
// seen its speed, and comes to rest where the ghost stops.
TEST(GhostFilter, MovingHandIsFollowedClosely) {
    GhostFilter f;
    f.reset(hand_at(Vec3::Zero()));
    HandPose out;
    for (int frame = 1; frame <= 90; ++frame) {
        const HandPose ghost = hand_at(Vec3(0.5 * frame * kDt, 0, 0));
        out = f.apply(ghost, kDt, kOn);
        if (frame > 45) {
            EXPECT_LT((out[Joint::IndexTip].position - ghost[Joint::IndexTip].position).norm(),
                      1e-4)
                << frame;
        }
    }
    const HandPose stop = hand_at(Vec3(0.5, 0, 0));
    for (int frame = 0; frame < 270; ++frame) out = f.apply(stop, kDt, kOn);
    EXPECT_LT((out[Joint::Palm].position - stop[Joint::Palm].position).norm(), 1e-6);
}

// Fingers closing while the wrist stands still are not held back by the still hand.
TEST(GhostFilter, FingersMovingAloneAreFollowed) {
    GhostFilter f;
    f.reset(hand_at(Vec3::Zero(), 0.0));
    double worst = 0.0;
    for (int frame = 1; frame <= 45; ++frame) {
        const HandPose ghost = hand_at(Vec3::Zero(), frame / 45.0);  // a fist in 0.5 s
        const HandPose out = f.apply(ghost, kDt, kOn);
        if (frame > 10) {
            worst = std::max(
                worst, (out[Joint::IndexTip].position - ghost[Joint::IndexTip].position).norm());
        }
    }
    EXPECT_LT(worst, 0.002);
}

// Smoothing that resumes after the filter only followed the ghost (a touch, a gated hand)
// knows the hand's speed: a moving hand is not held back, and a still, noisy one is smoothed
// at once rather than passed through.
TEST(GhostFilter, ResumedSmoothingKnowsTheHandsSpeed) {
    GhostFilter moving;
    moving.reset(hand_at(Vec3::Zero()));
    for (int frame = 1; frame <= 90; ++frame)
        moving.follow(hand_at(Vec3(0.5 * frame * kDt, 0, 0)), kDt, kOn);
    const HandPose next = hand_at(Vec3(0.5 * 91 * kDt, 0, 0));
    const HandPose out = moving.apply(next, kDt, kOn);
    EXPECT_LT((out[Joint::Palm].position - next[Joint::Palm].position).norm(), 1e-4);

    std::mt19937_64 rng(5);
    std::normal_distribution<double> noise(0.0, 0.002);
    const HandPose still = hand_at(Vec3::Zero());
    auto noisy = [&] {
        HandPose h = still;
        for (Pose& p : h.joints) p.position += Vec3(noise(rng), noise(rng), noise(rng));
        return h;
    };
    GhostFilter resting;
    resting.reset(still);
    for (int frame = 0; frame < 90; ++frame) resting.follow(noisy(), kDt, kOn);
    HandPose previous = resting.apply(noisy(), kDt, kOn);
    double moved_sq = 0.0;
    for (int frame = 0; frame < 5; ++frame) {
        const HandPose out = resting.apply(noisy(), kDt, kOn);
        moved_sq +=
            (out[Joint::IndexTip].position - previous[Joint::IndexTip].position).squaredNorm();
        previous = out;
    }
    // The noise alone moves a joint sqrt(6) * 2 mm a frame.
    EXPECT_LT(std::sqrt(moved_sq / 5), 0.5 * std::sqrt(6.0) * 0.002);
}

// Orientations pass unsmoothed: a knuckle that turns in place would otherwise trail.
TEST(GhostFilter, OrientationsPassThrough) {
    GhostFilter f;
    f.reset(hand_at(Vec3::Zero(), 0.0));
    const HandPose fist = hand_at(Vec3::Zero(), 1.0);
    const HandPose out = f.apply(fist, kDt, kOn);
    for (std::size_t j = 0; j < kJointCount; ++j)
        EXPECT_EQ(out.joints[j].orientation.coeffs(), fist.joints[j].orientation.coeffs()) << j;
}

TEST(GhostFilter, ResetStartsOverAtTheGivenPose) {
    GhostFilter f;
    f.reset(hand_at(Vec3::Zero()));
    f.apply(hand_at(Vec3(0.01, 0, 0)), kDt, kOn);
    const HandPose far = hand_at(Vec3(3, 0, 0));
    f.reset(far);
    const HandPose out = f.apply(far, kDt, kOn);
    EXPECT_LT((out[Joint::Wrist].position - far[Joint::Wrist].position).norm(), 1e-12);
}

}  // namespace
}  // namespace physhand
