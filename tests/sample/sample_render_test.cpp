// The rendered sample app on the simulated runtime, through the loader and the layer, for
// each paper scene: the scene succeeds, and at a moment of contact the touched object is
// translucent. The app is run three times with identical physics: once to learn when the
// object is touched and where view 0 shows it, then capturing that frame with and without
// the touch feedback; where the object is, the two frames must differ (the background shows
// through), and far from it they must not.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "png_file.h"

namespace {

using Png = physhand::test::PngImage;
using physhand::test::read_png;
using physhand::test::Rgba;

constexpr int kViewSize = 320;  // swapchain pixels: small, lavapipe draws on the CPU
// Around the object's centre, in swapchain pixels: well inside a 4 cm cube a metre away.
constexpr int kWindow = 2;
constexpr int kChanged = 12;  // of 255, in some channel: a visible change

std::filesystem::path scene_file(const std::string& name) {
    return std::filesystem::path(PHYSHAND_SCENES_DIR) / (name + ".json");
}

// Runs the sample on one scene; returns its stdout, or fails.
std::string run_sample(const std::string& scene, const std::string& options,
                       const std::filesystem::path& capture, int capture_every) {
    std::string command;
    if (!capture.empty()) {
        command = "PHYSHAND_SIM_CAPTURE='" + capture.string() +
                  "' PHYSHAND_SIM_CAPTURE_EVERY=" + std::to_string(capture_every) + " ";
    }
    command += std::string("'") + PHYSHAND_SAMPLE + "' --json --view-size " +
               std::to_string(kViewSize) + " " + options + " '" + scene_file(scene).string() +
               "' </dev/null";
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        ADD_FAILURE() << "cannot run " << command;
        return {};
    }
    std::string out;
    char buffer[4096];
    while (std::fgets(buffer, sizeof(buffer), pipe) != nullptr) out += buffer;
    EXPECT_EQ(pclose(pipe), 0) << command;
    return out;
}

int difference(const Rgba& a, const Rgba& b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

class SampleRenderTest : public testing::TestWithParam<std::string> {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() / ("physhand_sample_render_" + GetParam());
        std::filesystem::remove_all(dir_);
        // The build tree's runtime and layer, on lavapipe where it is installed, with the
        // layer's defaults whatever the user's config; the app names each scene.
        setenv("XR_RUNTIME_JSON", PHYSHAND_SIM_RUNTIME_JSON, 1);
        setenv("XDG_DATA_HOME", PHYSHAND_BUILD_SHARE, 1);
        setenv("XDG_CONFIG_HOME", PHYSHAND_EMPTY_CONFIG_HOME, 1);
        unsetenv("PHYSHAND_CONFIG");
        unsetenv("PHYSHAND_SIM_SCENE");
        unsetenv("DISABLE_XR_APILAYER_PHYSHAND_physical_hands");
        if (*PHYSHAND_LAVAPIPE != '\0') {
            setenv("VK_DRIVER_FILES", PHYSHAND_LAVAPIPE, 1);
            setenv("VK_ICD_FILENAMES", PHYSHAND_LAVAPIPE, 1);
        }
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::filesystem::path dir_;
};

TEST_P(SampleRenderTest, SucceedsAndTheTouchedObjectIsTranslucent) {
    const nlohmann::json result = nlohmann::json::parse(run_sample(GetParam(), "", {}, 0));
    EXPECT_EQ(result["path"], "layer");
    EXPECT_TRUE(result["success"].get<bool>()) << result.dump(1);
    EXPECT_GT(result["frame_ms_median"].get<double>(), 0.0);
    ASSERT_FALSE(result["touches"].empty()) << "no object was touched";

    // The object touched longest, at the middle of its touch.
    nlohmann::json touch = result["touches"][0];
    for (const auto& t : result["touches"]) {
        const auto length = [](const nlohmann::json& j) {
            return j["last_frame"].get<int>() - j["first_frame"].get<int>();
        };
        if (length(t) > length(touch)) touch = t;
    }
    ASSERT_FALSE(touch["view0_position"].is_null()) << touch.dump();
    const int frame = touch["frame"];
    const double u = touch["view0_position"][0], v = touch["view0_position"][1];
    ASSERT_TRUE(u > 0.05 && u < 0.95 && v > 0.05 && v < 0.95) << "out of view: " << touch.dump();

    run_sample(GetParam(), "", dir_ / "feedback", frame);
    run_sample(GetParam(), "--no-feedback", dir_ / "opaque", frame);
    char name[64];
    std::snprintf(name, sizeof(name), "frame_%05d_view0.png", frame);
    const Png shown = read_png(dir_ / "feedback" / name);
    const Png opaque = read_png(dir_ / "opaque" / name);
    ASSERT_EQ(shown.width, opaque.width);
    ASSERT_GT(shown.width, 0u);

    const int scale = static_cast<int>(shown.width) / kViewSize;  // captured pixels per drawn
    const int cx = static_cast<int>(u * shown.width), cy = static_cast<int>(v * shown.height);
    int changed = 0, total = 0;
    for (int y = cy - kWindow * scale; y <= cy + kWindow * scale; ++y) {
        for (int x = cx - kWindow * scale; x <= cx + kWindow * scale; ++x) {
            ++total;
            if (difference(shown.rgba(x, y), opaque.rgba(x, y)) > kChanged) ++changed;
        }
    }
    // A good part of it: fingers may lie in front of the rest (a flick touches the ball with
    // the back of the hand between it and the eye), the same in both frames.
    EXPECT_GT(changed, total / 4) << touch["collider"] << " at frame " << frame << " (" << cx
                                  << ", " << cy << ") is not translucent";
    // The sky is untouched: the two runs show the same world.
    EXPECT_LE(difference(shown.rgba(2, 2), opaque.rgba(2, 2)), 1);
}

INSTANTIATE_TEST_SUITE_P(PaperScenes, SampleRenderTest,
                         testing::Values("throw", "sphere", "displacement", "stack"));

}  // namespace
