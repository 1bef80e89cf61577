// The sample app, headless, through loader -> layer -> simulated runtime, against the
// physics-only runner on the same scene: the same outcome and the very same final bodies.

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
std::pair<nlohmann::json, nlohmann::json> run_both(const std::string& scene,
                                                   const std::string& options) {
    const Output physics =
        run_command(quoted(PHYSHAND_SCENE_EXE) + " " + quoted(scene) + " " + options + " --json");
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

}  // namespace
}  // namespace physhand::layer_test
