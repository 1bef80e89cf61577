// The layer's own step at xrEndFrame: an app that locates no hands, or never enabled hand
// tracking, still gets a world that moves on and the runtime's hands in the simulation;
// an app that locates its hands before ending the frame steps once per frame, as before.
// The layer's samples of the ghost hands (PHYSHAND_RECORD) show when it stepped.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

namespace fs = std::filesystem;

const std::vector<const char*> kWithoutHandTracking = {XR_MND_HEADLESS_EXTENSION_NAME,
                                                       XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME};
constexpr const char* kHandTrackingFunctions[] = {
    "xrCreateHandTrackerEXT", "xrDestroyHandTrackerEXT", "xrLocateHandJointsEXT"};

// One sample of the recorded right hand: its time and whether every joint was valid.
struct RecordedSample {
    double t = 0.0;
    bool valid = true;
};

class FrameStep : public LayerTest {
  protected:
    void SetUp() override {
        LayerTest::SetUp();
        use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
        env_.set("PHYSHAND_RECORD", (test_dir() / "record").string());
    }

    // The layer's samples of the right hand (26 rows each), in the order it took them. Ends
    // the session first: the layer closes its files then.
    std::vector<RecordedSample> recorded_right_hand() {
        end_session();
        std::vector<RecordedSample> samples;
        const fs::path dir = test_dir() / "record";
        if (!fs::exists(dir)) return samples;
        for (const auto& entry : fs::directory_iterator(dir)) {
            if (!entry.path().filename().string().ends_with("-right.csv")) continue;
            std::ifstream file(entry.path());
            std::string line;
            std::getline(file, line);  // header
            for (int row = 0; std::getline(file, line); ++row) {
                std::istringstream fields(line);
                std::string t;
                std::getline(fields, t, ',');
                if (row % XR_HAND_JOINT_COUNT_EXT == 0) samples.push_back({std::stod(t), true});
                samples.back().valid = samples.back().valid && line.ends_with(",1");
            }
        }
        return samples;
    }

    static void expect_one_sample_per_frame(const std::vector<RecordedSample>& samples,
                                            int frames) {
        ASSERT_EQ(samples.size(), static_cast<std::size_t>(frames));
        for (std::size_t i = 1; i < samples.size(); ++i) {
            EXPECT_GT(samples[i].t, samples[i - 1].t) << "sample " << i;
        }
    }

    // A frame in which the app locates the hand at the predicted display time, then ends
    // the frame for that time, as apps do.
    XrTime frame_locating(XrHandTrackerEXT tracker, HandJoints& hand) {
        auto wait = xr<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
        auto state = xr<XrFrameState>(XR_TYPE_FRAME_STATE);
        EXPECT_EQ(xrWaitFrame(session_, &wait, &state), XR_SUCCESS);
        auto begin = xr<XrFrameBeginInfo>(XR_TYPE_FRAME_BEGIN_INFO);
        EXPECT_EQ(xrBeginFrame(session_, &begin), XR_SUCCESS);
        locate_ok(tracker, state.predictedDisplayTime, hand);
        auto end = xr<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
        end.displayTime = state.predictedDisplayTime;
        end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
        EXPECT_EQ(xrEndFrame(session_, &end), XR_SUCCESS);
        return state.predictedDisplayTime;
    }
};

// The layer enables XR_EXT_hand_tracking down the chain for itself; the app, which did
// not, still cannot reach its functions, and core validation (beneath the layer) is silent.
TEST_F(FrameStep, HandTrackingTheAppDidNotEnableStaysUnavailableToIt) {
    ASSERT_EQ(create_instance(kWithoutHandTracking), XR_SUCCESS);
    for (const char* name : kHandTrackingFunctions) {
        PFN_xrVoidFunction fn = reinterpret_cast<PFN_xrVoidFunction>(&xrGetInstanceProcAddr);
        EXPECT_EQ(xrGetInstanceProcAddr(instance_, name, &fn), XR_ERROR_FUNCTION_UNSUPPORTED)
            << name;
        EXPECT_EQ(fn, nullptr) << name;
    }
}

// With colliders to meet, the layer tracks the hands itself and steps once per frame.
TEST_F(FrameStep, AnAppWithoutHandTrackingGetsTheHandsSimulatedEveryFrame) {
    ASSERT_EQ(create_instance(kWithoutHandTracking), XR_SUCCESS);
    start_session();
    create_desk();
    constexpr int kFrames = 30;
    frames(kFrames);
    const std::vector<RecordedSample> samples = recorded_right_hand();
    ASSERT_NO_FATAL_FAILURE(expect_one_sample_per_frame(samples, kFrames));
    EXPECT_TRUE(samples.back().valid);
}

// Nothing to show the step (headless, no collider): the layer neither tracks nor steps.
TEST_F(FrameStep, NothingIsSteppedWithoutCollidersOrOverlay) {
    ASSERT_EQ(create_instance(kWithoutHandTracking), XR_SUCCESS);
    start_session();
    frames(10);
    EXPECT_TRUE(recorded_right_hand().empty());
}

// A dynamic cube falls onto the desk over 120 frames in which nothing is located: the
// world moved on every frame (a single locate simulates at most 0.1 s of the gap).
TEST_F(FrameStep, TheWorldMovesOnWhileTheAppLocatesNothing) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const XrTime start = frame();
    create_desk();
    auto info = collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND, stage_,
                              pose_at(-0.2f, kDeskTop + 0.1f, -0.5f), start);
    info.halfExtents = {0.02f, 0.02f, 0.02f};
    const auto cube = create_collider(info);
    const auto landed = locate_collider(cube, frames(120));
    EXPECT_NEAR(landed.pose.position.y, kDeskTop + 0.02f, 0.002);
}

// The app's locate at the frame's time steps; xrEndFrame for that same time steps nothing
// more, and the layer tracks no hand the app tracks.
TEST_F(FrameStep, AnAppLocatingEachFrameStepsOncePerFrame) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    create_desk();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    constexpr int kFrames = 30;
    for (int f = 0; f < kFrames; ++f) frame_locating(right, hand);
    ASSERT_NO_FATAL_FAILURE(expect_one_sample_per_frame(recorded_right_hand(), kFrames));
    EXPECT_TRUE(hand.locations.isActive);
}

}  // namespace
}  // namespace physhand::layer_test
