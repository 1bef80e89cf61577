#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>

#include "frame_clock.h"
#include "physical_hand.h"
#include "scene_run.h"
#include "scene_variants.h"
#include "simulation.h"
#include "test_scenes.h"
#include "tracking.h"

namespace physhand {
namespace {

class SampleScene : public ::testing::TestWithParam<std::string> {};

// `scene` played frame by frame by the default hand following the scene's script.
struct ScenePlay {
    explicit ScenePlay(const Scene& scene)
        : sim(settings_for(RunOptions{}), scene.gravity), tracked(scene) {
        for (const Collider& c : scene.colliders) sim.add_collider(c);
    }
    void step(int frame) {
        sim.step_sampling(frame_time_s(frame), [&](double t) {
            return std::array<HandPose, 2>{tracked.ghost(HandSide::Left, t),
                                           tracked.ghost(HandSide::Right, t)};
        });
    }
    Simulation sim;
    TrackedHands tracked;
};

TEST_P(SampleScene, SucceedsWithTheDefaultDrive) {
    const RunResult r = run_scene(testing::sample_scene(GetParam()), RunOptions{});
    for (const PredicateResult& p : r.predicates) {
        EXPECT_TRUE(p.passed) << p.type << " " << p.subject << ": " << p.detail;
    }
    EXPECT_TRUE(r.success);
    EXPECT_EQ(r.metrics.nonfinite_count, 0);
    EXPECT_LT(r.metrics.max_body_speed, SimulationSettings{}.max_body_speed);
}

INSTANTIATE_TEST_SUITE_P(Paper, SampleScene,
                         ::testing::Values("throw", "sphere", "displacement", "stack"));
INSTANTIATE_TEST_SUITE_P(Measurement, SampleScene,
                         ::testing::Values("free_motion", "press_table", "lift_hold", "jitter"));

INSTANTIATE_TEST_SUITE_P(AppEngine, SampleScene, ::testing::Values("app_push"));

// The coupling recipe (an app's own engine, the hands' impulses) pushes the cube as the
// hands' simulation pushes one of its own: into the region, within 1.5 cm of it (12.9 mm;
// the unjoined hand's, under 1 cm).
TEST(SampleScenes, AnAppsOwnCubeIsPushedAsTheLayersOwnWouldBe) {
    const Scene coupled = testing::sample_scene("app_push");
    Scene own = coupled;
    own.app_engine.clear();
    const RunResult a = run_scene(coupled, RunOptions{});
    const RunResult b = run_scene(own, RunOptions{});
    ASSERT_TRUE(a.success && b.success);
    const auto end = [](const RunResult& r) {
        return std::find_if(r.bodies.begin(), r.bodies.end(),
                            [](const auto& body) { return body.first == "cube"; })
            ->second.position;
    };
    EXPECT_LT((end(a) - end(b)).norm(), 0.015) << end(a).transpose() << " / " << end(b).transpose();
}

// Pushed near its top, a 16 cm post the app keeps to itself falls over as the layer's own
// does, and lands within 2 cm of it.
TEST(SampleScenes, AnAppsOwnPostTipsOverAsTheLayersOwnWould) {
    Scene coupled = testing::sample_scene("app_push");
    Collider& post = coupled.colliders.back();
    ASSERT_EQ(post.id, "cube");
    post.shape.half_extents = Vec3(0.02, 0.08, 0.02);
    post.pose.position.y() = 0.83;
    post.friction = 0.8;
    for (Keyframe& key : coupled.hands[static_cast<int>(HandSide::Right)]->keyframes) {
        key.wrist.position.y() = 0.88;  // the hand pushes the post's upper half
    }
    coupled.success.clear();
    Scene own = coupled;
    own.app_engine.clear();
    const RunResult a = run_scene(coupled, RunOptions{});
    const RunResult b = run_scene(own, RunOptions{});
    for (const RunResult* r : {&a, &b}) {
        const Pose& end = r->bodies.front().second;
        EXPECT_LT(std::abs((end.orientation * Vec3::UnitY()).y()), 0.5) << "still standing";
    }
    EXPECT_LT((a.bodies.front().second.position - b.bodies.front().second.position).norm(), 0.02);
}

// Every scene played with each bone kept on the one before it and on the palm (issue 19).
// Unjoined, the bones parted by up to 53 mm (displacement: fingers stopped by the wall while
// the hand goes on; press_table: the thumb's base 2 cm above where the palm, flat on the
// table, puts it). Under tracking noise (jitter) the hand is built from a noisy first sample:
// its joints move at once to where the next ghosts have them while it touches nothing (at
// 0.6 m/s: 2.98 mm apart in the third frame). The figure is measured, not a constant.
TEST(SampleScenes, TheHandStaysInOnePiece) {
    for (const char* name : {"throw", "sphere", "displacement", "stack", "free_motion",
                             "press_table", "lift_hold", "jitter", "app_push"}) {
        const RunResult r = run_scene(testing::sample_scene(name), RunOptions{});
        EXPECT_TRUE(r.success) << name;
        EXPECT_EQ(r.metrics.nonfinite_count, 0) << name;
        EXPECT_LT(r.metrics.max_joint_gap_mm, 1.0) << name;
        if (std::string(name) == "free_motion") {
            EXPECT_GT(r.metrics.max_joint_gap_mm, 0.0);
        }
    }
}

// Squeezed ever tighter (lift_hold's final curls 0.3 to 1.0), the hand stays in one piece and
// holds the cube in most squeezes: a bone the cube stops is held there while the
// bones before it bend, and takes no velocity from that closing. Moved by its share instead,
// each finger passed its whole curl on into the cube, which slipped out past the thumb from a
// curl of 0.5 (2 of 8 held), contact points 7 mm deep; taking the closing's move as velocity,
// 4 of 8 held. A cube spinning out of the grip swept an edge 3.2 mm into the thumb (curl 0.7)
// while a joined bone had one move to leave it.
TEST(SampleScenes, AHandSqueezingTightHoldsInOnePiece) {
    int held = 0;
    for (int step = 0; step < 8; ++step) {
        const double curl = 0.3 + 0.1 * step;
        const RunResult r =
            run_scene(squeezed(testing::sample_scene("lift_hold"), curl), RunOptions{});
        held += r.success ? 1 : 0;
        EXPECT_LT(r.metrics.max_joint_gap_mm, 0.35) << curl;
        EXPECT_LT(r.metrics.max_penetration_mm, 2.0) << curl;
    }
    EXPECT_GE(held, 5);
}

// The hand's bones bend within a human hand's ranges: in displacement, where the wall
// catches the fingers that push the cube in, joints without ranges folded a fingertip fully
// back (180 degrees), bent a middle joint 47 degrees back and twisted one by 103.
TEST(SampleScenes, AHandBendsAsAHandDoes) {
    const Scene scene = testing::sample_scene("displacement");
    ScenePlay play(scene);
    double furthest = 0.0;  // past a range, radians
    for (int f = 1; frame_time_s(f) < scene.duration_s; ++f) {
        play.step(f);
        const HandPose& hand = play.sim.hand(HandSide::Right).joints;
        for (Joint first : kFingerFirstBone) {
            for (std::size_t bone = 0; bone < 3; ++bone) {
                const Joint anchor = static_cast<Joint>(index_of(first) + bone);
                const std::optional<JointRange> range = joint_range(anchor);
                if (!range) continue;
                const Joint before =
                    bone == 0 ? Joint::Palm : static_cast<Joint>(index_of(anchor) - 1);
                const Quat turn = hand[before].orientation.inverse() * hand[anchor].orientation;
                if (const std::optional<Quat> within = range->bring_within(turn))
                    furthest = std::max(furthest, within->angularDistance(turn));
            }
        }
    }
    EXPECT_LT(furthest, 2.0 * std::numbers::pi / 180.0);
}

// Fingers curled round a 2 cm bar, their ghosts then pulled 10 cm back through it and held
// still: once the hand is still, its joints report no motion. Each bone reported its Bullet
// velocity, and the joints, still, up to 2.5 m/s: every substep the joint closing moved the
// caught bones into the bar, adding the move as velocity, and a contact pushed them back.
TEST(SampleScenes, FingersCaughtAtABarReportTheMotionTheyMake) {
    const Scene scene = parse_scene(R"({
      "format": "physhand-scene/1", "name": "caught_at_a_bar", "duration_s": 5.0,
      "colliders": [{"id": "bar", "shape": "box", "half_extents": [0.2, 0.01, 0.01],
                     "motion": "static", "pose": {"position": [0.1, 0.95, -0.45]}}],
      "hands": {"right": {"keyframes": [
        {"t": 0.0, "wrist": {"position": [0.1222, 1.0, -0.25]}, "curl": [0, 0, 0, 0, 0]},
        {"t": 1.0, "wrist": {"position": [0.1222, 0.985, -0.36]}},
        {"t": 2.0, "wrist": {"position": [0.1222, 0.985, -0.36]},
         "curl": [0.1, 0.8, 0.8, 0.8, 0.8]},
        {"t": 3.5, "wrist": {"position": [0.1222, 0.985, -0.26]}},
        {"t": 5.0, "wrist": {"position": [0.1222, 0.985, -0.26]}}]}}})",
                                    ".");
    ScenePlay play(scene);
    HandPose before;
    double widest_gap = 0.0, most_moved = 0.0, fastest = 0.0;
    for (int f = 1; frame_time_s(f) < scene.duration_s; ++f) {
        play.step(f);
        const PhysicalHandState& hand = play.sim.hand(HandSide::Right);
        widest_gap = std::max(widest_gap, hand.max_joint_gap);
        if (frame_time_s(f) > 4.0) {
            for (std::size_t j = 0; j < kJointCount; ++j) {
                most_moved =
                    std::max(most_moved,
                             (hand.joints.joints[j].position - before.joints[j].position).norm());
                fastest = std::max(fastest, hand.linear_velocity[j].norm());
            }
        }
        before = hand.joints;
    }
    EXPECT_LT(widest_gap, 0.00035);
    EXPECT_LT(most_moved, 1e-4);
    EXPECT_LT(fastest, 0.01);
}

// app_lift is played by SampleApp.AppEngineScenesMatchThePhysicsRunner.
TEST(SampleScenes, EverySceneFileIsCoveredAbove) {
    int count = 0;
    for (const auto& e : std::filesystem::directory_iterator(PHYSHAND_SCENES_DIR)) {
        count += e.path().extension() == ".json";
    }
    EXPECT_EQ(count, 10);
}

// The default runs one substep per frame: a hand pressed into a table or gripping a cube
// must neither sink in by more than the benchmark resolves (5 mm before hands found contacts
// 2 cm ahead; 0.26 mm where a finger capsule landed along the table, before each capsule end
// had a contact of its own; 0.025 mm where the palm box landed, before its corners had;
// 0.02 mm with fingers pulled into the table, before warm starting took half the impulses;
// joined, 0.075 mm) nor chatter, which shows as motion of the still hand (rest_jitter_mm).
// Its tracking error counts the palm, which the ball of the thumb holds 3 mm off the table
// (touching nothing, 5 cm above its ghost): 19 mm RMS.
TEST(SampleScenes, DefaultHandPressesAndGripsWithoutSinkingOrChatter) {
    ASSERT_EQ(default_drive().substeps, 1);
    const RunResult press = run_scene(testing::sample_scene("press_table"), RunOptions{});
    EXPECT_LT(press.metrics.max_penetration_mm, 0.1);
    EXPECT_LT(press.metrics.rest_jitter_mm, 0.1);
    const RunResult lift = run_scene(testing::sample_scene("lift_hold"), RunOptions{});
    EXPECT_LT(lift.metrics.max_penetration_mm, 1.0);
    ASSERT_TRUE(lift.predicates.at(0).slip_mm);
    EXPECT_LT(*lift.predicates[0].slip_mm, 0.01);
}

// The default drive follows a smoothed ghost: a still hand under tracking noise moves less
// than its ghost, where the unsmoothed drive passes the noise on whole.
TEST(SampleScenes, StillHandIsSteadierThanItsGhost) {
    const Scene jitter = testing::sample_scene("jitter");
    const RunResult smoothed = run_scene(jitter, RunOptions{});
    EXPECT_LT(smoothed.metrics.jitter_mm, 0.5 * smoothed.metrics.ghost_jitter_mm);
    SimulationSettings raw;
    raw.drive.smoothing = GhostSmoothing{};
    EXPECT_GT(run_scene(jitter, raw).metrics.jitter_mm, 0.9 * smoothed.metrics.ghost_jitter_mm);
}

// press_table with the hand pitched so that the fingers press first.
Scene pitched_press_table() {
    Scene scene = testing::sample_scene("press_table");
    const Quat pitch(Eigen::AngleAxisd(0.15, Vec3::UnitX()));
    for (Keyframe& k : scene.hands[static_cast<int>(HandSide::Right)]->keyframes)
        k.wrist.orientation = pitch * k.wrist.orientation;
    return scene;
}

// A still ghost pressed into a table: the returned joints stay still (rest_jitter_mm), with the
// palm flat on it and with the hand pitched so the fingers press first (bones held a hair above
// the table by their joints shook 0.15-0.18 mm while they counted as resting only when touching
// it), and sink no further into it than the contacts resolve.
TEST(SampleScenes, AHandRestingOnATableIsQuiet) {
    ASSERT_EQ(default_drive().substeps, 1);
    for (const Scene& scene : {testing::sample_scene("press_table"), pitched_press_table()}) {
        SCOPED_TRACE(scene.name);
        const RunResult r = run_scene(scene, RunOptions{});
        EXPECT_LT(r.metrics.rest_jitter_mm, 0.1);
        EXPECT_LT(r.metrics.max_penetration_mm, 1.0);  // pitched: 0.52
        // The thumb's first bone, as shown, 5.8 mm into the table (pitched: 9.2): the palm box
        // cannot lie as low as the ball of the thumb, and the joints' closing, after the
        // contacts, pulls it down after the palm (docs/design.md).
        EXPECT_LT(r.metrics.max_shown_depth_mm, 10.0);
    }
}

// press_table with its table made of the box's 12 triangles, the top split along one diagonal
// or the other, as a modelling tool might export it.
Scene press_table_of_triangles(bool other_diagonal) {
    Scene scene = testing::sample_scene("press_table");
    for (Collider& c : scene.colliders) {
        if (c.id != "table") continue;
        const Vec3 h = c.shape.half_extents;
        c.shape.kind = ShapeKind::Mesh;
        for (int i = 0; i < 8; ++i)
            c.shape.vertices.push_back(
                Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
        // Two triangles a face, the faces in the order -z, +z, -y, +y (the top), -x, +x.
        const std::array<int, 3> top_a =
            other_diagonal ? std::array<int, 3>{2, 6, 3} : std::array<int, 3>{2, 6, 7};
        const std::array<int, 3> top_b =
            other_diagonal ? std::array<int, 3>{3, 6, 7} : std::array<int, 3>{2, 7, 3};
        c.shape.indices = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                           top_a,     top_b,     {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    }
    return scene;
}

// On a table of triangles a pressed hand rests as on the box. Bullet's own pairs kept one
// point of each part against the mesh, the last triangle's, along the normal GJK gave it
// there: the hand sank 11-12 mm into the table as shown, a bone's end came 9-10 cm from its
// neighbour's, and the joints shook 0.78 mm RMS at rest on one of the two splits.
TEST(SampleScenes, AHandPressedOnATableOfTrianglesRestsOnItAsOnABox) {
    for (const bool other_diagonal : {false, true}) {
        SCOPED_TRACE(other_diagonal ? "the other diagonal" : "one diagonal");
        const RunResult r = run_scene(press_table_of_triangles(other_diagonal), RunOptions{});
        EXPECT_TRUE(r.success);
        EXPECT_LT(r.metrics.rest_jitter_mm, 0.1);
        EXPECT_LT(r.metrics.max_penetration_mm, 0.5);
        EXPECT_LT(r.metrics.max_joint_gap_mm, 1.0);
        EXPECT_LT(r.metrics.max_shown_depth_mm, 10.0);  // the ball of the thumb: 9.1, box 5.8
    }
}

// Pressed 5 cm into a table, every joint stays over its ghost: a thumb bone driven that deep
// tipped on its end and walked up to 4.5 cm across the table, off its hand.
TEST(SampleScenes, AHandPressedIntoATableStaysOverItsGhost) {
    for (const Scene& scene : {testing::sample_scene("press_table"), pitched_press_table()}) {
        Simulation sim(settings_for(RunOptions{}), scene.gravity);
        for (const Collider& c : scene.colliders) sim.add_collider(c);
        const TrackedHands tracked(scene);
        const auto ghosts_at = [&](double t) {
            return std::array<HandPose, 2>{tracked.ghost(HandSide::Left, t),
                                           tracked.ghost(HandSide::Right, t)};
        };
        double furthest = 0.0;
        for (int f = 1; frame_time_s(f) < scene.duration_s; ++f) {
            sim.step_sampling(frame_time_s(f), ghosts_at);
            const HandPose ghost = ghosts_at(frame_time_s(f))[static_cast<int>(HandSide::Right)];
            const HandPose& hand = sim.hand(HandSide::Right).joints;
            for (std::size_t j = 0; j < kJointCount; ++j) {
                Vec3 along_table = hand.joints[j].position - ghost.joints[j].position;
                along_table.y() = 0.0;
                furthest = std::max(furthest, along_table.norm());
            }
        }
        EXPECT_LT(furthest, 0.005);
    }
}

TEST(SampleScenes, HeldObjectBarelySlipsAndGatedHandsAreExact) {
    const RunResult lift = run_scene(testing::sample_scene("lift_hold"), RunOptions{});
    ASSERT_TRUE(lift.predicates.at(0).slip_mm);
    EXPECT_LT(*lift.predicates[0].slip_mm, 5.0);
    const RunResult free = run_scene(testing::sample_scene("free_motion"), RunOptions{});
    EXPECT_LT(free.metrics.tracking_error_rms_mm, 1.0);
    EXPECT_EQ(free.metrics.max_penetration_mm, 0.0);
}

}  // namespace
}  // namespace physhand
