#include <gtest/gtest.h>

#include "run_report.h"
#include "scene_run.h"
#include "test_scenes.h"

namespace physhand {
namespace {

nlohmann::json without_timing(nlohmann::json j) {
    j.erase("step_us_median");
    j.erase("step_us_p99");
    return j;
}

TEST(Determinism, SameSceneAndOptionsGiveBitIdenticalResults) {
    Scene scene = testing::sample_scene("stack");
    scene.tracking.noise_mm = 1.0;
    for (const char* drive : {"bones", "paper"}) {
        RunOptions options;
        options.drive = drive;
        const auto a = without_timing(to_json(run_scene(scene, options)));
        const auto b = without_timing(to_json(run_scene(scene, options)));
        EXPECT_EQ(a.dump(), b.dump()) << drive;
    }
}

TEST(Determinism, TheSeedChangesTheNoiseAndOnlyThat) {
    Scene scene = testing::sample_scene("jitter");
    RunOptions a, b;
    a.seed = 1;
    b.seed = 2;
    const RunResult ra = run_scene(scene, a);
    const RunResult rb = run_scene(scene, b);
    EXPECT_NE(ra.metrics.jitter_mm, rb.metrics.jitter_mm);
    EXPECT_NEAR(ra.metrics.ghost_jitter_mm, rb.metrics.ghost_jitter_mm, 0.5);
}

}  // namespace
}  // namespace physhand
