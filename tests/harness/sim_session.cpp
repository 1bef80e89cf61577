// Sessions: the state machine (driven through xrPollEvent), the frame loop and the
// virtual clock.

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

// The display time of the latest waited frame; the first frame's before any.
XrTime now(const InstanceData& instance) {
    return instance.display.display_time(std::max<std::int64_t>(instance.frames_waited - 1, 0));
}

void queue_state(InstanceData& instance, XrSession handle, SessionData& session,
                 XrSessionState state) {
    instance.events.push_back({handle, state, now(instance)});
    session.queued_state = state;
}

// A running session steps down one state at a time, as real runtimes do, to STOPPING;
// xrEndSession then takes it to EXITING so the application ends on its own.
void queue_stopping(InstanceData& instance, XrSession handle, SessionData& session) {
    if (session.stop_queued) return;
    session.stop_queued = true;
    if (session.queued_state == XR_SESSION_STATE_FOCUSED) {
        queue_state(instance, handle, session, XR_SESSION_STATE_VISIBLE);
    }
    if (session.queued_state == XR_SESSION_STATE_VISIBLE) {
        queue_state(instance, handle, session, XR_SESSION_STATE_SYNCHRONIZED);
    }
    queue_state(instance, handle, session, XR_SESSION_STATE_STOPPING);
}

// The first struct whose type is a graphics binding, or nullptr: matched by name
// (XR_TYPE_GRAPHICS_BINDING_*) so that a binding for any graphics API the headers know is
// seen, and refused unless it is Vulkan's.
const XrBaseInStructure* graphics_binding(const void* next) {
    constexpr std::string_view kPrefix = "XR_TYPE_GRAPHICS_BINDING_";
    for (auto* s = static_cast<const XrBaseInStructure*>(next); s != nullptr; s = s->next) {
        const char* name = structure_type_name(s->type);
        if (name != nullptr && std::string_view(name).starts_with(kPrefix)) return s;
    }
    return nullptr;
}

}  // namespace

void destroy_session(Runtime& rt, XrSession session) {
    SessionData* data = rt.sessions.find(session);
    // Its contact sheet, once every frame is in (sim_capture.cpp).
    const InstanceData& instance = *rt.instances.find(data->instance);
    if (instance.capture && !data->sheet_tiles.empty()) {
        write_png(instance.capture->contact_sheet, contact_sheet(data->sheet_tiles));
    }
    std::erase_if(rt.instances.find(data->instance)->events,
                  [&](const StateChange& change) { return change.session == session; });
    rt.spaces.erase_if([&](XrSpace, const SpaceData& space) { return space.session == session; });
    rt.hand_trackers.erase_if([&](XrHandTrackerEXT, const HandTrackerData& tracker) {
        return tracker.session == session;
    });
    // Before the session: their images are freed on its device.
    rt.swapchains.erase_if(
        [&](XrSwapchain, const SwapchainData& swapchain) { return swapchain.session == session; });
    rt.sessions.erase(session);
}

XrResult xrCreateSession(XrInstance instance, const XrSessionCreateInfo* createInfo,
                         XrSession* session) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_SESSION_CREATE_INFO) || session == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (createInfo->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
        std::unique_ptr<VulkanSession> vulkan;
        const XrBaseInStructure* binding = graphics_binding(createInfo->next);
        if (binding == nullptr) {
            if (!data->headless) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
        } else if (binding->type == XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR) {
            if (XrResult result = open_vulkan_session(
                    *data, *reinterpret_cast<const XrGraphicsBindingVulkanKHR*>(binding), &vulkan);
                XR_FAILED(result)) {
                return result;
            }
        } else {
            return XR_ERROR_GRAPHICS_DEVICE_INVALID;
        }
        *session = rt.sessions.add(SessionData{.instance = instance, .vulkan = std::move(vulkan)});
        SessionData& created = *rt.sessions.find(*session);
        queue_state(*data, *session, created, XR_SESSION_STATE_IDLE);
        queue_state(*data, *session, created, XR_SESSION_STATE_READY);
        return XR_SUCCESS;
    });
}

XrResult xrDestroySession(XrSession session) {
    return guarded([&](Runtime& rt) {
        const SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        // Allowed, but an app that quits this way never let the runtime end the session:
        // said, so that a test of an app's shutdown can see it.
        if (data->running) {
            std::fprintf(stderr,
                         "physhand simulated runtime: a running session was destroyed (no "
                         "xrRequestExitSession and xrEndSession before)\n");
        }
        destroy_session(rt, session);
        return XR_SUCCESS;
    });
}

XrResult xrBeginSession(XrSession session, const XrSessionBeginInfo* beginInfo) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(beginInfo, XR_TYPE_SESSION_BEGIN_INFO)) return XR_ERROR_VALIDATION_FAILURE;
        if (beginInfo->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) {
            return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
        }
        if (data->running) return XR_ERROR_SESSION_RUNNING;
        if (data->state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
        data->running = true;
        InstanceData& instance = *rt.instances.find(data->instance);
        queue_state(instance, session, *data, XR_SESSION_STATE_SYNCHRONIZED);
        queue_state(instance, session, *data, XR_SESSION_STATE_VISIBLE);
        queue_state(instance, session, *data, XR_SESSION_STATE_FOCUSED);
        return XR_SUCCESS;
    });
}

XrResult xrEndSession(XrSession session) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!data->running) return XR_ERROR_SESSION_NOT_RUNNING;
        if (data->state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
        data->running = false;
        data->frame_waited = false;
        data->frame_begun = false;
        InstanceData& instance = *rt.instances.find(data->instance);
        queue_state(instance, session, *data, XR_SESSION_STATE_IDLE);
        queue_state(instance, session, *data, XR_SESSION_STATE_EXITING);
        return XR_SUCCESS;
    });
}

XrResult xrRequestExitSession(XrSession session) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!data->running) return XR_ERROR_SESSION_NOT_RUNNING;
        queue_stopping(*rt.instances.find(data->instance), session, *data);
        return XR_SUCCESS;
    });
}

XrResult xrWaitFrame(XrSession session, const XrFrameWaitInfo* frameWaitInfo,
                     XrFrameState* frameState) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if ((frameWaitInfo != nullptr && frameWaitInfo->type != XR_TYPE_FRAME_WAIT_INFO) ||
            !has_type(frameState, XR_TYPE_FRAME_STATE)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!data->running) return XR_ERROR_SESSION_NOT_RUNNING;
        InstanceData& instance = *rt.instances.find(data->instance);
        if (data->vulkan == nullptr && !instance.display.headless_frame_loop) {
            // No frame loop: no display time, and no frame to begin. The scene ends by the
            // monotonic clock.
            frameState->predictedDisplayTime = 0;
            frameState->predictedDisplayPeriod = 0;
            frameState->shouldRender = XR_FALSE;
            timespec now{};
            clock_gettime(CLOCK_MONOTONIC, &now);
            const XrTime time =
                instance.display.from_monotonic(now.tv_sec * 1'000'000'000LL + now.tv_nsec);
            if (instance.scene && scene_time(time) > instance.scene->duration_s) {
                queue_stopping(instance, session, *data);
            }
            return XR_SUCCESS;
        }
        // A real runtime would block this second wait until xrBeginFrame; with nothing to
        // wait for, blocking would deadlock a single-threaded application instead.
        if (data->frame_waited) return XR_ERROR_CALL_ORDER_INVALID;
        data->frame_waited = true;
        const XrTime display_time = instance.display.display_time(instance.frames_waited);
        ++instance.frames_waited;
        frameState->predictedDisplayTime = display_time;
        frameState->predictedDisplayPeriod = instance.display.period_ns;
        frameState->shouldRender =
            data->state == XR_SESSION_STATE_VISIBLE || data->state == XR_SESSION_STATE_FOCUSED;
        if ((instance.scene && scene_time(display_time) > instance.scene->duration_s) ||
            (instance.end_after_frame &&
             instance.display.frame_slot(display_time) > *instance.end_after_frame)) {
            queue_stopping(instance, session, *data);
        }
        return XR_SUCCESS;
    });
}

XrResult xrBeginFrame(XrSession session, const XrFrameBeginInfo* frameBeginInfo) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (frameBeginInfo != nullptr && frameBeginInfo->type != XR_TYPE_FRAME_BEGIN_INFO) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!data->running) return XR_ERROR_SESSION_NOT_RUNNING;
        if (!data->frame_waited) return XR_ERROR_CALL_ORDER_INVALID;
        data->frame_waited = false;
        // Beginning over an unended frame discards that frame.
        if (data->frame_begun) return XR_FRAME_DISCARDED;
        data->frame_begun = true;
        return XR_SUCCESS;
    });
}

XrResult xrEndFrame(XrSession session, const XrFrameEndInfo* frameEndInfo) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(frameEndInfo, XR_TYPE_FRAME_END_INFO) ||
            (frameEndInfo->layerCount > 0 && frameEndInfo->layers == nullptr)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!data->running) return XR_ERROR_SESSION_NOT_RUNNING;
        if (!data->frame_begun) return XR_ERROR_CALL_ORDER_INVALID;
        if (frameEndInfo->displayTime <= 0) return XR_ERROR_TIME_INVALID;
        if (frameEndInfo->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE) {
            return XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED;
        }
        if (XrResult result = check_layers(rt, session, *frameEndInfo); XR_FAILED(result)) {
            return result;
        }
        data->frame_begun = false;
        capture_frame(rt, session, *frameEndInfo);
        return XR_SUCCESS;
    });
}

}  // namespace physhand::sim
