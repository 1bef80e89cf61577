// The simulated runtime seen as an application sees it: through the real Khronos loader,
// which finds the runtime by the manifest the build generates. Headless sessions; Vulkan
// ones are tested in sim_vulkan_test.cpp.

#include <dlfcn.h>
#include <openxr/openxr_platform.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "loader_negotiation.h"
#include "scene.h"
#include "sim_runtime_fixture.h"
#include "tracking.h"

namespace {

using namespace physhand::sim_test;

constexpr double kEyeHeight = 1.6;

void expect_position(const XrVector3f& actual, double x, double y, double z) {
    EXPECT_NEAR(actual.x, x, 1e-5);
    EXPECT_NEAR(actual.y, y, 1e-5);
    EXPECT_NEAR(actual.z, z, 1e-5);
}

void expect_pose(const XrPosef& actual, const physhand::Pose& expected) {
    expect_position(actual.position, expected.position.x(), expected.position.y(),
                    expected.position.z());
    const XrQuaternionf& q = actual.orientation;
    physhand::Quat got(q.w, q.x, q.y, q.z);
    EXPECT_GT(std::abs(got.dot(expected.orientation)), 1 - 1e-6);
}

constexpr XrSpaceLocationFlags kAllLocationFlags =
    XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
    XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;

// Output of xrLocateHandJointsEXT with velocities chained; pinned, as it points into itself.
struct HandJoints {
    HandJoints() = default;
    HandJoints(const HandJoints&) = delete;
    HandJoints& operator=(const HandJoints&) = delete;

    XrHandJointLocationsEXT locations =
        xr<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
    XrHandJointVelocitiesEXT velocities =
        xr<XrHandJointVelocitiesEXT>(XR_TYPE_HAND_JOINT_VELOCITIES_EXT);
    std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT> joints{};
    std::array<XrHandJointVelocityEXT, XR_HAND_JOINT_COUNT_EXT> joint_velocities{};
};

class SimRuntimeTest : public SimRuntimeFixture {
  protected:
    XrHandTrackerEXT hand_tracker(XrSession session, XrHandEXT hand) {
        auto info = xr<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
        info.hand = hand;
        info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
        XrHandTrackerEXT tracker = XR_NULL_HANDLE;
        EXPECT_EQ(function<PFN_xrCreateHandTrackerEXT>("xrCreateHandTrackerEXT")(session, &info,
                                                                                 &tracker),
                  XR_SUCCESS);
        return tracker;
    }

    XrResult locate_joints(XrHandTrackerEXT tracker, XrSpace base, XrTime time, HandJoints& out,
                           bool with_velocities = true) {
        auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
        info.baseSpace = base;
        info.time = time;
        out.locations.next = with_velocities ? &out.velocities : nullptr;
        out.locations.jointCount = XR_HAND_JOINT_COUNT_EXT;
        out.locations.jointLocations = out.joints.data();
        out.velocities.jointCount = XR_HAND_JOINT_COUNT_EXT;
        out.velocities.jointVelocities = out.joint_velocities.data();
        return function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")(tracker, &info,
                                                                            &out.locations);
    }

    // The display times of `count` whole frames, and the period the last predicted.
    static std::vector<XrTime> display_times(XrSession session, int count, XrDuration* period) {
        std::vector<XrTime> times;
        for (int n = 0; n < count; ++n) {
            XrFrameState state;
            EXPECT_EQ(wait_frame(session, &state), XR_SUCCESS);
            EXPECT_EQ(xrBeginFrame(session, nullptr), XR_SUCCESS);
            EXPECT_EQ(end_frame(session, state.predictedDisplayTime), XR_SUCCESS);
            *period = state.predictedDisplayPeriod;
            times.push_back(state.predictedDisplayTime);
        }
        return times;
    }
};

TEST_F(SimRuntimeTest, AdvertisesExtensionsAndRejectsUnknownOnes) {
    uint32_t count = 0;
    ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr), XR_SUCCESS);
    std::vector<XrExtensionProperties> extensions(
        count, xr<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
    ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, extensions.data()),
              XR_SUCCESS);
    auto has = [&](const char* name) {
        for (const auto& e : extensions) {
            if (std::strcmp(e.extensionName, name) == 0) return true;
        }
        return false;
    };
    EXPECT_TRUE(has(XR_EXT_HAND_TRACKING_EXTENSION_NAME));
    EXPECT_TRUE(has(XR_MND_HEADLESS_EXTENSION_NAME));

    EXPECT_EQ(create_instance({XR_MND_HEADLESS_EXTENSION_NAME, "XR_PHYSHAND_no_such_extension"}),
              XR_ERROR_EXTENSION_NOT_PRESENT);
    instance_ = XR_NULL_HANDLE;
}

TEST_F(SimRuntimeTest, DescribesItsSystem) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    auto instance_properties = xr<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
    ASSERT_EQ(xrGetInstanceProperties(instance_, &instance_properties), XR_SUCCESS);
    EXPECT_STREQ(instance_properties.runtimeName, "physhand simulated runtime");

    auto handheld = xr<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    handheld.formFactor = XR_FORM_FACTOR_HANDHELD_DISPLAY;
    XrSystemId id = XR_NULL_SYSTEM_ID;
    EXPECT_EQ(xrGetSystem(instance_, &handheld, &id), XR_ERROR_FORM_FACTOR_UNSUPPORTED);

    auto hand = xr<XrSystemHandTrackingPropertiesEXT>(XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT);
    auto properties = xr<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
    properties.next = &hand;
    ASSERT_EQ(xrGetSystemProperties(instance_, system(), &properties), XR_SUCCESS);
    EXPECT_EQ(hand.supportsHandTracking, XR_TRUE);
    EXPECT_EQ(properties.graphicsProperties.maxLayerCount, 16u);
    EXPECT_EQ(xrGetSystemProperties(instance_, system() + 1, &properties), XR_ERROR_SYSTEM_INVALID);

    uint32_t count = 0;
    std::array<XrViewConfigurationType, 4> configurations{};
    ASSERT_EQ(xrEnumerateViewConfigurations(instance_, system(), 4, &count, configurations.data()),
              XR_SUCCESS);
    ASSERT_EQ(count, 1u);
    EXPECT_EQ(configurations[0], XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO);

    auto configuration = xr<XrViewConfigurationProperties>(XR_TYPE_VIEW_CONFIGURATION_PROPERTIES);
    EXPECT_EQ(xrGetViewConfigurationProperties(
                  instance_, system(), XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, &configuration),
              XR_SUCCESS);
    EXPECT_EQ(xrGetViewConfigurationProperties(
                  instance_, system(), XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO, &configuration),
              XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);

    std::array<XrViewConfigurationView, 2> views{};
    views.fill(xr<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
    EXPECT_EQ(xrEnumerateViewConfigurationViews(instance_, system(),
                                                XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 1,
                                                &count, views.data()),
              XR_ERROR_SIZE_INSUFFICIENT);
    EXPECT_EQ(count, 2u);
    ASSERT_EQ(xrEnumerateViewConfigurationViews(instance_, system(),
                                                XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 2,
                                                &count, views.data()),
              XR_SUCCESS);
    for (const auto& view : views) {
        EXPECT_EQ(view.recommendedImageRectWidth, 1024u);
        EXPECT_EQ(view.recommendedImageRectHeight, 1024u);
    }

    XrEnvironmentBlendMode blend{};
    ASSERT_EQ(
        xrEnumerateEnvironmentBlendModes(
            instance_, system(), XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 1, &count, &blend),
        XR_SUCCESS);
    EXPECT_EQ(blend, XR_ENVIRONMENT_BLEND_MODE_OPAQUE);

    char name[XR_MAX_RESULT_STRING_SIZE];
    ASSERT_EQ(xrResultToString(instance_, XR_ERROR_HANDLE_INVALID, name), XR_SUCCESS);
    EXPECT_STREQ(name, "XR_ERROR_HANDLE_INVALID");
    char type_name[XR_MAX_STRUCTURE_NAME_SIZE];
    ASSERT_EQ(xrStructureTypeToString(instance_, XR_TYPE_SPACE_LOCATION, type_name), XR_SUCCESS);
    EXPECT_STREQ(type_name, "XR_TYPE_SPACE_LOCATION");
}

TEST_F(SimRuntimeTest, InternsPaths) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrPath path = XR_NULL_PATH, again = XR_NULL_PATH;
    ASSERT_EQ(xrStringToPath(instance_, "/user/hand/right", &path), XR_SUCCESS);
    ASSERT_EQ(xrStringToPath(instance_, "/user/hand/right", &again), XR_SUCCESS);
    EXPECT_EQ(path, again);
    char text[XR_MAX_PATH_LENGTH];
    uint32_t count = 0;
    ASSERT_EQ(xrPathToString(instance_, path, sizeof(text), &count, text), XR_SUCCESS);
    EXPECT_STREQ(text, "/user/hand/right");
    EXPECT_EQ(count, sizeof("/user/hand/right"));
    EXPECT_EQ(xrStringToPath(instance_, "/user//hand", &path), XR_ERROR_PATH_FORMAT_INVALID);
    EXPECT_EQ(xrStringToPath(instance_, "/User/hand", &path), XR_ERROR_PATH_FORMAT_INVALID);
    EXPECT_EQ(xrPathToString(instance_, 12345, sizeof(text), &count, text), XR_ERROR_PATH_INVALID);
}

TEST_F(SimRuntimeTest, SessionsAreHeadlessOrVulkan) {
    ASSERT_EQ(create_instance({XR_EXT_HAND_TRACKING_EXTENSION_NAME}), XR_SUCCESS);
    XrSession created = XR_NULL_HANDLE;
    EXPECT_EQ(create_session(&created), XR_ERROR_GRAPHICS_DEVICE_INVALID);
    destroy_instance();

    ASSERT_EQ(create_instance(), XR_SUCCESS);
    // A Vulkan binding needs a Vulkan extension enabled; other graphics APIs never work.
    auto vulkan = xr<XrBaseInStructure>(XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR);
    EXPECT_EQ(create_session(&created, &vulkan), XR_ERROR_GRAPHICS_DEVICE_INVALID);
    auto opengl = xr<XrBaseInStructure>(XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR);
    EXPECT_EQ(create_session(&created, &opengl), XR_ERROR_GRAPHICS_DEVICE_INVALID);
    ASSERT_EQ(create_session(&created), XR_SUCCESS);

    // A headless session has no swapchain format.
    uint32_t count = 1;
    EXPECT_EQ(xrEnumerateSwapchainFormats(created, 0, &count, nullptr), XR_SUCCESS);
    EXPECT_EQ(count, 0u);
    auto info = xr<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
    info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
    info.format = 43;  // VK_FORMAT_R8G8B8A8_SRGB
    info.width = info.height = 16;
    info.sampleCount = info.faceCount = info.arraySize = info.mipCount = 1;
    XrSwapchain swapchain = XR_NULL_HANDLE;
    EXPECT_EQ(xrCreateSwapchain(created, &info, &swapchain), XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);
}

TEST_F(SimRuntimeTest, HeadlessSessionReachesFocusedOneStatePerPoll) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession created = session();
    EXPECT_EQ(begin_session(created), XR_ERROR_SESSION_NOT_READY);  // READY not yet polled
    expect_states({XR_SESSION_STATE_IDLE, XR_SESSION_STATE_READY});
    XrFrameState state;
    EXPECT_EQ(wait_frame(created, &state), XR_ERROR_SESSION_NOT_RUNNING);
    ASSERT_EQ(begin_session(created), XR_SUCCESS);
    EXPECT_EQ(begin_session(created), XR_ERROR_SESSION_RUNNING);
    expect_states(
        {XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_FOCUSED});
    EXPECT_EQ(xrDestroySession(created), XR_SUCCESS);
    EXPECT_EQ(xrDestroySession(created), XR_ERROR_HANDLE_INVALID);
}

TEST_F(SimRuntimeTest, FrameLoopAdvancesExactlyOnePeriod) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession running = focused_session();
    EXPECT_EQ(xrBeginFrame(running, nullptr), XR_ERROR_CALL_ORDER_INVALID);
    EXPECT_EQ(end_frame(running, 1), XR_ERROR_CALL_ORDER_INVALID);

    XrFrameState first;
    ASSERT_EQ(wait_frame(running, &first), XR_SUCCESS);
    EXPECT_GT(first.predictedDisplayTime, 0);
    EXPECT_EQ(first.predictedDisplayPeriod, kPeriod);
    EXPECT_EQ(first.shouldRender, XR_TRUE);
    XrFrameState state;
    EXPECT_EQ(wait_frame(running, &state), XR_ERROR_CALL_ORDER_INVALID);  // no xrBeginFrame
    ASSERT_EQ(xrBeginFrame(running, nullptr), XR_SUCCESS);
    ASSERT_EQ(end_frame(running, first.predictedDisplayTime), XR_SUCCESS);
    EXPECT_EQ(end_frame(running, first.predictedDisplayTime), XR_ERROR_CALL_ORDER_INVALID);

    for (XrTime n = 1; n <= 10; ++n)
        EXPECT_EQ(frame(running), first.predictedDisplayTime + n * kPeriod);

    // Beginning over an unended frame discards it.
    ASSERT_EQ(wait_frame(running, &state), XR_SUCCESS);
    ASSERT_EQ(xrBeginFrame(running, nullptr), XR_SUCCESS);
    ASSERT_EQ(wait_frame(running, &state), XR_SUCCESS);
    EXPECT_EQ(xrBeginFrame(running, nullptr), XR_FRAME_DISCARDED);
    EXPECT_EQ(end_frame(running, state.predictedDisplayTime), XR_SUCCESS);
    EXPECT_EQ(state.predictedDisplayTime, first.predictedDisplayTime + 12 * kPeriod);

    // xrEndFrame checks what it is given; a failed call leaves the frame open.
    ASSERT_EQ(wait_frame(running, &state), XR_SUCCESS);
    ASSERT_EQ(xrBeginFrame(running, nullptr), XR_SUCCESS);
    auto quad = xr<XrCompositionLayerQuad>(XR_TYPE_COMPOSITION_LAYER_QUAD);
    quad.space = bogus_handle<XrSpace>();
    quad.pose = identity_pose();
    std::vector<const XrCompositionLayerBaseHeader*> layers(
        17, reinterpret_cast<const XrCompositionLayerBaseHeader*>(&quad));
    auto end_info = xr<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    end_info.displayTime = state.predictedDisplayTime;
    end_info.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    end_info.layerCount = static_cast<uint32_t>(layers.size());
    end_info.layers = layers.data();
    EXPECT_EQ(xrEndFrame(running, &end_info), XR_ERROR_LAYER_LIMIT_EXCEEDED);
    end_info.layerCount = 1;
    EXPECT_EQ(xrEndFrame(running, &end_info), XR_ERROR_HANDLE_INVALID);
    quad.space = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL);
    end_info.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_ADDITIVE;
    EXPECT_EQ(xrEndFrame(running, &end_info), XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED);
    end_info.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    // A headless session has no swapchain for a layer to show.
    EXPECT_EQ(xrEndFrame(running, &end_info), XR_ERROR_HANDLE_INVALID);
    // PHYSHAND_SIM_REJECT_LAYERS_OVER lowers the limit, read at every frame.
    setenv("PHYSHAND_SIM_REJECT_LAYERS_OVER", "0", 1);
    EXPECT_EQ(xrEndFrame(running, &end_info), XR_ERROR_LAYER_LIMIT_EXCEEDED);
    end_info.layerCount = 0;
    EXPECT_EQ(xrEndFrame(running, &end_info), XR_SUCCESS);
    unsetenv("PHYSHAND_SIM_REJECT_LAYERS_OVER");
}

TEST_F(SimRuntimeTest, DisplayRateJitterAndDroppedFramesComeFromTheEnvironment) {
    setenv("PHYSHAND_SIM_DISPLAY_HZ", "144", 1);
    setenv("PHYSHAND_SIM_FRAME_JITTER_MS", "1.5", 1);
    setenv("PHYSHAND_SIM_DROP_EVERY", "4", 1);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrDuration period = 0;
    const std::vector<XrTime> times = display_times(focused_session(), 60, &period);
    EXPECT_EQ(period, physhand::frame_period_ns(144.0));
    int dropped = 0;
    for (std::size_t n = 1; n < times.size(); ++n) {
        const XrDuration gap = times[n] - times[n - 1];
        EXPECT_GE(gap, period - 3'000'000) << n;
        EXPECT_LE(gap, 2 * period + 3'000'000) << n;
        dropped += gap > 3 * period / 2 + 3'000'000 / 2 ? 1 : 0;
        // On its slot's time, give or take the jitter, and not always on time.
        const double slots = static_cast<double>(times[n] - times[0]) / static_cast<double>(period);
        EXPECT_LE(std::abs(slots - std::round(slots)) * static_cast<double>(period), 1.5e6) << n;
    }
    EXPECT_GE(dropped, 15);  // one frame in four: a slot of every 4 is skipped
    EXPECT_LE(dropped, 20);
    std::vector<XrDuration> gaps;
    for (std::size_t n = 1; n < times.size(); ++n) gaps.push_back(times[n] - times[n - 1]);
    std::sort(gaps.begin(), gaps.end());
    EXPECT_LT(gaps.front(), period - 500'000);  // jittered: some frames come early
    destroy_instance();

    // The same environment gives the same times; values out of range are ignored.
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    EXPECT_EQ(display_times(focused_session(), 60, &period), times);
    destroy_instance();
    setenv("PHYSHAND_SIM_DISPLAY_HZ", "500", 1);
    setenv("PHYSHAND_SIM_FRAME_JITTER_MS", "-1", 1);
    setenv("PHYSHAND_SIM_DROP_EVERY", "1", 1);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    const std::vector<XrTime> plain = display_times(focused_session(), 5, &period);
    EXPECT_EQ(period, kPeriod);
    for (std::size_t n = 1; n < plain.size(); ++n) EXPECT_EQ(plain[n] - plain[n - 1], kPeriod);
    unsetenv("PHYSHAND_SIM_DISPLAY_HZ");
    unsetenv("PHYSHAND_SIM_FRAME_JITTER_MS");
    unsetenv("PHYSHAND_SIM_DROP_EVERY");
}

TEST_F(SimRuntimeTest, ASceneLastsItsDurationAtAnyDisplayRate) {
    setenv("PHYSHAND_SIM_DISPLAY_HZ", "20", 1);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    unsetenv("PHYSHAND_SIM_DISPLAY_HZ");
    XrSession running = focused_session();
    XrTime t0 = 0, last = 0;
    int frames = 0;
    bool stopping = false;
    for (; frames < 100 && !stopping; ++frames) {
        last = frame(running);
        if (frames == 0) t0 = last;
        while (auto state = poll_state()) stopping |= *state == XR_SESSION_STATE_STOPPING;
    }
    EXPECT_TRUE(stopping);
    // 0.5 s at 20 Hz: frames at 0.05 .. 0.55 s, the last the first past the duration.
    EXPECT_EQ(frames, 11);
    EXPECT_NEAR(physhand::clock_seconds(last - t0) + 0.05, 0.55, 1e-6);
}

// PHYSHAND_SIM_END_AFTER_FRAME=N ends the scene early: the session stops at the frame
// after frame N, as it would at the scene's end.
TEST_F(SimRuntimeTest, EndAfterFrameStopsTheSessionEarly) {
    setenv("PHYSHAND_SIM_END_AFTER_FRAME", "5", 1);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    unsetenv("PHYSHAND_SIM_END_AFTER_FRAME");
    XrSession running = focused_session();
    int frames = 0;
    bool stopping = false;
    for (; frames < 100 && !stopping; ++frames) {
        frame(running);
        while (auto state = poll_state()) stopping |= *state == XR_SESSION_STATE_STOPPING;
    }
    EXPECT_TRUE(stopping);
    EXPECT_EQ(frames, 6);
}

// PHYSHAND_SIM_HEADLESS_FRAME_LOOP=0: a headless session as Monado's, whose xrWaitFrame
// gives no display time and counts as no wait; the time comes from the monotonic clock.
TEST_F(SimRuntimeTest, HeadlessSessionsWithoutAFrameLoopTellTimeByTheMonotonicClock) {
    setenv("PHYSHAND_SIM_HEADLESS_FRAME_LOOP", "0", 1);
    const auto created = std::chrono::steady_clock::now();
    ASSERT_EQ(create_instance({XR_EXT_HAND_TRACKING_EXTENSION_NAME, XR_MND_HEADLESS_EXTENSION_NAME,
                               XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME}),
              XR_SUCCESS);
    unsetenv("PHYSHAND_SIM_HEADLESS_FRAME_LOOP");
    XrSession running = focused_session();
    for (int n = 0; n < 3; ++n) {
        XrFrameState state;
        ASSERT_EQ(wait_frame(running, &state), XR_SUCCESS);
        EXPECT_EQ(state.predictedDisplayTime, 0);
        EXPECT_EQ(state.shouldRender, XR_FALSE);
        EXPECT_EQ(xrBeginFrame(running, nullptr), XR_ERROR_CALL_ORDER_INVALID);
        EXPECT_EQ(end_frame(running, 1), XR_ERROR_CALL_ORDER_INVALID);
    }

    auto to_time = function<PFN_xrConvertTimespecTimeToTimeKHR>("xrConvertTimespecTimeToTimeKHR");
    auto to_timespec =
        function<PFN_xrConvertTimeToTimespecTimeKHR>("xrConvertTimeToTimespecTimeKHR");
    timespec now{};
    ASSERT_EQ(clock_gettime(CLOCK_MONOTONIC, &now), 0);
    XrTime time = 0;
    ASSERT_EQ(to_time(instance_, &now, &time), XR_SUCCESS);
    EXPECT_GT(time, 0);
    timespec back{};
    ASSERT_EQ(to_timespec(instance_, time, &back), XR_SUCCESS);
    EXPECT_EQ(back.tv_sec, now.tv_sec);
    EXPECT_EQ(back.tv_nsec, now.tv_nsec);
    timespec bad = now;
    bad.tv_nsec = 1'000'000'000;
    EXPECT_EQ(to_time(instance_, &bad, &time), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(to_time(instance_, nullptr, &time), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(to_timespec(instance_, 0, &back), XR_ERROR_TIME_INVALID);

    // The hands are located at such times, and the session stops once the scene is over.
    XrSpace stage = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE);
    HandJoints joints;
    ASSERT_EQ(locate_joints(hand_tracker(running, XR_HAND_RIGHT_EXT), stage, time, joints),
              XR_SUCCESS);
    EXPECT_EQ(joints.locations.isActive, XR_TRUE);
    bool stopping = false;
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (!stopping && std::chrono::steady_clock::now() < give_up) {
        XrFrameState state;
        ASSERT_EQ(wait_frame(running, &state), XR_SUCCESS);
        while (auto polled = poll_state()) stopping |= *polled == XR_SESSION_STATE_STOPPING;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_TRUE(stopping);
    // The scene's time ran with the monotonic clock from the instance's creation.
    EXPECT_GT(std::chrono::steady_clock::now() - created,
              std::chrono::duration<double>(kDuration - kPeriod * 1e-9));
}

TEST_F(SimRuntimeTest, TheTimespecClockNeedsItsExtension) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    PFN_xrVoidFunction fn = nullptr;
    EXPECT_EQ(xrGetInstanceProcAddr(instance_, "xrConvertTimespecTimeToTimeKHR", &fn),
              XR_ERROR_FUNCTION_UNSUPPORTED);
    EXPECT_EQ(fn, nullptr);
}

TEST_F(SimRuntimeTest, ReferenceSpacesLocate) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession running = session();
    const XrTime time = 1'000'000'000;

    uint32_t count = 0;
    std::array<XrReferenceSpaceType, 3> types{};
    ASSERT_EQ(xrEnumerateReferenceSpaces(running, 3, &count, types.data()), XR_SUCCESS);
    EXPECT_EQ(count, 3u);

    XrSpace stage = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE);
    XrSpace local = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL);
    XrSpace view = reference_space(running, XR_REFERENCE_SPACE_TYPE_VIEW);
    XrSpaceLocation location = locate(local, stage, time);
    EXPECT_EQ(location.locationFlags, kAllLocationFlags);
    expect_pose(location.pose, {physhand::Vec3(0, kEyeHeight, 0), physhand::Quat::Identity()});
    expect_pose(locate(stage, local, time).pose,
                {physhand::Vec3(0, -kEyeHeight, 0), physhand::Quat::Identity()});
    expect_pose(locate(view, stage, time).pose,
                {physhand::Vec3(0, kEyeHeight, 0), physhand::Quat::Identity()});

    // Offsets: A = LOCAL turned 90 degrees about +Y and moved 1 m along +X, B = STAGE
    // moved 2 m along -Z. B seen from A is at (2, -1.6, -1), turned -90 degrees.
    const float s = std::sqrt(0.5f);
    XrSpace a = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL, {{0, s, 0, s}, {1, 0, 0}});
    XrSpace b = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE, {{0, 0, 0, 1}, {0, 0, -2}});
    const physhand::Quat turn(Eigen::AngleAxisd(std::numbers::pi / 2, physhand::Vec3::UnitY()));
    expect_pose(locate(a, stage, time).pose, {physhand::Vec3(1, kEyeHeight, 0), turn});
    expect_pose(locate(b, a, time).pose, {physhand::Vec3(2, -kEyeHeight, -1), turn.inverse()});

    auto velocity = xr<XrSpaceVelocity>(XR_TYPE_SPACE_VELOCITY);
    location.next = &velocity;
    ASSERT_EQ(xrLocateSpace(b, a, time, &location), XR_SUCCESS);
    EXPECT_EQ(velocity.velocityFlags,
              XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT);

    XrExtent2Df bounds;
    EXPECT_EQ(xrGetReferenceSpaceBoundsRect(running, XR_REFERENCE_SPACE_TYPE_STAGE, &bounds),
              XR_SPACE_BOUNDS_UNAVAILABLE);

    auto view_info = xr<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
    view_info.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    view_info.displayTime = time;
    view_info.space = stage;
    auto view_state = xr<XrViewState>(XR_TYPE_VIEW_STATE);
    std::array<XrView, 2> views{};
    views.fill(xr<XrView>(XR_TYPE_VIEW));
    ASSERT_EQ(xrLocateViews(running, &view_info, &view_state, 2, &count, views.data()), XR_SUCCESS);
    ASSERT_EQ(count, 2u);
    expect_position(views[0].pose.position, -0.032, kEyeHeight, 0);
    expect_position(views[1].pose.position, 0.032, kEyeHeight, 0);
    for (const XrView& v : views) {
        EXPECT_NEAR(v.fov.angleLeft, -std::numbers::pi / 4, 1e-6);
        EXPECT_NEAR(v.fov.angleRight, std::numbers::pi / 4, 1e-6);
        EXPECT_NEAR(v.fov.angleUp, std::numbers::pi / 4, 1e-6);
        EXPECT_NEAR(v.fov.angleDown, -std::numbers::pi / 4, 1e-6);
    }

    EXPECT_EQ(xrLocateSpace(local, stage, 0, &location), XR_ERROR_TIME_INVALID);
    ASSERT_EQ(xrDestroySpace(b), XR_SUCCESS);
    EXPECT_EQ(xrLocateSpace(b, stage, time, &location), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(xrLocateSpace(stage, bogus_handle<XrSpace>(), time, &location),
              XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(xrDestroySpace(b), XR_ERROR_HANDLE_INVALID);
}

TEST_F(SimRuntimeTest, HandJointsMatchTrackedHands) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    const physhand::Scene scene = physhand::load_scene(scene_path_);
    const physhand::TrackedHands tracked(scene);

    XrSession running = focused_session();
    XrSpace stage = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE);
    XrSpace local = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL);
    XrHandTrackerEXT right = hand_tracker(running, XR_HAND_RIGHT_EXT);
    XrHandTrackerEXT left = hand_tracker(running, XR_HAND_LEFT_EXT);

    XrTime t0 = 0;
    int active_frames = 0, dropped_frames = 0;
    for (int n = 0; n < 40; ++n) {
        XrTime time = frame(running);
        if (n == 0) t0 = time;
        const double t = scene_time(time, t0);
        const physhand::HandPose expected = tracked.ghost(physhand::HandSide::Right, t);
        const physhand::HandPose before = tracked.ghost(physhand::HandSide::Right, t - 1e-3);
        SCOPED_TRACE(testing::Message() << "t = " << t);

        HandJoints in_stage, in_local;
        ASSERT_EQ(locate_joints(right, stage, time, in_stage), XR_SUCCESS);
        ASSERT_EQ(locate_joints(right, local, time, in_local, false), XR_SUCCESS);
        ASSERT_EQ(in_stage.locations.isActive, expected.active ? XR_TRUE : XR_FALSE);
        (expected.active ? active_frames : dropped_frames)++;
        for (std::size_t i = 0; i < XR_HAND_JOINT_COUNT_EXT; ++i) {
            const XrHandJointLocationEXT& joint = in_stage.joints[i];
            if (!expected.active) {
                EXPECT_EQ(joint.locationFlags, 0u);
                EXPECT_EQ(in_stage.joint_velocities[i].velocityFlags, 0u);
                continue;
            }
            const physhand::Pose& pose = expected.joints[i];
            EXPECT_EQ(joint.locationFlags, kAllLocationFlags);
            expect_pose(joint.pose, pose);
            EXPECT_NEAR(joint.radius, expected.radii[i], 1e-6);
            expect_pose(in_local.joints[i].pose,
                        {pose.position - physhand::Vec3(0, kEyeHeight, 0), pose.orientation});

            if (!before.active) continue;
            const XrHandJointVelocityEXT& velocity = in_stage.joint_velocities[i];
            EXPECT_EQ(velocity.velocityFlags,
                      XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT);
            const physhand::Vec3 linear = (pose.position - before.joints[i].position) / 1e-3;
            expect_position(velocity.linearVelocity, linear.x(), linear.y(), linear.z());
            Eigen::AngleAxisd turn(pose.orientation * before.joints[i].orientation.conjugate());
            const physhand::Vec3 angular = turn.axis() * turn.angle() / 1e-3;
            EXPECT_NEAR(velocity.angularVelocity.x, angular.x(), 1e-3);
            EXPECT_NEAR(velocity.angularVelocity.y, angular.y(), 1e-3);
            EXPECT_NEAR(velocity.angularVelocity.z, angular.z(), 1e-3);
        }

        HandJoints left_joints;
        ASSERT_EQ(locate_joints(left, stage, time, left_joints), XR_SUCCESS);
        EXPECT_EQ(left_joints.locations.isActive, XR_FALSE);
        EXPECT_EQ(left_joints.joints[0].locationFlags, 0u);
    }
    EXPECT_GT(active_frames, 0);
    EXPECT_GT(dropped_frames, 0);
}

TEST_F(SimRuntimeTest, DropoutMakesTheHandInactive) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession running = focused_session();
    XrSpace stage = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE);
    XrHandTrackerEXT right = hand_tracker(running, XR_HAND_RIGHT_EXT);
    const XrTime t0 = frame(running);  // scene frame 1
    const auto at = [&](double seconds) {
        return t0 - kPeriod + static_cast<XrTime>(seconds * 1e9);
    };

    HandJoints joints;
    ASSERT_EQ(locate_joints(right, stage, at(0.1), joints), XR_SUCCESS);
    EXPECT_EQ(joints.locations.isActive, XR_TRUE);
    ASSERT_EQ(locate_joints(right, stage, at((kDropoutFrom + kDropoutTo) / 2), joints), XR_SUCCESS);
    EXPECT_EQ(joints.locations.isActive, XR_FALSE);
    for (const auto& joint : joints.joints) EXPECT_EQ(joint.locationFlags, 0u);
    ASSERT_EQ(locate_joints(right, stage, at(0.4), joints), XR_SUCCESS);
    EXPECT_EQ(joints.locations.isActive, XR_TRUE);
}

TEST_F(SimRuntimeTest, WithoutASceneHandsAreNeverActive) {
    unsetenv("PHYSHAND_SIM_SCENE");
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession running = focused_session();
    XrSpace stage = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE);
    XrHandTrackerEXT right = hand_tracker(running, XR_HAND_RIGHT_EXT);
    for (int n = 0; n < 60; ++n) {  // longer than the scene would last
        HandJoints joints;
        ASSERT_EQ(locate_joints(right, stage, frame(running), joints), XR_SUCCESS);
        EXPECT_EQ(joints.locations.isActive, XR_FALSE);
    }
    EXPECT_EQ(poll_state(), std::nullopt);  // and the session does not end on its own
}

TEST_F(SimRuntimeTest, RejectsInvalidHandlesAndArguments) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession running = session();
    XrSpace stage = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE);
    XrHandTrackerEXT right = hand_tracker(running, XR_HAND_RIGHT_EXT);
    const XrTime time = 1'000'000'000;
    HandJoints joints;
    ASSERT_EQ(locate_joints(right, stage, time, joints), XR_SUCCESS);

    auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
    info.baseSpace = stage;
    info.time = time;
    auto locate_raw = function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT");
    joints.locations.jointCount = 25;
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_VALIDATION_FAILURE);
    joints.locations.jointCount = XR_HAND_JOINT_COUNT_EXT;
    joints.velocities.jointCount = 27;
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_VALIDATION_FAILURE);
    joints.locations.next = nullptr;
    joints.locations.jointLocations = nullptr;
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_VALIDATION_FAILURE);
    joints.locations.jointLocations = joints.joints.data();
    joints.locations.type = XR_TYPE_SPACE_LOCATION;
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_VALIDATION_FAILURE);
    joints.locations.type = XR_TYPE_HAND_JOINT_LOCATIONS_EXT;
    info.type = XR_TYPE_SPACE_LOCATION;
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_VALIDATION_FAILURE);
    info.type = XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT;
    EXPECT_EQ(locate_raw(right, nullptr, &joints.locations), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(locate_raw(right, &info, nullptr), XR_ERROR_VALIDATION_FAILURE);
    info.time = 0;
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_TIME_INVALID);
    info.time = time;

    EXPECT_EQ(locate_raw(bogus_handle<XrHandTrackerEXT>(), &info, &joints.locations),
              XR_ERROR_HANDLE_INVALID);
    info.baseSpace = bogus_handle<XrSpace>();
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_HANDLE_INVALID);
    info.baseSpace = stage;
    auto destroy = function<PFN_xrDestroyHandTrackerEXT>("xrDestroyHandTrackerEXT");
    ASSERT_EQ(destroy(right), XR_SUCCESS);
    EXPECT_EQ(locate_raw(right, &info, &joints.locations), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(destroy(right), XR_ERROR_HANDLE_INVALID);

    auto create = function<PFN_xrCreateHandTrackerEXT>("xrCreateHandTrackerEXT");
    auto create_info = xr<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
    create_info.hand = XR_HAND_LEFT_EXT;
    create_info.handJointSet = static_cast<XrHandJointSetEXT>(1);
    XrHandTrackerEXT tracker = XR_NULL_HANDLE;
    EXPECT_EQ(create(running, &create_info, &tracker), XR_ERROR_VALIDATION_FAILURE);
    create_info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
    create_info.hand = static_cast<XrHandEXT>(3);
    EXPECT_EQ(create(running, &create_info, &tracker), XR_ERROR_VALIDATION_FAILURE);
    create_info.hand = XR_HAND_LEFT_EXT;
    EXPECT_EQ(create(bogus_handle<XrSession>(), &create_info, &tracker), XR_ERROR_HANDLE_INVALID);

    // Destroying a session destroys its spaces and trackers.
    tracker = hand_tracker(running, XR_HAND_LEFT_EXT);
    ASSERT_EQ(xrDestroySession(running), XR_SUCCESS);
    EXPECT_EQ(destroy(tracker), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(xrDestroySpace(stage), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(begin_session(running), XR_ERROR_HANDLE_INVALID);
}

TEST_F(SimRuntimeTest, SceneEndStopsThenExits) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession running = focused_session();
    XrTime t0 = 0, last = 0;
    std::vector<XrSessionState> states;
    for (int n = 0; n < 100 && (states.empty() || states.back() != XR_SESSION_STATE_STOPPING);
         ++n) {
        last = frame(running);
        if (n == 0) t0 = last;
        while (auto state = poll_state()) states.push_back(*state);
    }
    EXPECT_EQ(states,
              (std::vector<XrSessionState>{XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_SYNCHRONIZED,
                                           XR_SESSION_STATE_STOPPING}));
    // Stopped at the first frame displayed after the scene's duration.
    EXPECT_GT(scene_time(last, t0), kDuration);
    EXPECT_LE(scene_time(last - kPeriod, t0), kDuration);

    ASSERT_EQ(xrEndSession(running), XR_SUCCESS);
    expect_states({XR_SESSION_STATE_IDLE, XR_SESSION_STATE_EXITING});
    XrFrameState state;
    EXPECT_EQ(wait_frame(running, &state), XR_ERROR_SESSION_NOT_RUNNING);
    EXPECT_EQ(xrEndSession(running), XR_ERROR_SESSION_NOT_RUNNING);
}

TEST_F(SimRuntimeTest, RequestExitStopsThenExits) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    XrSession running = focused_session();
    frame(running);
    EXPECT_EQ(xrEndSession(running), XR_ERROR_SESSION_NOT_STOPPING);
    ASSERT_EQ(xrRequestExitSession(running), XR_SUCCESS);
    expect_states(
        {XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_STOPPING});
    ASSERT_EQ(xrEndSession(running), XR_SUCCESS);
    expect_states({XR_SESSION_STATE_IDLE, XR_SESSION_STATE_EXITING});
    EXPECT_EQ(xrRequestExitSession(running), XR_ERROR_SESSION_NOT_RUNNING);
}

TEST_F(SimRuntimeTest, ActionsExistButAreNeverActive) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    auto set_info = xr<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
    std::strcpy(set_info.actionSetName, "gameplay");
    std::strcpy(set_info.localizedActionSetName, "Gameplay");
    XrActionSet set = XR_NULL_HANDLE;
    ASSERT_EQ(xrCreateActionSet(instance_, &set_info, &set), XR_SUCCESS);
    XrActionSet duplicate = XR_NULL_HANDLE;
    EXPECT_EQ(xrCreateActionSet(instance_, &set_info, &duplicate), XR_ERROR_NAME_DUPLICATED);

    auto action = [&](const char* name, XrActionType type) {
        auto info = xr<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
        std::strcpy(info.actionName, name);
        std::strcpy(info.localizedActionName, name);
        info.actionType = type;
        XrAction created = XR_NULL_HANDLE;
        EXPECT_EQ(xrCreateAction(set, &info, &created), XR_SUCCESS);
        return created;
    };
    XrAction select = action("select", XR_ACTION_TYPE_BOOLEAN_INPUT);
    XrAction squeeze = action("squeeze", XR_ACTION_TYPE_FLOAT_INPUT);
    XrAction aim = action("aim", XR_ACTION_TYPE_POSE_INPUT);
    XrAction buzz = action("buzz", XR_ACTION_TYPE_VIBRATION_OUTPUT);

    XrPath profile = XR_NULL_PATH, click = XR_NULL_PATH;
    ASSERT_EQ(xrStringToPath(instance_, "/interaction_profiles/khr/simple_controller", &profile),
              XR_SUCCESS);
    ASSERT_EQ(xrStringToPath(instance_, "/user/hand/right/input/select/click", &click), XR_SUCCESS);
    XrActionSuggestedBinding binding{select, click};
    auto suggested =
        xr<XrInteractionProfileSuggestedBinding>(XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
    suggested.interactionProfile = profile;
    suggested.countSuggestedBindings = 1;
    suggested.suggestedBindings = &binding;
    ASSERT_EQ(xrSuggestInteractionProfileBindings(instance_, &suggested), XR_SUCCESS);

    XrSession running = focused_session();
    XrActiveActionSet active{set, XR_NULL_PATH};
    auto sync = xr<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
    sync.countActiveActionSets = 1;
    sync.activeActionSets = &active;
    EXPECT_EQ(xrSyncActions(running, &sync), XR_ERROR_ACTIONSET_NOT_ATTACHED);
    XrPath right_hand = XR_NULL_PATH;
    ASSERT_EQ(xrStringToPath(instance_, "/user/hand/right", &right_hand), XR_SUCCESS);
    auto current = xr<XrInteractionProfileState>(XR_TYPE_INTERACTION_PROFILE_STATE);
    EXPECT_EQ(xrGetCurrentInteractionProfile(running, right_hand, &current),
              XR_ERROR_ACTIONSET_NOT_ATTACHED);
    auto attach = xr<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
    attach.countActionSets = 1;
    attach.actionSets = &set;
    ASSERT_EQ(xrAttachSessionActionSets(running, &attach), XR_SUCCESS);
    EXPECT_EQ(xrAttachSessionActionSets(running, &attach), XR_ERROR_ACTIONSETS_ALREADY_ATTACHED);
    ASSERT_EQ(xrSyncActions(running, &sync), XR_SUCCESS);

    auto get = xr<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
    get.action = select;
    auto boolean = xr<XrActionStateBoolean>(XR_TYPE_ACTION_STATE_BOOLEAN);
    ASSERT_EQ(xrGetActionStateBoolean(running, &get, &boolean), XR_SUCCESS);
    EXPECT_EQ(boolean.isActive, XR_FALSE);
    auto value = xr<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
    EXPECT_EQ(xrGetActionStateFloat(running, &get, &value), XR_ERROR_ACTION_TYPE_MISMATCH);
    get.action = squeeze;
    ASSERT_EQ(xrGetActionStateFloat(running, &get, &value), XR_SUCCESS);
    EXPECT_EQ(value.isActive, XR_FALSE);
    get.action = aim;
    auto pose = xr<XrActionStatePose>(XR_TYPE_ACTION_STATE_POSE);
    ASSERT_EQ(xrGetActionStatePose(running, &get, &pose), XR_SUCCESS);
    EXPECT_EQ(pose.isActive, XR_FALSE);

    // No controller: no profile, no bound source, nothing to vibrate (which succeeds).
    current.interactionProfile = profile;
    ASSERT_EQ(xrGetCurrentInteractionProfile(running, right_hand, &current), XR_SUCCESS);
    EXPECT_EQ(current.interactionProfile, XR_NULL_PATH);
    auto bound =
        xr<XrBoundSourcesForActionEnumerateInfo>(XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO);
    bound.action = select;
    uint32_t count = 1;
    ASSERT_EQ(xrEnumerateBoundSourcesForAction(running, &bound, 0, &count, nullptr), XR_SUCCESS);
    EXPECT_EQ(count, 0u);
    auto haptic = xr<XrHapticActionInfo>(XR_TYPE_HAPTIC_ACTION_INFO);
    haptic.action = buzz;
    auto vibration = xr<XrHapticVibration>(XR_TYPE_HAPTIC_VIBRATION);
    vibration.duration = XR_MIN_HAPTIC_DURATION;
    vibration.amplitude = 1;
    const auto* feedback = reinterpret_cast<const XrHapticBaseHeader*>(&vibration);
    EXPECT_EQ(xrApplyHapticFeedback(running, &haptic, feedback), XR_SUCCESS);
    EXPECT_EQ(xrStopHapticFeedback(running, &haptic), XR_SUCCESS);
    haptic.action = select;
    EXPECT_EQ(xrApplyHapticFeedback(running, &haptic, feedback), XR_ERROR_ACTION_TYPE_MISMATCH);

    auto space_info = xr<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
    space_info.action = aim;
    space_info.poseInActionSpace = identity_pose();
    XrSpace aim_space = XR_NULL_HANDLE;
    ASSERT_EQ(xrCreateActionSpace(running, &space_info, &aim_space), XR_SUCCESS);
    XrSpace stage = reference_space(running, XR_REFERENCE_SPACE_TYPE_STAGE);
    EXPECT_EQ(locate(aim_space, stage, frame(running)).locationFlags, 0u);

    EXPECT_EQ(xrDestroyActionSet(set), XR_SUCCESS);
    EXPECT_EQ(xrDestroyAction(aim), XR_ERROR_HANDLE_INVALID);  // went with its set
}

TEST_F(SimRuntimeTest, HandTrackingFunctionsNeedTheExtension) {
    ASSERT_EQ(create_instance({XR_MND_HEADLESS_EXTENSION_NAME}), XR_SUCCESS);
    PFN_xrVoidFunction fn = nullptr;
    EXPECT_EQ(xrGetInstanceProcAddr(instance_, "xrLocateHandJointsEXT", &fn),
              XR_ERROR_FUNCTION_UNSUPPORTED);
    EXPECT_EQ(fn, nullptr);
}

// The loader only walks the happy path of negotiation and filters unknown extensions
// itself, so the runtime's own checks are exercised by opening the library directly.
TEST_F(SimRuntimeTest, NegotiatesAndValidatesWithoutTheLoader) {
    void* library = dlopen(PHYSHAND_SIM_RUNTIME_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(library, nullptr) << dlerror();
    auto negotiate = reinterpret_cast<PFN_xrNegotiateLoaderRuntimeInterface>(
        dlsym(library, "xrNegotiateLoaderRuntimeInterface"));
    ASSERT_NE(negotiate, nullptr);
    EXPECT_EQ(dlsym(library, "xrCreateInstance"), nullptr);  // only the negotiation is exported

    XrNegotiateLoaderInfo loader{
        XR_LOADER_INTERFACE_STRUCT_LOADER_INFO, XR_LOADER_INFO_STRUCT_VERSION,
        sizeof(XrNegotiateLoaderInfo),          1,
        XR_CURRENT_LOADER_RUNTIME_VERSION,      XR_MAKE_VERSION(1, 0, 0),
        XR_MAKE_VERSION(1, 0x3ff, 0xfff)};
    XrNegotiateRuntimeRequest request{XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST,
                                      XR_RUNTIME_INFO_STRUCT_VERSION,
                                      sizeof(XrNegotiateRuntimeRequest),
                                      0,
                                      0,
                                      nullptr};
    loader.structSize = sizeof(XrNegotiateLoaderInfo) - 1;
    EXPECT_EQ(negotiate(&loader, &request), XR_ERROR_INITIALIZATION_FAILED);
    loader.structSize = sizeof(XrNegotiateLoaderInfo);
    loader.minInterfaceVersion = XR_CURRENT_LOADER_RUNTIME_VERSION + 1;
    loader.maxInterfaceVersion = XR_CURRENT_LOADER_RUNTIME_VERSION + 1;
    EXPECT_EQ(negotiate(&loader, &request), XR_ERROR_INITIALIZATION_FAILED);
    loader.minInterfaceVersion = 1;
    loader.maxInterfaceVersion = XR_CURRENT_LOADER_RUNTIME_VERSION;
    ASSERT_EQ(negotiate(&loader, &request), XR_SUCCESS);
    EXPECT_EQ(request.runtimeInterfaceVersion, XR_CURRENT_LOADER_RUNTIME_VERSION);
    EXPECT_EQ(XR_VERSION_MAJOR(request.runtimeApiVersion), 1);
    PFN_xrGetInstanceProcAddr get_proc = request.getInstanceProcAddr;
    ASSERT_NE(get_proc, nullptr);

    PFN_xrVoidFunction fn = nullptr;
    EXPECT_EQ(get_proc(XR_NULL_HANDLE, "xrGetSystem", &fn), XR_ERROR_HANDLE_INVALID);
    ASSERT_EQ(get_proc(XR_NULL_HANDLE, "xrCreateInstance", &fn), XR_SUCCESS);
    auto create = reinterpret_cast<PFN_xrCreateInstance>(fn);
    auto info = xr<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
    std::strcpy(info.applicationInfo.applicationName, "sim_runtime_test");
    info.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
    const char* unknown = "XR_PHYSHAND_no_such_extension";
    info.enabledExtensionCount = 1;
    info.enabledExtensionNames = &unknown;
    XrInstance direct = XR_NULL_HANDLE;
    EXPECT_EQ(create(&info, &direct), XR_ERROR_EXTENSION_NOT_PRESENT);
    info.enabledExtensionCount = 0;
    ASSERT_EQ(create(&info, &direct), XR_SUCCESS);

    EXPECT_EQ(get_proc(direct, "xrNoSuchFunction", &fn), XR_ERROR_FUNCTION_UNSUPPORTED);
    EXPECT_EQ(get_proc(bogus_handle<XrInstance>(), "xrGetSystem", &fn), XR_ERROR_HANDLE_INVALID);
    ASSERT_EQ(get_proc(direct, "xrDestroyInstance", &fn), XR_SUCCESS);
    auto destroy = reinterpret_cast<PFN_xrDestroyInstance>(fn);
    EXPECT_EQ(destroy(direct), XR_SUCCESS);
    EXPECT_EQ(destroy(direct), XR_ERROR_HANDLE_INVALID);
    dlclose(library);
}

}  // namespace
