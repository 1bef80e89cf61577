// The sample app, headless, through loader -> layer -> simulated runtime, against the
// physics-only runner on the same scene: the same outcome and the very same final bodies.

#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

struct Output {
    int status = -1;
    std::string text;
};

Output run_command(const std::string& command) {
    Output out;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) return out;
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;) {
        out.text.append(buffer, n);
    }
    out.status = pclose(pipe);
    return out;
}

// The one JSON object the tool printed (core validation may print a line of its own).
nlohmann::json result_of(const Output& output) {
    std::istringstream lines(output.text);
    for (std::string line; std::getline(lines, line);) {
        if (!line.empty() && line.front() == '{') return nlohmann::json::parse(line);
    }
    return nullptr;
}

std::string quoted(const std::string& text) {
    return "'" + text + "'";
}

// Runs both tools on `scene` (the sample headless) with the same `options`; expects both to
// succeed and returns their results, physics first.
// `physics_options`, if given, go to the physics runner alone.
std::pair<nlohmann::json, nlohmann::json> run_both(const std::string& scene,
                                                   const std::string& options,
                                                   const std::string& physics_options = "") {
    const Output physics = run_command(quoted(PHYSHAND_SCENE_EXE) + " " + quoted(scene) + " " +
                                       options + " " + physics_options + " --json");
    EXPECT_EQ(physics.status, 0) << physics.text;
    // The sample plays the scene it is given: no PHYSHAND_SIM_SCENE of ours.
    const Output layer = run_command(quoted(PHYSHAND_SAMPLE_EXE) + " --headless " + quoted(scene) +
                                     " " + options + " --json");
    EXPECT_EQ(layer.status, 0) << layer.text;
    const nlohmann::json expected = result_of(physics);
    const nlohmann::json got = result_of(layer);
    EXPECT_TRUE(expected.is_object()) << physics.text;
    EXPECT_TRUE(got.is_object()) << layer.text;
    return {expected, got};
}

// The same outcome and the very same final bodies: both paths simulate bit-identical
// worlds, and the layer hands poses over as the 32-bit floats of OpenXR.
void expect_same_run(const nlohmann::json& expected, const nlohmann::json& got) {
    ASSERT_TRUE(expected.is_object() && got.is_object());
    EXPECT_EQ(expected.value("path", ""), "physics");
    EXPECT_EQ(got.value("path", ""), "layer");
    EXPECT_EQ(got.at("scene"), expected.at("scene"));
    EXPECT_EQ(got.at("drive"), expected.at("drive"));
    EXPECT_EQ(got.at("substeps"), expected.at("substeps"));
    EXPECT_EQ(got.at("success"), expected.at("success"));
    EXPECT_EQ(got.value("nonfinite_count", -1), 0);

    const nlohmann::json& bodies = expected.at("bodies");
    ASSERT_EQ(got.at("bodies").size(), bodies.size());
    ASSERT_FALSE(bodies.empty());
    for (const auto& [id, body] : bodies.items()) {
        SCOPED_TRACE(id);
        ASSERT_TRUE(got.at("bodies").contains(id));
        const nlohmann::json& pose = got.at("bodies").at(id);
        for (const char* part : {"position", "orientation"}) {
            ASSERT_EQ(pose.at(part).size(), body.at(part).size()) << part;
            for (std::size_t i = 0; i < body.at(part).size(); ++i) {
                EXPECT_EQ(pose.at(part)[i].get<float>(), body.at(part)[i].get<float>())
                    << part << "[" << i << "]";
            }
        }
    }
}

const std::string kLiftHold = std::string(PHYSHAND_SCENES_DIR) + "/lift_hold.json";

using SampleApp = LayerTest;

TEST_F(SampleApp, HeadlessPlayerMatchesThePhysicsRunner) {
    const auto [expected, got] = run_both(kLiftHold, "");
    expect_same_run(expected, got);
    EXPECT_EQ(got.at("drive"), "bones");
}

// A cube the app keeps in its own engine, coupled to the hands through their impulses, ends
// where the physics runner's coupling puts it: pushed into its region (app_push), kicked out
// of a pinch (app_lift, the coupling's limit, XR_PHYSHAND_physical_hands.h).
TEST_F(SampleApp, AppEngineScenesMatchThePhysicsRunner) {
    for (const char* name : {"app_push", "app_lift"}) {
        SCOPED_TRACE(name);
        const auto [expected, got] =
            run_both(std::string(PHYSHAND_SCENES_DIR) + "/" + name + ".json", "");
        expect_same_run(expected, got);
        EXPECT_EQ(got.at("success"), std::string(name) == "app_push");
    }
}

// Each touch begins one line, with its hand part, object and speed (beside the summary line;
// JSON results keep stdout to themselves).
TEST_F(SampleApp, PrintsALineForEachTouch) {
    const Output layer =
        run_command(quoted(PHYSHAND_SAMPLE_EXE) + " --headless " + quoted(kLiftHold));
    ASSERT_EQ(layer.status, 0) << layer.text;
    EXPECT_NE(layer.text.find("touch t=2.38 s right thumb_distal -> cube at 0.04 m/s\n"),
              std::string::npos)
        << layer.text;
}

// The sample sets its drive through the extension, so the drive it reports is the one that
// ran, whatever the layer's config picks.
TEST_F(SampleApp, RunsTheDriveItReportsWhateverTheConfigSays) {
    env_.set("PHYSHAND_CONFIG",
             write_file("config.json", R"({"drive": {"name": "paper", "substeps": 8}})").string());
    const auto [expected, got] = run_both(kLiftHold, "");
    expect_same_run(expected, got);
}

TEST_F(SampleApp, DriveAndSubstepsOptionsMatchThePhysicsRunner) {
    const auto [expected, got] = run_both(kLiftHold, "--drive implicit --substeps 3");
    expect_same_run(expected, got);
    EXPECT_EQ(got.at("drive"), "implicit");
    EXPECT_EQ(got.at("substeps"), 3);
}

// The simulated runtime's display at another rate, with jitter, or dropping frames: the
// sample's scene clock follows the display times, the layer steps the same physics frames as
// the runner shown at those times, and no frame repeats the last one's pose.
TEST_F(SampleApp, EveryDisplayRateMatchesThePhysicsRunner) {
    struct Timing {
        const char* rate_hz;
        const char* jitter_ms;
    };
    for (const Timing timing : {Timing{"72", "0"}, Timing{"144", "0"}, Timing{"120", "2"}}) {
        SCOPED_TRACE(std::string(timing.rate_hz) + " Hz, jitter " + timing.jitter_ms + " ms");
        env_.set("PHYSHAND_SIM_DISPLAY_HZ", timing.rate_hz);
        env_.set("PHYSHAND_SIM_FRAME_JITTER_MS", timing.jitter_ms);
        const auto [expected, got] = run_both(kLiftHold, "",
                                              std::string("--display-hz ") + timing.rate_hz +
                                                  " --frame-jitter-ms " + timing.jitter_ms);
        expect_same_run(expected, got);
        EXPECT_EQ(got.value("display_hz", 0.0), std::stod(timing.rate_hz));
        EXPECT_EQ(got.value("repeated_pose_frames", -1), 0);
        EXPECT_EQ(got.value("frames", 0), expected.value("frames", -1));
    }
}

TEST_F(SampleApp, DroppedFramesAndSlowDisplaysKeepTheScenesDuration) {
    env_.set("PHYSHAND_SIM_DROP_EVERY", "3");
    const auto [every_frame, dropped] = run_both(kLiftHold, "");
    EXPECT_TRUE(dropped.value("success", false));
    EXPECT_EQ(dropped.value("repeated_pose_frames", -1), 0);
    // Two frames of three shown, over the same 9 s.
    EXPECT_NEAR(dropped.value("frames", 0), every_frame.value("frames", 0) * 2 / 3, 2);
    env_.unset("PHYSHAND_SIM_DROP_EVERY");
    env_.set("PHYSHAND_SIM_DISPLAY_HZ", "20");
    const auto [expected, got] = run_both(kLiftHold, "", "--display-hz 20");
    expect_same_run(expected, got);
    EXPECT_EQ(got.value("frames", 0), 180);  // 9 s
}

// A runtime whose headless sessions have no frame loop (Monado's): the sample calls no frame
// functions, paces itself at 90 Hz and tells the time by XR_KHR_convert_timespec_time, so
// the scene plays in real time, to its end.
TEST_F(SampleApp, HeadlessWithoutAFrameLoopPlaysInRealTime) {
    env_.set("PHYSHAND_SIM_HEADLESS_FRAME_LOOP", "0");
    const auto start = std::chrono::steady_clock::now();
    const Output layer =
        run_command(quoted(PHYSHAND_SAMPLE_EXE) + " --headless " + quoted(kLiftHold) + " --json");
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    ASSERT_EQ(layer.status, 0) << layer.text;
    const nlohmann::json got = result_of(layer);
    ASSERT_TRUE(got.is_object()) << layer.text;
    EXPECT_TRUE(got.value("success", false)) << layer.text;
    EXPECT_EQ(got.value("repeated_pose_frames", -1), 0);
    EXPECT_EQ(got.value("nonfinite_count", -1), 0);
    // lift_hold lasts 9 s, from a period before the first frame (its scene time is 1/90 s):
    // a process that starts within 11 ms plays it in 9 s less that period (8.99957 s seen).
    EXPECT_GE(took.count(), 9.0 - 1.0 / 90.0);
    EXPECT_GT(got.value("frames", 0), 700);
}

TEST_F(SampleApp, ThePhysicsRunnerRejectsDisplayTimingOutOfRange) {
    for (const char* option : {"--display-hz 500", "--display-hz 19", "--display-hz x",
                               "--frame-jitter-ms 4", "--frame-jitter-ms -1"}) {
        const Output out = run_command(quoted(PHYSHAND_SCENE_EXE) + " " + quoted(kLiftHold) + " " +
                                       option + " 2>&1");
        EXPECT_EQ(WEXITSTATUS(out.status), 2) << option;
        const bool rate = std::string(option).starts_with("--display-hz");
        EXPECT_NE(out.text.find(rate ? "display" : "jitter"), std::string::npos)
            << option << ": " << out.text;
    }
}

}  // namespace
}  // namespace physhand::layer_test
