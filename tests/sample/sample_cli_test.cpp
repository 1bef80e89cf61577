// physhand-sample's command line: a bad option or scene file ends it with exit code 2 and a
// message naming what is wrong, before any OpenXR call.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "command_output.h"

namespace {

using physhand::test::CommandOutput;

CommandOutput run_sample(const std::string& arguments) {
    return physhand::test::run_command(std::string("'") + PHYSHAND_SAMPLE + "' " + arguments +
                                       " 2>&1");
}

const std::string kScene = std::string("'") + PHYSHAND_SCENES_DIR + "/sphere.json'";

// Exit code 2, and the sample's message says `expected`.
void expect_rejected(const std::string& arguments, const std::string& expected) {
    const CommandOutput run = run_sample(arguments);
    EXPECT_EQ(run.status, 2) << arguments << "\n" << run.out;
    const std::size_t message = run.out.find("physhand-sample: ");
    EXPECT_NE(message, std::string::npos) << arguments << "\n" << run.out;
    EXPECT_NE(run.out.find(expected, message), std::string::npos) << arguments << "\n" << run.out;
}

TEST(SampleCommandLine, RejectsABadOption) {
    expect_rejected("--frobnicate " + kScene, "unknown option --frobnicate");
    expect_rejected("", "no scene file");
    expect_rejected("--headless --live " + kScene, "--live needs the rendered mode");
    expect_rejected("--view-size 8 " + kScene, "--view-size: \"8\" is not a width");
    expect_rejected("--view-size 320.5 " + kScene, "--view-size: \"320.5\" is not a width");
    expect_rejected("--drive nosuch " + kScene, "--drive: unknown drive \"nosuch\"");
    expect_rejected("--substeps 0 " + kScene, "--substeps: \"0\" is not a whole number");
    expect_rejected("--substeps 65 " + kScene, "--substeps: \"65\" is not a whole number");
    expect_rejected(kScene + " --substeps", "--substeps: \"\" is not a whole number");
}

TEST(SampleCommandLine, RejectsAHoverDistanceThatIsNoDistance) {
    for (const char* bad : {"-1", "-0.5", "nan", "inf", "-inf", "101", "3cm", ""}) {
        SCOPED_TRACE(bad);
        expect_rejected(kScene + " --hover-cm '" + bad + "'",
                        "--hover-cm: \"" + std::string(bad) + "\" is not a distance in cm");
    }
}

class MalformedScene : public testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("physhand_sample_cli_" + std::to_string(getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& text) {
        const std::filesystem::path path = dir_ / name;
        std::ofstream(path) << text;
        return "'" + path.string() + "'";
    }

    std::filesystem::path dir_;
};

TEST_F(MalformedScene, IsRejectedNamingWhatIsWrong) {
    const std::string bad_box = write("bad_box.json", R"({
      "format": "physhand-scene/1", "name": "bad_box", "description": "", "duration_s": 1,
      "colliders": [ { "id": "cube", "shape": "box", "half_extents": [0.02, 0.02],
                       "motion": "static" } ] })");
    expect_rejected(bad_box,
                    "bad_box.json: colliders[0].half_extents: expected an array of 3 numbers");
    expect_rejected(write("not_json.json", "{ \"format\": "), "not_json.json: invalid JSON");
    expect_rejected("'" + (dir_ / "missing.json").string() + "'", "missing.json: cannot open");
    // A bad file among good ones: nothing is played.
    const CommandOutput run = run_sample(kScene + " " + bad_box + " --headless --json");
    EXPECT_EQ(run.status, 2) << run.out;
    EXPECT_EQ(run.out.find("\"scene\""), std::string::npos) << run.out;
}

}  // namespace
