// A small fixed subset of the robustness benchmark (physhand-robustness): the variants of
// the sample tasks a real headset and user bring, played with the default drive.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "scene_run.h"
#include "scene_variants.h"
#include "test_scenes.h"

namespace physhand {
namespace {

using testing::sample_scene;

Scene lift_hold_with_dropout(double from_s, double to_s) {
    Scene scene = sample_scene("lift_hold");
    scene.tracking.dropouts.push_back({HandSide::Right, from_s, to_s});
    return scene;
}

// The hand is lost for 300, 500 or 700 ms while lifting (0.2 m/s) and comes back 6-14 cm
// higher: it carries on through the loss and is brought onto the ghost without a jolt, cube
// and all.
TEST(Robustness, ALiftSurvivesDropoutsOfAFewHundredMilliseconds) {
    for (const double lost_s : {0.3, 0.5, 0.7}) {
        SCOPED_TRACE(lost_s);
        const RunResult r = run_scene(lift_hold_with_dropout(4.0, 4.0 + lost_s), RunOptions{});
        EXPECT_TRUE(r.success) << r.predicates[0].detail;
        EXPECT_EQ(r.guards.dropouts, 1u);
        EXPECT_EQ(r.guards.reacquisitions, 1u);
        EXPECT_EQ(r.guards.reseats, 0u);
        EXPECT_EQ(r.metrics.nonfinite_count, 0);
    }
}

// Lost for longer than the grace period, the hand lets go: the cube falls from where it was
// held, and is neither held on to nor flung.
TEST(Robustness, ALongDropoutLetsGoGently) {
    const RunResult r = run_scene(lift_hold_with_dropout(4.8, 6.0), RunOptions{});
    EXPECT_FALSE(r.success);
    EXPECT_EQ(r.guards.dropouts, 1u);
    EXPECT_EQ(r.guards.reacquisitions, 0u);
    // Falling 25 cm onto the table: 2.2 m/s.
    EXPECT_LT(r.metrics.max_body_speed, 2.6);
}

// A free hand lost as it nears something comes back eased onto its ghost rather than swept
// there at up to 4 m/s: lost while reaching for the cube (0.85-1.15 s), it knocked the cube at
// 1.3 m/s; lost while flicking the ball (1.52-1.82 s), whose flick it misses, it came back 13
// cm on, hit the ball on its way there and flung it 8 m. Eased back, it pushes the ball on
// along the table at under 1 m/s (the flick's ghost sweeps at 0.8 m/s; the table runs on, so
// that the ball's speed is the push's, not its fall's). It is never re-seated past the ball:
// it was, and never touched it, when the easing left it 15 cm from its ghost, and when it came
// back 15.1 cm on after 233 ms lost in a flick 1.4 times as fast.
TEST(Robustness, AHandLostNearSomethingIsNotSweptIntoItOnReturn) {
    const RunResult reach = run_scene(lift_hold_with_dropout(0.85, 1.15), RunOptions{});
    EXPECT_TRUE(reach.success) << reach.predicates[0].detail;
    EXPECT_EQ(reach.guards.reacquisitions, 1u);
    EXPECT_LT(reach.metrics.max_body_speed, 0.6);

    for (double speed : {1.0, 1.4}) {
        Scene flick = sped_up(sample_scene("sphere"), speed);
        flick.tracking.dropouts.push_back({HandSide::Right, 1.52 / speed, 1.82 / speed});
        for (Collider& c : flick.colliders) {
            if (c.id != "table") continue;
            c.shape.half_extents.z() = 1.0;
            c.pose.position.z() = -1.1;
        }
        const RunResult r = run_scene(flick, RunOptions{});
        EXPECT_EQ(r.guards.reacquisitions, 1u) << speed;
        EXPECT_EQ(r.guards.reseats, 0u) << speed;
        EXPECT_LT(r.metrics.max_body_speed, 1.0) << speed;
        const auto ball = std::find_if(r.bodies.begin(), r.bodies.end(),
                                       [](const auto& b) { return b.first == "ball"; });
        ASSERT_NE(ball, r.bodies.end());
        // It starts at z -0.3: pushed on along the table.
        EXPECT_LT(ball->second.position.z(), -0.5) << speed;
    }
}

// Every family: other masses, a slipperier cube, the motion faster and slower, a smaller and
// a larger cube (gripped as a person would grip it), 30 and 60 Hz tracking with 2 mm of
// noise, 3 mm of noise at 90 Hz (before the NoiseFilter the cube was never lifted), dropouts
// anywhere in the motion, and the left hand.
// A runtime's reference space may face any way: turned about the vertical through the
// origin, each task succeeds as it does facing the way it was written. Turned in 5-degree
// steps over a whole turn, at two shifts, lift_hold, the throw and the stack succeeded in
// all 144 plays each; by quarter turns at 16 shifts, the sphere task in all 64 and
// displacement in 59 (16 of 16 unturned: its cube, placed, is as easily drawn back out of
// the hole under any small change).
TEST(Robustness, TheTasksSucceedWhicheverWayTheyFace) {
    for (const char* name : {"lift_hold", "throw", "stack"}) {
        for (double degrees : {30.0, 135.0, 250.0}) {
            const RunResult r = run_scene(turned(sample_scene(name), degrees), RunOptions{});
            EXPECT_TRUE(r.success) << name << " turned " << degrees << " degrees";
        }
    }
    for (double degrees : {90.0, 180.0, 270.0}) {
        const RunResult r = run_scene(turned(sample_scene("sphere"), degrees), RunOptions{});
        EXPECT_TRUE(r.success) << "sphere turned " << degrees << " degrees";
    }
}

TEST(Robustness, LiftHoldVariantsHold) {
    for (const SceneVariant& v : scene_variants(sample_scene("lift_hold"), {.seeds = 2})) {
        const RunResult r = run_scene(v.scene, RunOptions{});
        EXPECT_TRUE(r.success) << v.scene.name << ": " << r.predicates[0].detail;
        EXPECT_EQ(r.metrics.nonfinite_count, 0) << v.scene.name;
    }
}

// Stacking through tracking noise: 2 mm at 30 and 60 Hz, 3 mm at 90 Hz. Each joint's own
// noise, which changes its bone's length from sample to sample, loosened the grips: before
// the skeleton fit (physics/skeleton_fit) all three 3 mm seeds dropped a cube.
TEST(Robustness, StacksThroughTrackingNoise) {
    for (const SceneVariant& v : scene_variants(sample_scene("stack"), {.seeds = 3})) {
        if (v.family != "noise" && v.family != "tracking") continue;
        const RunResult r = run_scene(v.scene, RunOptions{});
        EXPECT_TRUE(r.success) << v.scene.name << ": " << r.predicates[0].detail;
    }
}

TEST(Robustness, ThePaperTasksSucceedWithTheLeftHand) {
    for (const char* name : {"throw", "sphere", "displacement", "stack"}) {
        const RunResult r = run_scene(mirrored(sample_scene(name)), RunOptions{});
        EXPECT_TRUE(r.success) << name;
    }
}

// A user squeezing deep into a held cube (lift_hold's fingers curled 0.5-1.0, 1-4 cm into
// it): parts are moved out of it (hand_depenetration.h). Before, contact points went 4.4-7.0
// mm in, the hand as shown up to 12.5 mm (read by Bullet's closest-point query, which reads a
// capsule across a cube's edge short); now at most 1.5 mm, 6.7 mm shown. With `paper`'s joint
// spheres at curl 0.8, 18.5 mm before friction anchors gave way to deeper points.
TEST(Robustness, ASqueezedGripHoldsWithoutSinkingIn) {
    const Scene lift_hold = sample_scene("lift_hold");
    for (const double curl : {0.5, 0.6, 0.7, 0.8, 0.9, 1.0}) {
        const RunResult r = run_scene(squeezed(lift_hold, curl), RunOptions{});
        EXPECT_LE(r.metrics.max_penetration_mm, 2.0) << "curl " << curl;
        EXPECT_LT(r.metrics.max_shown_depth_mm, 8.0) << "curl " << curl;
    }
    RunOptions paper;
    paper.drive = "paper";
    EXPECT_LT(run_scene(squeezed(lift_hold, 0.8), paper).metrics.max_shown_depth_mm, 2.0);
}

// The same squeezes played where the robustness benchmark plays them, moved by up to 1.3 mm:
// the cube stays held in most. Where the ghost's fingers pass right through it (curls 0.7-1.0),
// the closing fingers push it against the thumb until it turns out of the grip; unjoined bones,
// parting by 45 mm there, held every one (docs/design.md).
TEST(Robustness, ASqueezedGripHoldsWhereverItIsPlayed) {
    const Scene lift_hold = sample_scene("lift_hold");
    int held = 0;
    for (int shift = 1; shift < 4; ++shift) {
        const Scene moved = shifted(lift_hold, Vec3(0.00037, 0.0, -0.00023) * shift);
        for (const double curl : {0.5, 0.6, 0.7, 0.8, 0.9, 1.0}) {
            const RunResult r = run_scene(squeezed(moved, curl), RunOptions{});
            held += r.success ? 1 : 0;
            EXPECT_LT(r.metrics.max_penetration_mm, 2.5) << "shift " << shift << " curl " << curl;
            EXPECT_LT(r.metrics.max_joint_gap_mm, 1.0) << "shift " << shift << " curl " << curl;
        }
    }
    EXPECT_GE(held, 10);  // of 18; 12 measured
}

// Thrown under 2 mm of tracking noise, where the fingers ahead of the cube let go over
// several frames: the thumb behind it lets go with them, and the cube flies straight enough to
// knock the pyramid down. Each of these failed at every one of 16 shifts when the thumb went
// on pushing (the cube left at 0.35 m/s sideways and clipped the pyramid's edge). Joined, one
// of them (30 Hz, seed 5) misses again: the cube, turned 15 degrees in the grip as it was
// picked up, leaves at 0.66 m/s sideways.
TEST(Robustness, AThrowThroughTrackingNoiseFliesStraight) {
    const std::vector<std::string> wanted = {"30hz_2mm_seed5", "30hz_2mm_seed6", "60hz_2mm_seed2",
                                             "60hz_2mm_seed5"};
    int played = 0, straight = 0;
    for (const SceneVariant& v : scene_variants(sample_scene("throw"), {.seeds = 6})) {
        if (v.family != "tracking" ||
            std::find(wanted.begin(), wanted.end(), v.name) == wanted.end()) {
            continue;
        }
        ++played;
        straight += run_scene(v.scene, RunOptions{}).success ? 1 : 0;
    }
    EXPECT_EQ(played, 4);
    EXPECT_GE(straight, 3);
}

// The displacement task's cube, put in its hole under tracking noise, stays there as the hand
// is drawn back: a fingertip left beyond the cube (the grip's far side) no longer drives into
// it at the hand's speed, which pulled it out onto the table at every one of these plays.
TEST(Robustness, ACubePutInItsHoleStaysThereAsTheHandDrawsBack) {
    const std::vector<std::pair<std::string, std::vector<int>>> wanted = {
        {"3mm_seed1", {3, 8, 9}}, {"30hz_2mm_seed7", {0, 1}}};
    int played = 0;
    for (const SceneVariant& v : scene_variants(sample_scene("displacement"), {.seeds = 7})) {
        const auto it = std::find_if(wanted.begin(), wanted.end(),
                                     [&](const auto& w) { return w.first == v.name; });
        if (it == wanted.end()) continue;
        for (int shift : it->second) {
            ++played;
            // As the robustness benchmark moves its plays (physhand-robustness --shifts).
            const Vec3 offset = Vec3(0.00037, 0.0, -0.00023) * shift;
            const RunResult r = run_scene(shifted(v.scene, offset), RunOptions{});
            EXPECT_TRUE(r.success)
                << v.name << " shift " << shift << ": " << r.predicates[0].detail;
        }
    }
    EXPECT_EQ(played, 5);
}

// The throw 1.5 and 1.7 times as fast (wrist up to 4.8 m/s, fingertips over 6 m/s as they
// open): no finger passes into the projectile as it lets go, and the projectile leaves no
// faster than the hand part that let it go last (+10 %), nor flies on faster than the palm
// that threw it (+10 %, and what 50 ms of falling adds). At one substep the opening fingers
// passed 38 mm into it and flung it off at 1.3 times the palm's speed.
TEST(Robustness, AFastThrowNeitherTunnelsNorFlings) {
    for (double speed : {1.5, 1.7}) {
        const RunResult r = run_scene(sped_up(sample_scene("throw"), speed), RunOptions{});
        EXPECT_LT(r.metrics.max_penetration_mm, 5.0) << speed;
        ASSERT_TRUE(r.metrics.throw_release) << speed;
        const Release& release = *r.metrics.throw_release;
        ASSERT_TRUE(release.ratio()) << speed;
        EXPECT_LE(*release.ratio(), 1.1) << speed;
        // Measured 50 ms after the last contact, the body has fallen for that long.
        const double fall = 9.81 * 0.050;
        EXPECT_LE(release.body_speed, 1.1 * release.hand_speed + fall) << speed;
    }
}

}  // namespace
}  // namespace physhand
