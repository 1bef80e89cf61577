// The layer's config file (PHYSHAND_CONFIG): static colliders for apps that know nothing of
// the extension, the off switch, the drive, and broken files that must not break the app.
// Apps here do not enable the extension unless said: what they get is compared with the
// same app run with the layer disabled (the runtime's own hands). The parser itself
// (layer/config.cpp, compiled in) is tested for what it reads and the key it blames.

#include "config.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

using layer::parse_config;

void expect_color(const overlay::Color& actual, const overlay::Color& expected) {
    EXPECT_EQ(actual.r, expected.r);
    EXPECT_EQ(actual.g, expected.g);
    EXPECT_EQ(actual.b, expected.b);
}

TEST(ConfigParse, NoDrawingKeysKeepTheOverlaysDefaults) {
    const layer::Config config = parse_config("{}");
    const overlay::Settings defaults;
    expect_color(config.drawing.hand_colors[0], defaults.hand_colors[0]);
    expect_color(config.drawing.hand_colors[1], defaults.hand_colors[1]);
    expect_color(config.drawing.contact_tint, defaults.contact_tint);
    EXPECT_EQ(config.drawing.ghost_alpha, defaults.ghost_alpha);
    EXPECT_TRUE(config.drawing.tint);
    EXPECT_TRUE(config.overlay);
}

TEST(ConfigParse, ColorsGhostOpacityAndTintSetTheDrawing) {
    const layer::Config config = parse_config(R"({"colors": {"left": [1, 0, 0.5],
        "contact": [0, 1, 0]}, "ghost_opacity": 0.45, "tint": false})");
    expect_color(config.drawing.hand_colors[0], {1.0f, 0.0f, 0.5f});
    expect_color(config.drawing.hand_colors[1], overlay::Settings{}.hand_colors[1]);
    expect_color(config.drawing.contact_tint, {0.0f, 1.0f, 0.0f});
    EXPECT_EQ(config.drawing.ghost_alpha, 0.45f);
    EXPECT_FALSE(config.drawing.tint);
    const layer::Config right = parse_config(R"({"colors": {"right": [0, 0, 1]}})");
    expect_color(right.drawing.hand_colors[1], {0.0f, 0.0f, 1.0f});
}

struct BadDrawing {
    const char* name;
    const char* json;
    const char* message;  // how the error begins: the key at fault
};

// Test names and failures show the case's name, not its bytes.
void PrintTo(const BadDrawing& bad, std::ostream* out) {
    *out << bad.name;
}

class ConfigParseRejects : public ::testing::TestWithParam<BadDrawing> {};

TEST_P(ConfigParseRejects, NamingTheKey) {
    try {
        parse_config(GetParam().json);
        ADD_FAILURE() << "accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_TRUE(std::string(e.what()).starts_with(GetParam().message)) << e.what();
    }
}

constexpr BadDrawing kBadDrawings[] = {
    {"ColorsNotAnObject", R"({"colors": [1, 0, 0]})", "colors: expected an object"},
    {"UnknownHand", R"({"colors": {"middle": [1, 0, 0]}})", "colors.middle: unknown key"},
    {"TwoChannels", R"({"colors": {"left": [1, 0]}})", "colors.left: expected an array of 3"},
    {"FourChannels", R"({"colors": {"right": [1, 0, 0, 1]}})",
     "colors.right: expected an array of 3"},
    {"ChannelOverOne", R"({"colors": {"right": [0, 255, 0]}})",
     "colors.right: expected an array of 3 numbers from 0 to 1"},
    {"NegativeChannel", R"({"colors": {"contact": [0, -0.1, 0]}})",
     "colors.contact: expected an array of 3 numbers from 0 to 1"},
    {"ColorName", R"({"colors": {"contact": "blue"}})", "colors.contact: expected an array"},
    {"OpacityOverOne", R"({"ghost_opacity": 1.5})", "ghost_opacity: expected a number from 0 to 1"},
    {"NegativeOpacity", R"({"ghost_opacity": -0.1})", "ghost_opacity: expected a number"},
    {"OpacityNotANumber", R"({"ghost_opacity": "half"})", "ghost_opacity: expected a number"},
};

INSTANTIATE_TEST_SUITE_P(Config, ConfigParseRejects, ::testing::ValuesIn(kBadDrawings),
                         [](const ::testing::TestParamInfo<BadDrawing>& info) {
                             return std::string(info.param.name);
                         });

// A bad value is reported on stderr with its key, and the whole config falls back to the
// defaults, as for any other broken config.
TEST(ConfigLoad, BadColorIsReportedAndTheDefaultsAreUsed) {
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() /
        ("physhand_config_bad_color_" + std::to_string(::getpid()) + ".json");
    std::ofstream(path) << R"({"overlay": false, "colors": {"left": [1, 0, 2]}})";
    ScopedEnv env;
    env.set("PHYSHAND_CONFIG", path.string());
    ::testing::internal::CaptureStderr();
    const layer::Config config = layer::load_config();
    const std::string log = ::testing::internal::GetCapturedStderr();
    std::filesystem::remove(path);
    EXPECT_NE(log.find("colors.left: expected an array of 3 numbers from 0 to 1"),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("using the defaults"), std::string::npos) << log;
    EXPECT_TRUE(config.overlay);
    expect_color(config.drawing.hand_colors[0], overlay::Settings{}.hand_colors[0]);
}

constexpr int kFrames = 180;  // the ghost palm sinks into the desk from frame 70 on

const nlohmann::json kDesk = {
    {"id", "desk"},       {"shape", "box"},  {"half_extents", {0.4, 0.025, 0.3}},
    {"motion", "static"}, {"friction", 0.6}, {"pose", {{"position", {0.0, 0.725, -0.4}}}}};

class Config : public LayerTest {
  protected:
    void SetUp() override {
        LayerTest::SetUp();
        use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
        ghost_ = record_run(LayerMode::Disabled, kFrames);
        ASSERT_EQ(ghost_.right.size(), static_cast<std::size_t>(kFrames));
        // The ghost sinks into where the desk is.
        ASSERT_LT(lowest_joint_over_desk(ghost_.right.back().joints), kDeskTop - 0.02);
    }

    void use_config(const std::string& text) {
        env_.set("PHYSHAND_CONFIG", write_file("config.json", text).string());
    }

    // The run, frame by frame, is exactly the runtime's.
    void expect_ghost_run(const RunResult& run) {
        ASSERT_EQ(run.right.size(), ghost_.right.size());
        for (std::size_t f = 0; f < run.right.size(); ++f) {
            EXPECT_TRUE(same_bits(run.right[f], ghost_.right[f])) << "frame " << f;
            EXPECT_TRUE(same_bits(run.left[f], ghost_.left[f])) << "frame " << f;
        }
    }

    RunResult ghost_;
};

TEST_F(Config, StaticCollidersGiveAnAppWithoutTheExtensionPhysicalHands) {
    use_config(nlohmann::json{{"colliders", {kDesk}}}.dump());
    const RunResult run = record_run(LayerMode::Implicit, kFrames);
    ASSERT_EQ(run.right.size(), static_cast<std::size_t>(kFrames));
    // Far from the desk the hand is the runtime's, exactly.
    for (int f = 0; f < 10; ++f) EXPECT_TRUE(same_bits(run.right[f], ghost_.right[f]));
    // On it, the hand rests on top while the ghost is inside.
    const HandSample& last = run.right.back();
    EXPECT_TRUE(last.is_active);
    EXPECT_GE(lowest_joint_over_desk(last.joints), kDeskTop + kThinnestHandBody - kMaxPenetration);
    EXPECT_GT(distance(last.joints[XR_HAND_JOINT_PALM_EXT].pose.position,
                       ghost_.right.back().joints[XR_HAND_JOINT_PALM_EXT].pose.position),
              0.02);
}

// Config colliders and the app's own share the session.
TEST_F(Config, ConfigCollidersMeetTheAppsColliders) {
    use_config(nlohmann::json{{"colliders", {kDesk}}}.dump());
    use_layer(LayerMode::Implicit);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const XrTime start = frame();
    auto info = collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND, stage_,
                              pose_at(-0.2f, kDeskTop + 0.1f, -0.5f), start);
    info.halfExtents = {0.02f, 0.02f, 0.02f};
    const auto cube = create_collider(info);
    const auto landed = locate_collider(cube, simulate_frames(120));
    EXPECT_NEAR(landed.pose.position.y, kDeskTop + 0.02f, 0.002);
}

TEST_F(Config, ConfigDriveIsTheSessionsDrive) {
    use_config(nlohmann::json{{"colliders", {kDesk}}, {"drive", {{"name", "paper"}}}}.dump());
    use_layer(LayerMode::Implicit);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    for (int f = 0; f < kFrames; ++f) ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
    ASSERT_EQ(hand.physical.isSimulated, XR_TRUE);
    // An unlimited 1000 N/m spring: beyond the default drive's 20 N limit.
    const float palm_lag =
        static_cast<float>(distance(hand.joints[XR_HAND_JOINT_PALM_EXT].pose.position,
                                    hand.ghost[XR_HAND_JOINT_PALM_EXT].position));
    EXPECT_NEAR(hand.spring_force[XR_HAND_JOINT_PALM_EXT], 1000.0f * palm_lag,
                0.15f * 1000.0f * palm_lag + 0.3f);
    EXPECT_GT(*std::max_element(hand.spring_force.begin(), hand.spring_force.end()), 20.0f);
}

// Switched off in its config, the layer passes everything through, its extension included:
// its functions are unsupported even though the app enabled it.
TEST_F(Config, ConfigCanTurnTheLayerOff) {
    use_config(nlohmann::json{{"enabled", false}, {"colliders", {kDesk}}}.dump());
    use_layer(LayerMode::Implicit);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    PFN_xrVoidFunction fn = nullptr;
    EXPECT_EQ(xrGetInstanceProcAddr(instance_, "xrCreatePhysicalColliderPHYSHAND", &fn),
              XR_ERROR_FUNCTION_UNSUPPORTED);
    EXPECT_EQ(fn, nullptr);
    destroy_instance();
    expect_ghost_run(record_run(LayerMode::Implicit, kFrames, all_extensions()));
}

class MalformedConfig : public Config, public ::testing::WithParamInterface<const char*> {};

// A config the layer cannot use is reported and ignored: the app starts, its session runs,
// the extension works, and (the desk it declares never made) the hands pass through.
TEST_P(MalformedConfig, LeavesTheAppWorkingWithTheDefaults) {
    std::string text = GetParam();
    const std::string desk = kDesk.dump();
    for (std::size_t at = text.find("DESK"); at != std::string::npos; at = text.find("DESK")) {
        text.replace(at, 4, desk);
    }
    if (text == "MISSING") {
        env_.set("PHYSHAND_CONFIG", (test_dir() / "no_such_config.json").string());
    } else {
        use_config(text);
    }
    expect_ghost_run(record_run(LayerMode::Implicit, kFrames));

    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const auto sphere = create_collider(collider_info(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND,
                                                      XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND,
                                                      stage_, pose_at(0, 1, -1), frame()));
    EXPECT_NEAR(locate_collider(sphere, now()).pose.position.y, 1.0f, 1e-6);
}

// A config text per case; DESK stands for a valid desk collider, MISSING for a path to no
// file at all.
constexpr const char* kMalformedConfigs[] = {
    "{ \"colliders\": [DESK], ",
    "",
    "[DESK]",
    "{\"colliders\": [DESK], \"colour\": 1}",
    "{\"colliders\": [DESK], \"drive\": {\"name\": \"no_such_drive\"}}",
    "{\"colliders\": [DESK], \"drive\": {\"name\": \"paper\", \"substeps\": 0}}",
    "{\"colliders\": [DESK], \"enabled\": \"yes\"}",
    "{\"colliders\": [DESK], \"colors\": {\"left\": [1, 0]}}",
    "{\"colliders\": [DESK, {\"id\": \"ball\", \"shape\": \"sphere\", \"radius\": 0.05, "
    "\"motion\": \"dynamic\", \"mass\": 1}]}",
    "{\"colliders\": [{\"id\": \"desk\", \"shape\": \"box\", \"motion\": \"static\", "
    "\"half_extents\": [0.4, 0, 0.3]}]}",
    "MISSING",
};
constexpr const char* kMalformedNames[] = {
    "Truncated",  "Empty",    "NotAnObject",     "UnknownKey", "UnknownDrive", "BadSubsteps",
    "BadBoolean", "BadColor", "DynamicCollider", "ZeroSize",   "MissingFile",
};
static_assert(std::size(kMalformedConfigs) == std::size(kMalformedNames));

std::string malformed_name(const ::testing::TestParamInfo<const char*>& info) {
    return kMalformedNames[info.index];
}

INSTANTIATE_TEST_SUITE_P(Config, MalformedConfig, ::testing::ValuesIn(kMalformedConfigs),
                         malformed_name);

}  // namespace
}  // namespace physhand::layer_test
