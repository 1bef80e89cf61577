#include "scene_variants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "../physics/test_scenes.h"
#include "tracking.h"

namespace physhand {
namespace {

using testing::sample_scene;

TEST(SceneVariants, TheMirroredScenePlaysTheMirrorImageWithTheOtherHand) {
    const Scene scene = sample_scene("lift_hold");
    const Scene m = mirrored(scene);
    ASSERT_FALSE(m.hand(HandSide::Right).has_value());
    ASSERT_TRUE(m.hand(HandSide::Left).has_value());
    for (double t : {0.0, 2.5, 4.1}) {
        const HandPose right = evaluate_script(*scene.hand(HandSide::Right), HandSide::Right, t);
        const HandPose left = evaluate_script(*m.hand(HandSide::Left), HandSide::Left, t);
        for (std::size_t j = 0; j < kJointCount; ++j) {
            const Pose expected = mirror_x(right.joints[j]);
            EXPECT_LT((left.joints[j].position - expected.position).norm(), 1e-9) << j;
            EXPECT_GT(std::abs(left.joints[j].orientation.dot(expected.orientation)), 1 - 1e-9);
        }
    }
    const Collider& cube = *m.find_collider("cube");
    EXPECT_DOUBLE_EQ(cube.pose.position.x(), -scene.find_collider("cube")->pose.position.x());
    // Twice is the scene again.
    const Scene twice = mirrored(m);
    EXPECT_EQ(twice.find_collider("cube")->pose.position,
              scene.find_collider("cube")->pose.position);
}

TEST(SceneVariants, AShiftedSceneMovesEverythingInItAndItsRegions) {
    const Vec3 offset(0.001, 0.002, -0.003);
    for (const char* name : {"lift_hold", "displacement"}) {
        const Scene scene = sample_scene(name);
        const Scene moved = shifted(scene, offset);
        for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
            EXPECT_LT((moved.colliders[i].pose.position - scene.colliders[i].pose.position - offset)
                          .norm(),
                      1e-12)
                << scene.colliders[i].id;
        }
        for (double t : {0.0, 2.5, 4.1}) {
            const HandPose before =
                evaluate_script(*scene.hand(HandSide::Right), HandSide::Right, t);
            const HandPose after =
                evaluate_script(*moved.hand(HandSide::Right), HandSide::Right, t);
            for (std::size_t j = 0; j < kJointCount; ++j) {
                EXPECT_LT((after.joints[j].position - before.joints[j].position - offset).norm(),
                          1e-9);
            }
        }
        for (std::size_t i = 0; i < scene.success.size(); ++i) {
            if (const auto* in = std::get_if<InsidePredicate>(&scene.success[i])) {
                EXPECT_LT((std::get<InsidePredicate>(moved.success[i]).center - in->center - offset)
                              .norm(),
                          1e-12);
            } else if (const auto* held = std::get_if<HeldPredicate>(&scene.success[i])) {
                EXPECT_DOUBLE_EQ(std::get<HeldPredicate>(moved.success[i]).min_y,
                                 held->min_y + offset.y());
            }
        }
    }
}

// Turned about the vertical, every pose turns with the scene, hands included, and a region
// turns by quarter turns, its box's sides swapped; any other turn of a scene with a region
// is refused, naming it.
TEST(SceneVariants, ATurnedSceneTurnsEverythingInItAndItsRegions) {
    const Quat turn(Eigen::AngleAxisd(std::numbers::pi / 6.0, Vec3::UnitY()));
    const Scene scene = sample_scene("lift_hold");
    const Scene t = turned(scene, 30.0);
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
        EXPECT_LT((t.colliders[i].pose.position - turn * scene.colliders[i].pose.position).norm(),
                  1e-12)
            << scene.colliders[i].id;
    }
    for (double time : {0.0, 2.5, 4.1}) {
        const HandPose before =
            evaluate_script(*scene.hand(HandSide::Right), HandSide::Right, time);
        const HandPose after = evaluate_script(*t.hand(HandSide::Right), HandSide::Right, time);
        for (std::size_t j = 0; j < kJointCount; ++j) {
            EXPECT_LT((after.joints[j].position - turn * before.joints[j].position).norm(), 1e-9);
            EXPECT_GT(
                std::abs(after.joints[j].orientation.dot(turn * before.joints[j].orientation)),
                1 - 1e-9);
        }
    }
    const Scene back = turned(t, -30.0);
    EXPECT_LT(
        (back.find_collider("cube")->pose.position - scene.find_collider("cube")->pose.position)
            .norm(),
        1e-12);

    const Scene displacement = sample_scene("displacement");
    const InsidePredicate& hole = std::get<InsidePredicate>(displacement.success[0]);
    const Scene quartered = turned(displacement, 90.0);
    const InsidePredicate& quarter = std::get<InsidePredicate>(quartered.success[0]);
    EXPECT_LT((quarter.center - Vec3(hole.center.z(), hole.center.y(), -hole.center.x())).norm(),
              1e-12);
    EXPECT_EQ(quarter.half_extents,
              Vec3(hole.half_extents.z(), hole.half_extents.y(), hole.half_extents.x()));
    try {
        turned(displacement, 30.0);
        ADD_FAILURE() << "a region turned by 30 degrees";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("inside"), std::string::npos) << e.what();
    }
}

TEST(SceneVariants, AFasterScriptKeepsItsShapeAndTheTimeToSettle) {
    const Scene scene = sample_scene("lift_hold");
    const Scene fast = sped_up(scene, 1.3);
    const auto& keys = scene.hand(HandSide::Right)->keyframes;
    const auto& fast_keys = fast.hand(HandSide::Right)->keyframes;
    ASSERT_EQ(keys.size(), fast_keys.size());
    for (std::size_t k = 0; k < keys.size(); ++k) {
        EXPECT_DOUBLE_EQ(fast_keys[k].t, keys[k].t / 1.3);
        EXPECT_EQ(fast_keys[k].wrist.position, keys[k].wrist.position);
    }
    const auto& held = std::get<HeldPredicate>(fast.success[0]);
    EXPECT_DOUBLE_EQ(held.from_s, std::get<HeldPredicate>(scene.success[0]).from_s / 1.3);
    EXPECT_EQ(fast.duration_s, scene.duration_s);
    EXPECT_DOUBLE_EQ(sped_up(scene, 0.7).duration_s, scene.duration_s / 0.7);
}

TEST(SceneVariants, EveryFamilyWithItsSeeds) {
    const Scene scene = sample_scene("lift_hold");
    const std::vector<SceneVariant> variants = scene_variants(scene, {.seeds = 3});
    std::map<std::string, int> per_family;
    std::set<std::string> names;
    for (const SceneVariant& v : variants) {
        ++per_family[v.family];
        EXPECT_TRUE(names.insert(v.scene.name).second) << v.scene.name;
        if (v.family == "dropout") {
            ASSERT_EQ(v.scene.tracking.dropouts.size(), 1u);
            const Dropout& d = v.scene.tracking.dropouts[0];
            EXPECT_NEAR(d.to_s - d.from_s, 0.3, 1e-12);
            EXPECT_GE(d.from_s, 0.0);
            EXPECT_LE(d.to_s, scene.hand(HandSide::Right)->keyframes.back().t);
        }
    }
    const std::map<std::string, int> expected = {{"mass", 2},    {"friction", 1}, {"speed", 2},
                                                 {"size", 2},    {"tracking", 6}, {"noise", 3},
                                                 {"dropout", 3}, {"mirror", 1}};
    EXPECT_EQ(per_family, expected);
}

// A person aiming at a target throws as hard as the target needs: the wind-up and the rest
// change pace, the throw does not. Without a throw the script is sped up whole.
TEST(SceneVariants, AThrowKeepsItsOwnPaceWhenTheRestChanges) {
    const Scene scene = sample_scene("throw");
    std::string adapted;
    const Scene slow = sped_up_aiming(scene, 0.7, adapted);
    EXPECT_NE(adapted.find("5.10-5.32 s, 5.32-5.38 s"), std::string::npos) << adapted;
    const auto& keys = scene.hand(HandSide::Right)->keyframes;
    const auto& slow_keys = slow.hand(HandSide::Right)->keyframes;
    ASSERT_EQ(keys.size(), slow_keys.size());
    for (std::size_t k = 1; k < keys.size(); ++k) {
        const double leg = keys[k].t - keys[k - 1].t;
        const double speed = (keys[k].wrist.position - keys[k - 1].wrist.position).norm() / leg;
        const double slow_leg = slow_keys[k].t - slow_keys[k - 1].t;
        EXPECT_NEAR(slow_leg, speed > kStrokeSpeed ? leg : leg / 0.7, 1e-9) << k;
        EXPECT_EQ(slow_keys[k].wrist.position, keys[k].wrist.position);
    }
    // The 0.28 s throw is not drawn out.
    EXPECT_NEAR(slow.duration_s, scene.duration_s / 0.7 - 0.28 * (1 / 0.7 - 1), 1e-9);

    const Scene lift = sample_scene("lift_hold");
    const Scene fast = sped_up_aiming(lift, 1.3, adapted);
    EXPECT_TRUE(adapted.empty()) << adapted;
    EXPECT_EQ(fast.hand(HandSide::Right)->keyframes.back().t,
              sped_up(lift, 1.3).hand(HandSide::Right)->keyframes.back().t);
}

// How deep the index fingertip's centre lies in a box along the ray from its centre.
double depth_in_box(const Collider& box, const Vec3& world) {
    const Vec3 p = box.pose.inverse() * world;
    const double fraction = p.cwiseAbs().cwiseQuotient(box.shape.half_extents).maxCoeff();
    return p.norm() * (1.0 / fraction - 1.0);
}

// A larger cube rests where the smaller one did, as dense; the hand reaches for it higher and
// grips it as deep; what the hand never comes near keeps its size.
TEST(SceneVariants, AnotherSizeRestsWhereItWasAndIsGrippedAsDeep) {
    const Scene scene = sample_scene("lift_hold");
    for (double scale : {0.75, 1.25}) {
        std::string adapted;
        const Scene sized = resized(scene, scale, adapted);
        EXPECT_NE(adapted.find("hand raised"), std::string::npos) << adapted;
        const Collider& cube = *scene.find_collider("cube");
        const Collider& big = *sized.find_collider("cube");
        EXPECT_NEAR(big.shape.half_extents.x(), scale * 0.02, 1e-12);
        EXPECT_NEAR(big.pose.position.y() - big.shape.half_extents.y(),
                    cube.pose.position.y() - cube.shape.half_extents.y(), 1e-12);
        EXPECT_NEAR(big.mass, cube.mass * scale * scale * scale, 1e-12);
        EXPECT_EQ(sized.find_collider("table")->shape.half_extents,
                  scene.find_collider("table")->shape.half_extents);

        const auto& keys = scene.hand(HandSide::Right)->keyframes;
        const auto& sized_keys = sized.hand(HandSide::Right)->keyframes;
        const auto raised = [&](std::size_t k) {
            return sized_keys[k].wrist.position.y() - keys[k].wrist.position.y();
        };
        // At the grip (t = 3.2 s) as much as the cube's centre rose; lifted, as much as its top.
        const std::size_t grip = 4;
        ASSERT_DOUBLE_EQ(keys[grip].t, 3.2);
        EXPECT_NEAR(raised(grip), (scale - 1.0) * 0.02, 1e-9);
        EXPECT_NEAR(raised(keys.size() - 1), (scale - 1.0) * 0.04, 1e-9);
        // The index fingertip as deep in the cube as before, within 1 mm.
        const auto tip = [&](const Keyframe& k) {
            return pose_hand(HandSide::Right, k.wrist, k.articulation)[Joint::IndexTip].position;
        };
        EXPECT_NEAR(depth_in_box(big, tip(sized_keys[grip])), depth_in_box(cube, tip(keys[grip])),
                    1e-3)
            << scale;
    }
    // Stacking, the hand brings the last cube onto the grown stack: at 14.9 s the cube it holds
    // is 10.6 cm above the table (8.6 cm above where it gripped it, 2 cm up), a quarter more.
    std::string adapted;
    const Scene stack = sample_scene("stack");
    const Scene stacked = resized(stack, 1.25, adapted);
    const auto& keys = stack.hand(HandSide::Right)->keyframes;
    const auto at =
        std::find_if(keys.begin(), keys.end(), [](const Keyframe& k) { return k.t == 14.9; });
    ASSERT_NE(at, keys.end());
    const std::size_t placing = static_cast<std::size_t>(at - keys.begin());
    EXPECT_NEAR(stacked.hand(HandSide::Right)->keyframes[placing].wrist.position.y() -
                    at->wrist.position.y(),
                0.25 * 0.106, 1e-9);

    const Scene thrown = resized(sample_scene("throw"), 1.25, adapted);
    EXPECT_NEAR(thrown.find_collider("projectile")->shape.half_extents.x(), 0.025, 1e-12);
    EXPECT_EQ(thrown.find_collider("pyramid_20")->shape.half_extents.x(), 0.025);
}

// Only what moves gets heavier; the hands and everything else are as they were.
TEST(SceneVariants, HeavierScalesTheDynamicCollidersOnly) {
    const Scene scene = sample_scene("stack");
    const Scene heavy = heavier(scene, 2.5);
    ASSERT_EQ(heavy.colliders.size(), scene.colliders.size());
    int dynamic = 0;
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
        const Collider& before = scene.colliders[i];
        const Collider& after = heavy.colliders[i];
        const bool moves = before.motion == Motion::Dynamic;
        dynamic += moves ? 1 : 0;
        EXPECT_EQ(after.mass, moves ? before.mass * 2.5 : before.mass) << before.id;
        EXPECT_EQ(after.pose.position, before.pose.position) << before.id;
        EXPECT_EQ(after.friction, before.friction) << before.id;
    }
    EXPECT_GE(dynamic, 3);
    EXPECT_EQ(heavy.hand(HandSide::Right)->keyframes.size(),
              scene.hand(HandSide::Right)->keyframes.size());
    EXPECT_EQ(heavy.name, "stack/mass/x2.5");
}

// The throw's projectile lies off the grasp, the pyramid it is thrown at where it was; the
// stack's three cubes (the base too, which the hand places on) move alike, so the stack's
// target moves with what the hand carries.
TEST(SceneVariants, AnOffCentreGraspMovesWhatTheHandHandlesOnly) {
    const Vec3 offset(0.006, 0.0, -0.003);
    const std::map<std::string, std::set<std::string>> handled = {
        {"throw", {"projectile"}}, {"stack", {"base", "middle", "top"}}, {"lift_hold", {"cube"}}};
    for (const auto& [name, moved] : handled) {
        const Scene scene = sample_scene(name);
        const Scene off = grasped_off_centre(scene, offset);
        ASSERT_EQ(off.colliders.size(), scene.colliders.size());
        for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
            const Collider& before = scene.colliders[i];
            const Vec3 expected =
                before.pose.position + (moved.count(before.id) ? offset : Vec3::Zero());
            EXPECT_EQ(off.colliders[i].pose.position, expected) << name << ' ' << before.id;
        }
        for (double t : {0.0, 2.5, 4.1}) {
            const HandPose a = evaluate_script(*scene.hand(HandSide::Right), HandSide::Right, t);
            const HandPose b = evaluate_script(*off.hand(HandSide::Right), HandSide::Right, t);
            for (std::size_t j = 0; j < kJointCount; ++j)
                EXPECT_EQ(a.joints[j].position, b.joints[j].position) << name << ' ' << j;
        }
    }
}

TEST(SceneVariants, ASqueezeClosesTheFinalGripOnly) {
    const Scene scene = sample_scene("lift_hold");
    const Scene tight = squeezed(scene, 0.8);
    const auto& keys = scene.hand(HandSide::Right)->keyframes;
    const auto& tight_keys = tight.hand(HandSide::Right)->keyframes;
    const auto final_curl = keys.back().articulation.curl;
    for (std::size_t k = 0; k < keys.size(); ++k) {
        const bool final_grip = keys[k].articulation.curl == final_curl;
        for (std::size_t finger = 0; finger < kFingerCount; ++finger) {
            const double before = keys[k].articulation.curl[finger];
            const double after = tight_keys[k].articulation.curl[finger];
            EXPECT_EQ(after, final_grip && finger > 0 ? std::max(before, 0.8) : before);
        }
    }
}

}  // namespace
}  // namespace physhand
