#pragma once

// The fixture of the simulated runtime's tests: an application on the runtime through the
// real Khronos loader, which finds the runtime by the manifest the build generates. Each
// test plays a short keyframed scene.

#include <gtest/gtest.h>
#include <openxr/openxr.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "frame_clock.h"

namespace physhand::sim_test {

constexpr XrTime kPeriod = physhand::kFramePeriodNs;  // 1/90 s

// Scene time of a display time, when the first frame displayed at `first` is scene frame 1.
inline double scene_time(XrTime time, XrTime first) {
    return physhand::clock_seconds(time - first + kPeriod);
}
constexpr double kDuration = 0.5;
constexpr double kDropoutFrom = 0.2, kDropoutTo = 0.26;

// A right hand that moves, turns, curls and drops out once; no left hand.
constexpr const char* kScene = R"({
  "format": "physhand-scene/1",
  "name": "sim_runtime_test",
  "description": "keyframed right hand with one dropout",
  "duration_s": 0.5,
  "colliders": [
    { "id": "floor", "shape": "plane", "normal": [0, 1, 0], "offset": 0, "motion": "static" }
  ],
  "hands": {
    "right": {
      "keyframes": [
        { "t": 0.0, "wrist": { "position": [0.15, 1.1, -0.3], "orientation": [0, 0, 0, 1] },
          "curl": [0.1, 0.1, 0.1, 0.1, 0.1] },
        { "t": 0.4, "wrist": { "position": [0.05, 1.0, -0.45],
                               "orientation": [0.258819, 0, 0, 0.9659258] },
          "curl": [0.5, 0.8, 0.8, 0.7, 0.6], "spread": 0.4 }
      ],
      "interpolation": "smooth",
      "scale": 1.0
    }
  },
  "tracking": { "rate_hz": 90,
                "dropouts": [ { "hand": "right", "from_s": 0.2, "to_s": 0.26 } ] }
})";

// A zeroed OpenXR struct carrying its type tag (the usual `XrFoo x{XR_TYPE_FOO}` trips
// -Wmissing-field-initializers).
template <typename T>
T xr(XrStructureType type) {
    T s{};
    s.type = type;
    return s;
}

template <typename Handle>
Handle bogus_handle() {
    return reinterpret_cast<Handle>(std::uintptr_t{0xdead0000});
}

inline XrPosef identity_pose() {
    return {{0, 0, 0, 1}, {0, 0, 0}};
}

class SimRuntimeFixture : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        setenv("XR_RUNTIME_JSON", PHYSHAND_SIM_RUNTIME_JSON, 1);
        unsetenv("XR_LOADER_DEBUG");
        // No layer may come between the test and the runtime, the project's implicit one
        // included.
        unsetenv("XR_ENABLE_API_LAYERS");
        setenv("DISABLE_XR_APILAYER_PHYSHAND_physical_hands", "1", 1);
    }

    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        scene_path_ =
            std::filesystem::temp_directory_path() /
            (std::string("physhand_") + info->test_suite_name() + "_" + info->name() + ".json");
        std::ofstream(scene_path_) << kScene;
        setenv("PHYSHAND_SIM_SCENE", scene_path_.c_str(), 1);
    }

    void TearDown() override {
        if (instance_ != XR_NULL_HANDLE) {
            EXPECT_EQ(xrDestroyInstance(instance_), XR_SUCCESS);
        }
        std::filesystem::remove(scene_path_);
    }

    XrResult create_instance(std::vector<const char*> extensions = {
                                 XR_EXT_HAND_TRACKING_EXTENSION_NAME,
                                 XR_MND_HEADLESS_EXTENSION_NAME}) {
        auto info = xr<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
        std::strcpy(info.applicationInfo.applicationName, "sim_runtime_test");
        info.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
        info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
        info.enabledExtensionNames = extensions.data();
        return xrCreateInstance(&info, &instance_);
    }

    void destroy_instance() {
        ASSERT_EQ(xrDestroyInstance(instance_), XR_SUCCESS);
        instance_ = XR_NULL_HANDLE;
    }

    XrSystemId system() {
        auto info = xr<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
        info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
        XrSystemId id = XR_NULL_SYSTEM_ID;
        EXPECT_EQ(xrGetSystem(instance_, &info, &id), XR_SUCCESS);
        return id;
    }

    XrResult create_session(XrSession* session, const void* next = nullptr) {
        auto info = xr<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
        info.next = next;
        info.systemId = system();
        return xrCreateSession(instance_, &info, session);
    }

    XrSession session() {
        XrSession created = XR_NULL_HANDLE;
        EXPECT_EQ(create_session(&created), XR_SUCCESS);
        return created;
    }

    // The next session state change, or nullopt when no event is queued.
    std::optional<XrSessionState> poll_state() {
        auto event = xr<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        XrResult result = xrPollEvent(instance_, &event);
        if (result == XR_EVENT_UNAVAILABLE) return std::nullopt;
        EXPECT_EQ(result, XR_SUCCESS);
        EXPECT_EQ(event.type, XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED);
        return reinterpret_cast<const XrEventDataSessionStateChanged&>(event).state;
    }

    void expect_states(std::initializer_list<XrSessionState> states) {
        for (XrSessionState state : states) EXPECT_EQ(poll_state(), state);
        EXPECT_EQ(poll_state(), std::nullopt);
    }

    static XrResult begin_session(XrSession session) {
        auto info = xr<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
        info.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
        return xrBeginSession(session, &info);
    }

    XrSession focused_session() {
        XrSession created = session();
        expect_states({XR_SESSION_STATE_IDLE, XR_SESSION_STATE_READY});
        EXPECT_EQ(begin_session(created), XR_SUCCESS);
        expect_states(
            {XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_FOCUSED});
        return created;
    }

    static XrResult wait_frame(XrSession session, XrFrameState* state) {
        auto info = xr<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
        *state = xr<XrFrameState>(XR_TYPE_FRAME_STATE);
        return xrWaitFrame(session, &info, state);
    }

    static XrResult end_frame(XrSession session, XrTime display_time) {
        auto info = xr<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
        info.displayTime = display_time;
        info.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
        return xrEndFrame(session, &info);
    }

    // One whole frame; returns its predicted display time.
    static XrTime frame(XrSession session) {
        XrFrameState state;
        EXPECT_EQ(wait_frame(session, &state), XR_SUCCESS);
        EXPECT_EQ(xrBeginFrame(session, nullptr), XR_SUCCESS);
        EXPECT_EQ(end_frame(session, state.predictedDisplayTime), XR_SUCCESS);
        return state.predictedDisplayTime;
    }

    static XrSpace reference_space(XrSession session, XrReferenceSpaceType type,
                                   XrPosef pose = identity_pose()) {
        auto info = xr<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
        info.referenceSpaceType = type;
        info.poseInReferenceSpace = pose;
        XrSpace space = XR_NULL_HANDLE;
        EXPECT_EQ(xrCreateReferenceSpace(session, &info, &space), XR_SUCCESS);
        return space;
    }

    static XrSpaceLocation locate(XrSpace space, XrSpace base, XrTime time) {
        auto location = xr<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
        EXPECT_EQ(xrLocateSpace(space, base, time, &location), XR_SUCCESS);
        return location;
    }

    template <typename Pfn>
    Pfn function(const char* name) {
        PFN_xrVoidFunction fn = nullptr;
        EXPECT_EQ(xrGetInstanceProcAddr(instance_, name, &fn), XR_SUCCESS) << name;
        return reinterpret_cast<Pfn>(fn);
    }

    std::filesystem::path scene_path_;
    XrInstance instance_ = XR_NULL_HANDLE;
};

}  // namespace physhand::sim_test
