#include "skeleton_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../physics/test_scenes.h"

namespace physhand {
namespace {

using testing::Noisy;

constexpr double kDt = 1 / 90.0;

// A hand moving, turning and closing as a person's does.
HandPose moving_hand(double t) {
    const Quat turn(Eigen::AngleAxisd(0.6 * std::sin(2.0 * t), Vec3::UnitY()) *
                    Eigen::AngleAxisd(0.3 * std::sin(3.0 * t), Vec3::UnitX()));
    return testing::hand_pose(HandSide::Right,
                              Vec3(0.2 * std::sin(3.0 * t), 1.0 + 0.1 * std::sin(5.0 * t), 0.0),
                              0.5 - 0.5 * std::cos(4.0 * t), turn);
}

// RMS distance per joint between two hands, m.
double rms_distance(const HandPose& a, const HandPose& b) {
    double sum = 0.0;
    for (std::size_t j = 0; j < kJointCount; ++j)
        sum += (a.joints[j].position - b.joints[j].position).squaredNorm();
    return std::sqrt(sum / kJointCount);
}

// How far the ghosts given and the fitted ones lay from the truth, RMS per joint, m.
struct Errors {
    double given = 0.0, fitted = 0.0;
};

// Plays frames `first` to `last` (exclusive) of `truth` through `fit`, each sample as
// `track` gives it, and measures the frames from `measured` on.
template <class Truth, class Track>
Errors play(SkeletonFit& fit, int first, int last, int measured, Truth truth, Track track) {
    double given_sq = 0.0, fitted_sq = 0.0;
    int counted = 0;
    for (int frame = first; frame < last; ++frame) {
        const HandPose real = truth(frame);
        const HandPose in = track(real, frame);
        const HandPose out = fit.apply(in, kDt);
        if (frame < measured) continue;
        given_sq += std::pow(rms_distance(in, real), 2);
        fitted_sq += std::pow(rms_distance(out, real), 2);
        ++counted;
    }
    return {std::sqrt(given_sq / counted), std::sqrt(fitted_sq / counted)};
}

HandPose moving_hand_at(int frame) {
    return moving_hand(frame * kDt);
}

// Positions and orientations of one skeleton: every sample comes out exactly as it went in.
TEST(SkeletonFit, PassesAHandWhoseJointsAgreeExactly) {
    SkeletonFit fit;
    fit.restart(moving_hand(0.0));
    for (int frame = 1; frame < 450; ++frame) {
        const HandPose in = moving_hand(frame * kDt);
        const HandPose out = fit.apply(in, kDt);
        for (std::size_t j = 0; j < kJointCount; ++j)
            ASSERT_EQ(out.joints[j].position, in.joints[j].position) << "frame " << frame;
    }
}

// Noise a skeleton makes (the hand's pose and its fingers' curl jittering, every joint where
// the skeleton puts it) is the runtime's to pass on: nothing is taken out.
TEST(SkeletonFit, LeavesNoiseThatTheSkeletonMakesItself) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> n(0.0, 1.0);
    SkeletonFit fit;
    for (int frame = 0; frame < 450; ++frame) {
        const Quat jitter(
            Eigen::AngleAxisd(0.03 * n(rng), Vec3(n(rng), n(rng), n(rng)).normalized()));
        HandArticulation a;
        for (double& c : a.curl) c = 0.4 + 0.05 * n(rng);
        const HandPose in =
            pose_hand(HandSide::Right,
                      Pose{Vec3(0.003 * n(rng), 1.0 + 0.003 * n(rng), 0.003 * n(rng)), jitter}, a);
        const HandPose out = frame == 0 ? (fit.restart(in), in) : fit.apply(in, kDt);
        ASSERT_LT(rms_distance(out, in), 1e-6) << "frame " << frame;
    }
}

// Each joint's own noise (3 mm per axis, a bone changing length from sample to sample) is cut
// to what the whole hand shares, on a hand that moves, turns and closes.
TEST(SkeletonFit, TakesOutTheNoiseEachJointMakesAlone) {
    Noisy noisy(0.003);
    SkeletonFit fit;
    fit.restart(noisy(moving_hand(0.0)));
    // From 2 s on: the bones are learned and the noise measured.
    const Errors e = play(fit, 1, 900, 180, moving_hand_at,
                          [&](const HandPose& real, int) { return noisy(real); });
    EXPECT_LT(e.fitted, 0.3 * e.given) << e.given << " -> " << e.fitted;
    EXPECT_NEAR(fit.position_noise(), 0.003 * std::sqrt(2.0), 0.001);  // a bone: two joints'
}

// A tracker at 30 Hz, its noisy samples interpolated to every 90 Hz frame (as the scenes'
// tracking and a runtime's predicted poses are): the noise is still found and taken out.
TEST(SkeletonFit, TakesOutTheNoiseOfASlowerTrackerInterpolated) {
    Noisy noisy(0.002);
    std::vector<HandPose> samples;
    for (int k = 0; k < 320; ++k) samples.push_back(noisy(moving_hand(k / 30.0)));
    SkeletonFit fit;
    fit.restart(samples[0]);
    const Errors e = play(fit, 1, 900, 180, moving_hand_at, [&](const HandPose&, int frame) {
        const auto k = static_cast<std::size_t>(frame / 3);
        HandPose in = samples[k];
        for (std::size_t j = 0; j < kJointCount; ++j) {
            in.joints[j] =
                interpolate(samples[k].joints[j], samples[k + 1].joints[j], (frame % 3) / 3.0);
        }
        return in;
    });
    EXPECT_LT(e.fitted, 0.5 * e.given) << e.given << " -> " << e.fitted;
}

// The hand scaled about its wrist.
HandPose scaled(const HandPose& hand, double scale) {
    HandPose out = hand;
    const Vec3 wrist = hand[Joint::Wrist].position;
    for (Pose& p : out.joints) p.position = wrist + scale * (p.position - wrist);
    return out;
}

// Bursts of garbage (up to 5 cm on every joint, 3 samples in 20) while the bones are learned
// are not learned: the noise that follows is taken out as well as without them.
TEST(SkeletonFit, LearnsNoGarbage) {
    Noisy burst(0.05, 11), noisy(0.003);
    SkeletonFit fit;
    fit.restart(moving_hand(0.0));
    const Errors e = play(fit, 1, 900, 450, moving_hand_at, [&](const HandPose& real, int frame) {
        return frame < 270 && frame % 20 < 3 ? burst(real) : noisy(real);
    });
    EXPECT_LT(e.fitted, 0.3 * e.given) << e.given << " -> " << e.fitted;
}

// A runtime that makes its hand 8 % larger (bones 2-6 mm longer): a clean ghost passes
// within 0.1 mm of itself again 1.5 s later (1.4 mm off at first), and a noisy one is fitted
// to the new bones.
TEST(SkeletonFit, FollowsBonesThatChange) {
    SkeletonFit fit;
    fit.restart(moving_hand(0.0));
    double worst = 0.0;
    for (int frame = 1; frame < 360; ++frame) {
        const HandPose in = scaled(moving_hand(frame * kDt), frame < 180 ? 1.0 : 1.08);
        const HandPose out = fit.apply(in, kDt);
        if (frame >= 180 + 135) worst = std::max(worst, rms_distance(out, in));
    }
    EXPECT_LT(worst, 1e-4);
    Noisy noisy(0.003);
    const Errors e = play(
        fit, 360, 900, 540, [](int frame) { return scaled(moving_hand_at(frame), 1.08); },
        [&](const HandPose& real, int) { return noisy(real); });
    EXPECT_LT(e.fitted, 0.3 * e.given) << e.given << " -> " << e.fitted;
}

// A runtime whose joint orientations say nothing of its bones (left at identity while the hand
// turns): the positions pass as they came, noise and all.
TEST(SkeletonFit, TrustsNoOrientationsThatDoNotDescribeTheBones) {
    Noisy noisy(0.002);
    SkeletonFit fit;
    for (int frame = 0; frame < 450; ++frame) {
        const Quat turn(Eigen::AngleAxisd(3.0 * frame * kDt, Vec3::UnitY()));
        HandPose in = noisy(testing::hand_pose(HandSide::Right, Vec3(0, 1, 0), 0.3, turn));
        for (Pose& joint : in.joints) joint.orientation = Quat::Identity();
        const HandPose out = frame == 0 ? (fit.restart(in), in) : fit.apply(in, kDt);
        if (frame >= 90) {
            ASSERT_EQ(rms_distance(out, in), 0.0) << "frame " << frame;
        }
    }
}

}  // namespace
}  // namespace physhand
