#include "scene_variants.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

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
    const std::map<std::string, int> expected = {{"mass", 2},     {"friction", 1}, {"speed", 2},
                                                 {"tracking", 6}, {"noise", 3},    {"dropout", 3},
                                                 {"mirror", 1}};
    EXPECT_EQ(per_family, expected);
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
