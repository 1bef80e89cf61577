// The rendered sample app on the simulated runtime, through the loader and the layer. For
// each paper scene: the scene succeeds, at a moment of contact the touched object is
// translucent, and just before the first contact the object a hand approaches has begun to
// fade. Each app run has identical physics: a first one (the overlay off, images small)
// learns when objects are touched and where view 0 shows them, then the frame of a moment is
// captured with and without the feedback, each run ending at that frame; where the object
// is, the two frames must differ (the background shows through), and far from it they must
// not. Also: a floor under scenes without one, the head position setting of the simulated
// runtime, and quitting a live session.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command_output.h"
#include "png_file.h"

namespace {

using Png = physhand::test::PngImage;
using physhand::test::read_png;
using physhand::test::Rgba;

constexpr int kViewSize = 320;  // swapchain pixels: small, lavapipe draws on the CPU
// Enough to learn where view 0 shows an object (as a fraction of the view, whatever its size).
constexpr int kLearnViewSize = 32;
// Around the object's centre, in swapchain pixels: well inside a 4 cm cube a metre away.
constexpr int kWindow = 2;
constexpr int kChanged = 12;  // of 255, in some channel: a visible change
// How far from an object's centre its image may reach, as a fraction of the image's width:
// a 5 cm ball 40 cm from the eye.
constexpr double kHoverReach = 0.06;

std::filesystem::path scene_file(const std::string& name) {
    return std::filesystem::path(PHYSHAND_SCENES_DIR) / (name + ".json");
}

using physhand::test::CommandOutput;

// Runs `command` in the shell, `environment` (NAME='value' ...) before it.
CommandOutput run_shell(const std::string& environment, const std::string& command) {
    return physhand::test::run_command(environment + " " + command);
}

std::string sample_command(const std::string& scene, const std::string& options, int view_size) {
    return std::string("'") + PHYSHAND_SAMPLE + "' --json --view-size " +
           std::to_string(view_size) + " " + options + " '" + scene_file(scene).string() + "'";
}

std::string capture_environment(const std::filesystem::path& capture, int capture_every) {
    return "PHYSHAND_SIM_CAPTURE='" + capture.string() +
           "' PHYSHAND_SIM_CAPTURE_EVERY=" + std::to_string(capture_every);
}

// Runs the sample on one scene, capturing frame `frame` into `capture` and ending the
// session right after it: the frames before it play as in a whole run, none after it is
// rendered.
void run_sample_to(const std::string& scene, const std::string& options,
                   const std::filesystem::path& capture, int frame, int view_size = kViewSize,
                   const std::string& environment = "") {
    const CommandOutput run =
        run_shell(environment + " " + capture_environment(capture, frame) +
                      " PHYSHAND_SIM_END_AFTER_FRAME=" + std::to_string(frame),
                  sample_command(scene, options, view_size) + " </dev/null");
    EXPECT_EQ(run.status, 0) << run.out;
}

Png view0(const std::filesystem::path& dir, int frame) {
    char name[64];
    std::snprintf(name, sizeof(name), "frame_%05d_view0.png", frame);
    return read_png(dir / name);
}

int difference(const Rgba& a, const Rgba& b) {
    return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

// Captured pixels per drawn one.
int scale_of(const Png& captured) {
    return static_cast<int>(captured.width) / kViewSize;
}

// Of the pixels within `reach` captured pixels of (u, v) (fractions of the image), how many
// differ visibly between `a` and `b`, and how many there are.
std::pair<int, int> changed_around(const Png& a, const Png& b, double u, double v, int reach) {
    const int width = static_cast<int>(a.width), height = static_cast<int>(a.height);
    const int cx = static_cast<int>(u * width), cy = static_cast<int>(v * height);
    int changed = 0, total = 0;
    for (int y = std::max(cy - reach, 0); y <= std::min(cy + reach, height - 1); ++y) {
        for (int x = std::max(cx - reach, 0); x <= std::min(cx + reach, width - 1); ++x) {
            ++total;
            if (difference(a.rgba(x, y), b.rgba(x, y)) > kChanged) ++changed;
        }
    }
    return {changed, total};
}

bool in_view(double u, double v) {
    return u > 0.05 && u < 0.95 && v > 0.05 && v < 0.95;
}

class SampleRender : public testing::Test {
  protected:
    void SetUp() override {
        // CTest runs each test in a process of its own.
        dir_ = std::filesystem::temp_directory_path() /
               ("physhand_sample_render_" + std::to_string(getpid()));
        std::filesystem::remove_all(dir_);
        // The build tree's runtime and layer, on lavapipe where it is installed, with the
        // layer's defaults whatever the user's config; the app names each scene.
        setenv("XR_RUNTIME_JSON", PHYSHAND_SIM_RUNTIME_JSON, 1);
        setenv("XDG_DATA_HOME", PHYSHAND_BUILD_SHARE, 1);
        setenv("XDG_CONFIG_HOME", PHYSHAND_EMPTY_CONFIG_HOME, 1);
        for (const char* name : {"PHYSHAND_CONFIG", "PHYSHAND_SIM_SCENE", "PHYSHAND_SIM_CAPTURE",
                                 "PHYSHAND_SIM_END_AFTER_FRAME", "PHYSHAND_SIM_CONTACT_SHEET",
                                 "PHYSHAND_SIM_HEAD_POSITION", "PHYSHAND_SIM_HEAD_PITCH_DEG",
                                 "DISABLE_XR_APILAYER_PHYSHAND_physical_hands"}) {
            unsetenv(name);
        }
        if (*PHYSHAND_LAVAPIPE != '\0') {
            setenv("VK_DRIVER_FILES", PHYSHAND_LAVAPIPE, 1);
            setenv("VK_ICD_FILENAMES", PHYSHAND_LAVAPIPE, 1);
        }
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // The environment of a run with the layer's overlay off, for runs whose images are not
    // looked at: it changes no physics, and on lavapipe it costs most of a run.
    std::string overlay_off() {
        const std::filesystem::path config = dir_ / "overlay_off.json";
        std::filesystem::create_directories(dir_);
        std::ofstream(config) << R"({"overlay": false})";
        return "PHYSHAND_CONFIG='" + config.string() + "'";
    }

    std::filesystem::path dir_;
};

class PaperScene : public SampleRender, public testing::WithParamInterface<std::string> {
  protected:
    // The scene played with the default feedback and no capture, the overlay off: its
    // result, checked.
    nlohmann::json learn() {
        const CommandOutput run = run_shell(
            overlay_off(), sample_command(GetParam(), "", kLearnViewSize) + " </dev/null");
        EXPECT_EQ(run.status, 0) << run.out;
        const nlohmann::json result = nlohmann::json::parse(run.out);
        EXPECT_EQ(result.at("path"), "layer");
        EXPECT_TRUE(result.at("success").get<bool>()) << result.dump(1);
        EXPECT_GT(result.at("frame_ms_median").get<double>(), 0.0);
        return result;
    }

    // View 0 of scene frame `frame` played with `options`, and with --no-feedback instead;
    // nullopt, with a failure, unless both were captured alike. They show the same world, so
    // the sky is the same. Objects alone: a hand's palm (the sample's own, or the layer's
    // overlay over it) lies in front of what it holds, hiding it alike in both.
    std::optional<std::pair<Png, Png>> with_and_without_feedback(const std::string& options,
                                                                 int frame) {
        run_sample_to(GetParam(), options + " --no-hands", dir_ / "shown", frame, kViewSize,
                      overlay_off());
        run_sample_to(GetParam(), "--no-feedback --no-hands", dir_ / "opaque", frame, kViewSize,
                      overlay_off());
        Png shown = view0(dir_ / "shown", frame), opaque = view0(dir_ / "opaque", frame);
        if (shown.width == 0 || shown.width != opaque.width || shown.height != opaque.height) {
            ADD_FAILURE() << "frame " << frame << " not captured alike";
            return std::nullopt;
        }
        EXPECT_LE(difference(shown.rgba(2, 2), opaque.rgba(2, 2)), 1);
        return std::make_pair(std::move(shown), std::move(opaque));
    }
};

TEST_P(PaperScene, SucceedsAndTheTouchedObjectIsTranslucent) {
    const nlohmann::json result = learn();
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
    ASSERT_TRUE(in_view(u, v)) << "out of view: " << touch.dump();

    // No hover: a hand at the object is within any hover distance, so only the touched
    // flags can make it translucent here.
    const auto frames = with_and_without_feedback("--hover-cm 0", frame);
    ASSERT_TRUE(frames);
    const auto& [shown, opaque] = *frames;
    const auto [changed, total] = changed_around(shown, opaque, u, v, kWindow * scale_of(shown));
    // A good part of it: another object may lie in front of the rest, the same in both
    // frames.
    EXPECT_GT(changed, total / 4) << touch["collider"] << " at frame " << frame << " (" << u << ", "
                                  << v << ") is not translucent";
}

TEST_P(PaperScene, AnObjectAboutToBeTouchedStartsToFade) {
    const nlohmann::json result = learn();
    // The object touched first, at the frame before.
    nlohmann::json touch;
    for (const auto& t : result["touches"]) {
        if (!t["approach_frame"].is_null() &&
            (touch.is_null() || t["approach_frame"] < touch["approach_frame"])) {
            touch = t;
        }
    }
    ASSERT_FALSE(touch.is_null()) << "no object was approached: " << result.dump(1);
    ASSERT_FALSE(touch["approach_view0_position"].is_null()) << touch.dump();
    const int frame = touch["approach_frame"];
    const double u = touch["approach_view0_position"][0], v = touch["approach_view0_position"][1];
    ASSERT_TRUE(in_view(u, v)) << "out of view: " << touch.dump();

    // Nothing is touched yet: only hovering can fade anything.
    const auto frames = with_and_without_feedback("", frame);
    ASSERT_TRUE(frames);
    const auto& [shown, opaque] = *frames;
    // The hand about to touch the object may hide most of it (the overlay's hand is drawn
    // over the app's layer), so what counts is that the frames differ around it, by a few
    // drawn pixels at least. Other objects near the hand may fade too.
    const int changed =
        changed_around(shown, opaque, u, v, static_cast<int>(kHoverReach * shown.width)).first;
    EXPECT_GE(changed, 2 * scale_of(shown) * scale_of(shown))
        << touch["collider"] << " at frame " << frame << " (" << u << ", " << v
        << ") has not begun to fade";
}

INSTANTIATE_TEST_SUITE_P(Sample, PaperScene,
                         testing::Values("throw", "sphere", "displacement", "stack"));

// lift_hold has a table and no floor collider: the sample draws one, so the view straight
// down (the bottom of the image, with the head pitched down) shows a grey floor, not sky.
TEST_F(SampleRender, DrawsAFloorWhereTheSceneHasNone) {
    // Drawn small: the floor is all that is looked at.
    constexpr int kFrame = 90;
    run_sample_to("lift_hold", "", dir_, kFrame, 64);
    const Png frame = view0(dir_, kFrame);
    ASSERT_GT(frame.width, 0u);
    const Rgba sky = frame.rgba(frame.width / 2, 2);  // 5 degrees below the horizon, 18 m away
    const Rgba below = frame.rgba(frame.width / 2, frame.height - 3);
    EXPECT_GT(difference(below, sky), 30) << "sky below the viewer";
    // The floor's grey, whatever its shading.
    EXPECT_LT(std::max({below.r, below.g, below.b}) - std::min({below.r, below.g, below.b}), 20);
}

// The side of the largest square of pixels that differ visibly between `a` and `b`.
int largest_changed_square(const Png& a, const Png& b) {
    const int width = static_cast<int>(a.width), height = static_cast<int>(a.height);
    // side[x]: of the largest such square with its bottom right corner at (x, y), row by row.
    std::vector<int> side(width + 1, 0), above(width + 1, 0);
    int largest = 0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            side[x + 1] = difference(a.rgba(x, y), b.rgba(x, y)) > kChanged
                              ? 1 + std::min({side[x], above[x], above[x + 1]})
                              : 0;
            largest = std::max(largest, side[x + 1]);
        }
        std::swap(side, above);
    }
    return largest;
}

// The sample draws its hands as the layer's collision shapes (XrHandCollisionShapesPHYSHAND):
// seen from straight above, press_table's palm, resting on the table 35 cm below the eye,
// is an unbroken 8 x 9 cm box, where joint spheres and bones leave the table showing between
// the metacarpals. Hand pixels are those that differ from the same frame drawn without hands.
TEST_F(SampleRender, HandsAreDrawnAsTheShapesTheyCollideAs) {
    constexpr int kFrame = 270;  // the palm pressed on the table for a second
    const std::string above = overlay_off() +
                              " PHYSHAND_SIM_HEAD_POSITION=0.1,1.1,-0.35"
                              " PHYSHAND_SIM_HEAD_PITCH_DEG=-90";
    run_sample_to("press_table", "", dir_ / "hands", kFrame, kViewSize, above);
    run_sample_to("press_table", "--no-hands", dir_ / "none", kFrame, kViewSize, above);
    const Png hands = view0(dir_ / "hands", kFrame), none = view0(dir_ / "none", kFrame);
    ASSERT_GT(hands.width, 0u);
    ASSERT_EQ(hands.width, none.width);
    // 6 cm at 35 cm in a view about 90 degrees wide: 8 % of its width (joint spheres: 2-3 %).
    EXPECT_GT(largest_changed_square(hands, none), static_cast<int>(hands.width * 0.08));
}

// A moved head sees the scene elsewhere in view 0; a malformed position is named and the
// default used.
TEST_F(SampleRender, HeadPositionMovesTheViews) {
    const auto seen = [&](const std::string& environment) {
        const CommandOutput run = run_shell(overlay_off() + " " + environment,
                                            sample_command("sphere", "", 32) + " </dev/null 2>&1");
        EXPECT_EQ(run.status, 0) << run.out;
        nlohmann::json position;
        std::istringstream lines(run.out);
        for (std::string line; std::getline(lines, line);) {
            if (line.starts_with("{")) {
                position = nlohmann::json::parse(line)["touches"][0]["view0_position"];
            }
        }
        EXPECT_FALSE(position.is_null()) << run.out;
        return std::make_pair(position, run.out);
    };
    const auto [standing, standing_out] = seen("");
    const auto [seated, seated_out] = seen("PHYSHAND_SIM_HEAD_POSITION=0.1,1.15,0");
    const auto [fallback, fallback_out] = seen("PHYSHAND_SIM_HEAD_POSITION=0.1,,1");
    EXPECT_NE(seated, standing);
    // Lower and closer, the eye sees the ball higher in the image.
    EXPECT_LT(seated[1].get<double>(), standing[1].get<double>());
    EXPECT_EQ(fallback, standing);
    EXPECT_NE(fallback_out.find("PHYSHAND_SIM_HEAD_POSITION=0.1,,1 is not X,Y,Z"),
              std::string::npos)
        << fallback_out;
    EXPECT_EQ(seated_out.find("PHYSHAND_SIM_HEAD_POSITION"), std::string::npos) << seated_out;
}

// `q` in live mode asks the runtime to end the session and lets it, instead of destroying
// a running one (the simulated runtime says so when that happens).
TEST_F(SampleRender, LiveQuitEndsTheSession) {
    const CommandOutput run =
        run_shell("", "printf 'q\\n' | " + sample_command("sphere", "--live", 32) + " 2>&1");
    EXPECT_EQ(run.status, 0) << run.out;
    EXPECT_NE(run.out.find("\"scene\""), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("running session was destroyed"), std::string::npos) << run.out;
}

}  // namespace
