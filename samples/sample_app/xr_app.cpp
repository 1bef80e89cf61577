#include "xr_app.h"

#include <openxr/physhand_physical_hands.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "frame_clock.h"
#include "hand_drive.h"
#include "quantile.h"
#include "run_metrics.h"
#include "touch_log.h"
#include "xr_check.h"

namespace physhand::sample {

namespace {

// How long the app waits, at the start and at the end, for the runtime to move the session
// on before it gives up (in live mode only once it asked to exit: a person puts the headset
// on when they like).
constexpr std::chrono::seconds kStateChangeTimeout{10};

// What the app enables; the layer's extension first, as the likeliest to be missing.
std::vector<const char*> extensions(bool rendered) {
    return {XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME, XR_EXT_HAND_TRACKING_EXTENSION_NAME,
            rendered ? XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME : XR_MND_HEADLESS_EXTENSION_NAME};
}

// What the loader offers: the runtime's extensions and the layers'.
std::vector<XrExtensionProperties> offered_extensions() {
    std::uint32_t count = 0;
    xr_check(XR_NULL_HANDLE, xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr),
             "xrEnumerateInstanceExtensionProperties");
    XrExtensionProperties blank{};
    blank.type = XR_TYPE_EXTENSION_PROPERTIES;
    std::vector<XrExtensionProperties> properties(count, blank);
    xr_check(XR_NULL_HANDLE,
             xrEnumerateInstanceExtensionProperties(nullptr, count, &count, properties.data()),
             "xrEnumerateInstanceExtensionProperties");
    return properties;
}

bool is_offered(const std::vector<XrExtensionProperties>& offered, const char* name) {
    return std::any_of(offered.begin(), offered.end(),
                       [&](const auto& p) { return std::strcmp(p.extensionName, name) == 0; });
}

// Throws unless the loader offers every extension the app needs.
void check_extensions(const std::vector<const char*>& wanted,
                      const std::vector<XrExtensionProperties>& offered) {
    for (const char* name : wanted) {
        if (is_offered(offered, name)) continue;
        if (name == wanted[0]) {
            throw std::runtime_error(
                "the physhand layer is not active (no " XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME
                " extension); is its manifest found, and "
                "DISABLE_XR_APILAYER_PHYSHAND_physical_hands unset?");
        }
        throw std::runtime_error(std::string("the runtime lacks ") + name);
    }
}

}  // namespace

XrApp::XrApp(const AppOptions& options) : options_(options) {
    const std::vector<XrExtensionProperties> offered = offered_extensions();
    std::vector<const char*> enabled = extensions(options.rendered);
    check_extensions(enabled, offered);
    // A headless session may have no frame loop (Monado's): time then comes from here.
    const bool timespec =
        !options.rendered && is_offered(offered, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
    if (timespec) enabled.push_back(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
    XrInstanceCreateInfo instance_info{};
    instance_info.type = XR_TYPE_INSTANCE_CREATE_INFO;
    std::strncpy(instance_info.applicationInfo.applicationName, "physhand-sample",
                 XR_MAX_APPLICATION_NAME_SIZE - 1);
    instance_info.applicationInfo.applicationVersion = 1;
    instance_info.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
    instance_info.enabledExtensionCount = static_cast<std::uint32_t>(enabled.size());
    instance_info.enabledExtensionNames = enabled.data();
    XrInstance instance = XR_NULL_HANDLE;
    xr_check(XR_NULL_HANDLE, xrCreateInstance(&instance_info, &instance), "xrCreateInstance");
    instance_ = XrHandle<XrInstance>(instance, xrDestroyInstance);
    clock_.emplace(instance, timespec);

    XrSystemGetInfo system_info{};
    system_info.type = XR_TYPE_SYSTEM_GET_INFO;
    system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    XrSystemId system = XR_NULL_SYSTEM_ID;
    xr_check(instance, xrGetSystem(instance, &system_info, &system), "xrGetSystem");

    // Headless: no graphics binding (XR_MND_headless).
    XrSessionCreateInfo session_info{};
    session_info.type = XR_TYPE_SESSION_CREATE_INFO;
    session_info.systemId = system;
    XrGraphicsBindingVulkan2KHR binding{};
    if (options.rendered) {
        vulkan_.emplace(instance, system);
        binding = vulkan_->binding();
        session_info.next = &binding;
    }
    XrSession session = XR_NULL_HANDLE;
    xr_check(instance, xrCreateSession(instance, &session_info, &session), "xrCreateSession");
    session_ = XrHandle<XrSession>(session, xrDestroySession);
    set_hand_drive(instance, session, options.drive);

    XrReferenceSpaceCreateInfo space_info{};
    space_info.type = XR_TYPE_REFERENCE_SPACE_CREATE_INFO;
    space_info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_STAGE;
    space_info.poseInReferenceSpace.orientation.w = 1.0f;
    XrSpace stage = XR_NULL_HANDLE;
    xr_check(instance, xrCreateReferenceSpace(session, &space_info, &stage),
             "xrCreateReferenceSpace(STAGE)");
    stage_ = XrHandle<XrSpace>(stage, xrDestroySpace);

    if (options.rendered)
        graphics_.emplace(instance, system, session, *vulkan_, options.view_width);
    trackers_.emplace(instance, session);
    collider_functions_ = ColliderFunctions::load(instance);
}

bool XrApp::poll_events() {
    const XrInstance instance = instance_.get();
    for (;;) {
        XrEventDataBuffer event{};
        event.type = XR_TYPE_EVENT_DATA_BUFFER;
        const XrResult result = xrPollEvent(instance, &event);
        xr_check(instance, result, "xrPollEvent");
        if (result == XR_EVENT_UNAVAILABLE) return true;
        if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) return false;
        if (event.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) continue;
        switch (reinterpret_cast<const XrEventDataSessionStateChanged&>(event).state) {
            case XR_SESSION_STATE_READY: {
                XrSessionBeginInfo begin{};
                begin.type = XR_TYPE_SESSION_BEGIN_INFO;
                begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
                xr_check(instance, xrBeginSession(session_.get(), &begin), "xrBeginSession");
                running_ = true;
                break;
            }
            case XR_SESSION_STATE_STOPPING:
                xr_check(instance, xrEndSession(session_.get()), "xrEndSession");
                running_ = false;
                break;
            case XR_SESSION_STATE_EXITING:
            case XR_SESSION_STATE_LOSS_PENDING:
                return false;
            default:
                break;
        }
    }
}

void XrApp::play_frame(const Scene& scene, XrTime time, double t, RunObserver& observer) {
    if (!colliders_) {
        colliders_.emplace(scene, collider_functions_, instance_.get(), session_.get(),
                           stage_.get(), time);
        announcer_.emplace(instance_.get(), session_.get(), stage_.get());
    }
    // Before the hands: locating them steps the physics, which must see this frame's targets.
    colliders_->follow(time, t);
    const double step_us = trackers_->locate(stage_.get(), time, hands_);
    observer.add_frame(t, step_us, hands_, colliders_->locate(time));
    announcer_->read(time, t, scene, *colliders_, *options_.touch_lines);
    scene_t_ = t;
}

bool XrApp::begin_frame(const XrFrameState& state) {
    if (!options_.rendered && state.predictedDisplayTime <= 0) return false;
    XrFrameBeginInfo begin{};
    begin.type = XR_TYPE_FRAME_BEGIN_INFO;
    const XrResult result = xrBeginFrame(session_.get(), &begin);
    if (!options_.rendered && result == XR_ERROR_CALL_ORDER_INVALID) return false;
    xr_check(instance_.get(), result, "xrBeginFrame");
    return true;
}

XrTime XrApp::unlooped_frame_time() {
    const auto now = std::chrono::steady_clock::now();
    if (next_frame_ > now) std::this_thread::sleep_until(next_frame_);
    next_frame_ = std::max(next_frame_, now) + std::chrono::nanoseconds(kFramePeriodNs);
    const std::optional<XrTime> time = clock_->now();
    if (!time) {
        throw std::runtime_error(
            "the runtime's headless session has no frame loop, and no "
            "XR_KHR_convert_timespec_time to tell the time by");
    }
    return *time;
}

void XrApp::end_frame(const XrFrameState& state, bool playing, int frame, TouchLog& touches) {
    // After the scene the last state played is shown again: nothing steps.
    const XrCompositionLayerBaseHeader* layer = nullptr;
    if (graphics_ && colliders_ && state.shouldRender == XR_TRUE) {
        layer = graphics_->render(stage_.get(), state.predictedDisplayTime, colliders_->located(),
                                  hands_, options_.drawing,
                                  announcer_->flashes(scene_t_, colliders_->located().size()));
        if (playing && layer != nullptr) {
            touches.add_frame(frame, colliders_->located(), [this](const Vec3& point) {
                return graphics_->view0_position(point);
            });
        }
    }
    XrFrameEndInfo end{};
    end.type = XR_TYPE_FRAME_END_INFO;
    end.displayTime = state.predictedDisplayTime;
    end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    end.layerCount = layer != nullptr ? 1 : 0;
    end.layers = &layer;
    xr_check(instance_.get(), xrEndFrame(session_.get(), &end), "xrEndFrame");
}

ScenePlayed XrApp::play(const Scene& scene) {
    const XrInstance instance = instance_.get();
    const XrSession session = session_.get();
    RunObserver observer(scene, options_.drive);
    TouchLog touches(scene);
    // The previous scene's colliders go; this one's are declared at its first frame.
    colliders_.reset();
    announcer_.reset();
    hands_ = {};
    if (graphics_) graphics_->show(scene);
    ScenePlayed played;
    int frame = 0;
    // Scene time comes from display times, never frame counts, so a scene lasts its duration
    // at any display rate: the first frame shown is one display period in, as in the
    // physics-only runner, and the scene is over once a frame reaches its duration.
    std::optional<XrTime> scene_start;
    double scene_t = 0.0;
    double display_hz = kFrameRateHz;
    // Since when no scene frame was played: before the session runs, and after the last.
    auto idle_since = std::chrono::steady_clock::now();
    while (poll_events()) {
        if (options_.live && !exit_requested_) {
            const UserCommand command = poll_user_command();
            if (command == UserCommand::Quit && running_) {
                // Ended as the runtime expects: the loop runs on until it stops the session.
                xr_check(instance, xrRequestExitSession(session), "xrRequestExitSession");
                exit_requested_ = true;
            } else if (command != UserCommand::None) {
                played.next = command;
                break;
            }
        }
        const bool playing =
            running_ && !exit_requested_ &&
            (options_.live || frame == 0 || !scene_over(scene_t, scene.duration_s));
        if (!playing && (!options_.live || exit_requested_) &&
            std::chrono::steady_clock::now() - idle_since > kStateChangeTimeout) {
            throw std::runtime_error(frame == 0 && !exit_requested_
                                         ? "the runtime never started the session"
                                         : "the runtime never ended the session");
        }
        if (!running_) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            continue;
        }
        // Every frame is waited, begun and ended, also those after the scene while the
        // session winds down, as the frame loop must run until STOPPING.
        XrFrameWaitInfo wait{};
        wait.type = XR_TYPE_FRAME_WAIT_INFO;
        XrFrameState state{};
        state.type = XR_TYPE_FRAME_STATE;
        xr_check(instance, xrWaitFrame(session, &wait, &state), "xrWaitFrame");
        const bool begun = begin_frame(state);
        const XrTime time = begun ? state.predictedDisplayTime : unlooped_frame_time();
        if (playing) {
            if (!scene_start) {
                const XrDuration period = state.predictedDisplayPeriod > 0
                                              ? state.predictedDisplayPeriod
                                              : kFramePeriodNs;
                scene_start = time - period;
                // To the millihertz: a period in whole nanoseconds is not exactly 1/rate.
                display_hz = std::round(1e12 / static_cast<double>(period)) * 1e-3;
            }
            scene_t = clock_seconds(time - *scene_start);
            ++frame;
            play_frame(scene, time, scene_t, observer);
            idle_since = std::chrono::steady_clock::now();
        }
        if (begun) end_frame(state, playing, frame, touches);
        if (!options_.live && frame > 0 && scene_over(scene_t, scene.duration_s) &&
            !exit_requested_) {
            xr_check(instance, xrRequestExitSession(session), "xrRequestExitSession");
            exit_requested_ = true;
        }
    }
    played.result = observer.result();
    played.result.display_hz = display_hz;
    if (graphics_) {
        played.rendering = {{"frame_ms_median", quantile(graphics_->frame_ms(), 0.5)},
                            {"touches", touches.to_json()}};
    }
    return played;
}

}  // namespace physhand::sample
