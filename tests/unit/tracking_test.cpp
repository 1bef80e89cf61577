#include "tracking.h"

#include <gtest/gtest.h>

#include "scene.h"

namespace physhand {
namespace {

Scene two_keyframe_scene(Interpolation interpolation) {
    Scene s;
    s.name = "t";
    s.duration_s = 2.0;
    HandScript script;
    script.interpolation = interpolation;
    Keyframe a;
    a.t = 0.0;
    a.wrist.position = Vec3(0, 1, 0);
    Keyframe b;
    b.t = 1.0;
    b.wrist.position = Vec3(0.2, 1, 0);
    b.articulation.curl = {1, 1, 1, 1, 1};
    script.keyframes = {a, b};
    s.hands[static_cast<int>(HandSide::Right)] = script;
    return s;
}

TEST(Tracking, LinearScriptInterpolatesPositionAndCurl) {
    const Scene s = two_keyframe_scene(Interpolation::Linear);
    const HandPose mid = evaluate_script(*s.hand(HandSide::Right), HandSide::Right, 0.25);
    EXPECT_NEAR(mid[Joint::Wrist].position.x(), 0.05, 1e-12);
    HandArticulation quarter;
    quarter.curl = {0.25, 0.25, 0.25, 0.25, 0.25};
    const HandPose expected =
        pose_hand(HandSide::Right, Pose{Vec3(0.05, 1, 0), Quat::Identity()}, quarter);
    EXPECT_NEAR((mid[Joint::IndexTip].position - expected[Joint::IndexTip].position).norm(), 0,
                1e-12);
}

TEST(Tracking, SmoothScriptEasesAndHoldsBeyondItsKeys) {
    const Scene s = two_keyframe_scene(Interpolation::Smooth);
    const HandScript& script = *s.hand(HandSide::Right);
    // Cubic Hermite with flat ends: 0.2 * (3 s^2 - 2 s^3) at s = 0.25.
    EXPECT_NEAR(evaluate_script(script, HandSide::Right, 0.25)[Joint::Wrist].position.x(),
                0.2 * (3 * 0.0625 - 2 * 0.015625), 1e-12);
    EXPECT_NEAR(evaluate_script(script, HandSide::Right, -1.0)[Joint::Wrist].position.x(), 0.0,
                1e-12);
    EXPECT_NEAR(evaluate_script(script, HandSide::Right, 5.0)[Joint::Wrist].position.x(), 0.2,
                1e-12);
}

TEST(Tracking, SmoothScriptNeverOvershootsAPause) {
    Scene s = two_keyframe_scene(Interpolation::Smooth);
    HandScript& script = *s.hands[static_cast<int>(HandSide::Right)];
    Keyframe hold = script.keyframes.back();
    hold.t = 2.0;
    script.keyframes.push_back(hold);
    for (double t = 0.0; t <= 2.0; t += 0.01) {
        EXPECT_LE(evaluate_script(script, HandSide::Right, t)[Joint::Wrist].position.x(),
                  0.2 + 1e-12);
    }
}

TEST(Tracking, NoiseIsSeededAndHasTheRequestedSpread) {
    Scene s = two_keyframe_scene(Interpolation::Linear);
    s.duration_s = 20.0;
    s.tracking.noise_mm = 2.0;
    s.tracking.seed = 3;
    const TrackedHands a(s), b(s);
    s.tracking.seed = 4;
    const TrackedHands c(s);
    double sum_sq = 0.0;
    int n = 0;
    for (int k = 120; k < 1800; ++k) {
        const double t = k / 90.0;
        const HandPose pa = a.ghost(HandSide::Right, t);
        EXPECT_EQ(pa[Joint::IndexTip].position,
                  b.ghost(HandSide::Right, t)[Joint::IndexTip].position);
        EXPECT_NE(pa[Joint::IndexTip].position,
                  c.ghost(HandSide::Right, t)[Joint::IndexTip].position);
        const Vec3 clean =
            evaluate_script(*s.hand(HandSide::Right), HandSide::Right, t)[Joint::IndexTip].position;
        sum_sq += (pa[Joint::IndexTip].position - clean).squaredNorm();
        n += 3;
    }
    EXPECT_NEAR(std::sqrt(sum_sq / n) * 1e3, 2.0, 0.15);  // per-axis standard deviation in mm
}

TEST(Tracking, DropoutsAndMissingHandsAreInactive) {
    Scene s = two_keyframe_scene(Interpolation::Linear);
    s.tracking.dropouts = {{HandSide::Right, 0.5, 0.7}};
    const TrackedHands hands(s);
    EXPECT_TRUE(hands.ghost(HandSide::Right, 0.49).active);
    EXPECT_FALSE(hands.ghost(HandSide::Right, 0.5).active);
    EXPECT_FALSE(hands.ghost(HandSide::Right, 0.69).active);
    EXPECT_TRUE(hands.ghost(HandSide::Right, 0.7).active);
    EXPECT_FALSE(hands.ghost(HandSide::Left, 0.3).active);
}

TEST(Tracking, SamplesAtTheTrackingRateAndInterpolatesBetween) {
    Scene s = two_keyframe_scene(Interpolation::Linear);
    s.tracking.rate_hz = 10.0;
    const TrackedHands hands(s);
    EXPECT_NEAR(hands.ghost(HandSide::Right, 0.1)[Joint::Wrist].position.x(), 0.02, 1e-12);
    EXPECT_NEAR(hands.ghost(HandSide::Right, 0.15)[Joint::Wrist].position.x(), 0.03, 1e-12);
}

}  // namespace
}  // namespace physhand
