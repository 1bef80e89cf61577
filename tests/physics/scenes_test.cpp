#include <gtest/gtest.h>

#include <filesystem>

#include "scene_run.h"
#include "test_scenes.h"

namespace physhand {
namespace {

class SampleScene : public ::testing::TestWithParam<std::string> {};

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

TEST(SampleScenes, EverySceneFileIsCoveredAbove) {
    int count = 0;
    for (const auto& e : std::filesystem::directory_iterator(PHYSHAND_SCENES_DIR)) {
        count += e.path().extension() == ".json";
    }
    EXPECT_EQ(count, 8);
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
