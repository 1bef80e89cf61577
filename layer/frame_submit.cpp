#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dispatch.h"
#include "layer_log.h"
#include "overlay_hands.h"
#include "overlay_session.h"
#include "sessions.h"
#include "xr_util.h"

// xrEndFrame: the simulation steps to the frame's time, and the overlay of the hands is
// composited over the app's layers.
namespace physhand::layer {

namespace {

const XrCompositionLayerProjection* find_projection(const XrFrameEndInfo& info) {
    for (uint32_t i = 0; i < info.layerCount; ++i) {
        const XrCompositionLayerBaseHeader* layer = info.layers[i];
        if (layer != nullptr && layer->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION) {
            const auto* projection = reinterpret_cast<const XrCompositionLayerProjection*>(layer);
            if (projection->viewCount > 0 && projection->views != nullptr) return projection;
        }
    }
    return nullptr;
}

// The hands as the frame's step left them, copied under the session's lock for the overlay
// to draw after it is released.
struct FrameHands {
    std::array<HandPose, 2> ghosts;
    std::array<HandPose, 2> physical;
    std::array<HandSolids, 2> solids;
};

// Null when there is nothing to draw. Session locked.
std::optional<FrameHands> frame_hands(const SessionState& state) {
    if (!state.simulation) return std::nullopt;
    FrameHands hands;
    bool any_active = false;
    for (const HandSide side : kHandSides) {
        const auto i = static_cast<std::size_t>(side);
        const PhysicalHandState& physical = state.simulation->hand(side);
        hands.ghosts[i] = state.ghosts[i];
        hands.physical[i] = physical.joints;
        hands.solids[i] = state.simulation->hand_solids(side);
        any_active = any_active || hands.ghosts[i].active || physical.joints.active;
    }
    if (!any_active) return std::nullopt;
    return hands;
}

// The overlay layer for this frame, or null when there is no room for it or it cannot be
// placed. Overlay locked. Throws on any failure.
const XrCompositionLayerProjection* draw_overlay(SessionState& state, const XrFrameEndInfo& info,
                                                 const FrameHands& frame_hands) {
    if (info.layerCount >= state.graphics.maxLayerCount || info.displayTime <= 0 ||
        (info.layerCount > 0 && info.layers == nullptr)) {
        return nullptr;
    }
    const XrCompositionLayerProjection* app_layer = find_projection(info);
    if (app_layer == nullptr) return nullptr;
    Pose frame;
    XrSpaceLocationFlags flags = 0;
    if (XR_FAILED(state.frame_in_space(app_layer->space, info.displayTime, frame, flags)) ||
        (flags & kPoseValid) != kPoseValid) {
        return nullptr;
    }
    std::array<overlay::Hand, 2> hands;
    for (const HandSide side : kHandSides) {
        const auto i = static_cast<std::size_t>(side);
        hands[i].ghost_active = frame_hands.ghosts[i].active;
        hands[i].physical_active = frame_hands.physical[i].active;
        hands[i].ghost = to_overlay(frame_hands.ghosts[i], frame);
        hands[i].physical = to_overlay(frame_hands.physical[i], frame);
        hands[i].solids = to_overlay(frame_hands.solids[i], frame);
        hands[i].solid_count = static_cast<uint32_t>(frame_hands.solids[i].count);
    }
    // Created with the first frame that has hands to draw: sessions without them pay nothing.
    if (!state.overlay) {
        state.overlay = std::make_unique<OverlaySession>(
            state.instance->next, state.session, *state.vulkan, state.graphics,
            state.recommended_views, state.instance->config.drawing);
    }
    return state.overlay->draw(*app_layer, hands);
}

// Turns the overlay off for the rest of the session, saying why once. Overlay locked.
void turn_overlay_off(SessionState& state, const char* why) {
    log_failure("xrEndFrame (the overlay is off for this session)", why);
    state.overlay.reset();
    state.vulkan.reset();
}

// Points `submitted` at the app's layers with the overlay's after them, when it drew one;
// returns whether it did. Overlay locked. Any failure turns the overlay off for the
// session; the app's frame then goes through unchanged, now and from now on.
bool append_overlay(SessionState& state, const XrFrameEndInfo& info, const FrameHands& hands,
                    XrFrameEndInfo& submitted) {
    const auto start = std::chrono::steady_clock::now();
    try {
        const XrCompositionLayerProjection* layer = draw_overlay(state, info, hands);
        if (layer == nullptr) return false;
        // A copy: the app's array is never modified.
        state.submitted_layers.assign(info.layers, info.layers + info.layerCount);
        state.submitted_layers.push_back(
            reinterpret_cast<const XrCompositionLayerBaseHeader*>(layer));
        submitted.layers = state.submitted_layers.data();
        submitted.layerCount = static_cast<uint32_t>(state.submitted_layers.size());
        state.overlay->record_drawn_frame(std::chrono::steady_clock::now() - start);
        return true;
    } catch (const std::exception& e) {
        turn_overlay_off(state, e.what());
    } catch (...) {
        turn_overlay_off(state, "unknown exception");
    }
    submitted = info;
    return false;
}

// Errors the app's own frame gets just the same, whatever the overlay appended to it: the
// session's state or the call's order, not the layers.
bool is_frame_independent(XrResult result) {
    switch (result) {
        case XR_ERROR_SESSION_LOST:
        case XR_ERROR_INSTANCE_LOST:
        case XR_ERROR_SESSION_NOT_RUNNING:
        case XR_ERROR_CALL_ORDER_INVALID:
        case XR_ERROR_TIME_INVALID:
        case XR_ERROR_HANDLE_INVALID:
            return true;
        default:
            return false;
    }
}

// The app's frame goes through whatever happens to the layer's step.
void step_frame(SessionState& state, XrTime display_time) noexcept {
    try {
        state.step_frame(display_time);
    } catch (const std::exception& e) {
        log_failure("xrEndFrame (the frame's step)", e.what());
    } catch (...) {
        log_failure("xrEndFrame (the frame's step)", "unknown exception");
    }
}

}  // namespace

XRAPI_ATTR XrResult XRAPI_CALL EndFrame(XrSession session, const XrFrameEndInfo* frameEndInfo) {
    return guarded("xrEndFrame", [&] {
        const std::shared_ptr<SessionState> state = find_session(session);
        if (!state) return XR_ERROR_HANDLE_INVALID;
        if (frameEndInfo == nullptr) return state->instance->next.EndFrame(session, frameEndInfo);
        XrFrameEndInfo submitted = *frameEndInfo;
        bool appended = false;
        {
            std::lock_guard overlay_lock(state->overlay_mutex);
            std::optional<FrameHands> hands;
            {
                std::lock_guard lock(state->mutex);
                if (state->alive) {
                    step_frame(*state, frameEndInfo->displayTime);
                    if (state->vulkan) hands = frame_hands(*state);
                }
            }
            // Drawing waits for swapchain images and the GPU: the session's lock is free
            // meanwhile, so other threads' locates never wait for it.
            if (hands) appended = append_overlay(*state, *frameEndInfo, *hands, submitted);
        }
        // Unlocked: the runtime may block here, and other threads may locate hands meanwhile.
        // The app synchronises xrEndFrame with xrDestroySession, so the layers stay alive.
        const XrResult result = state->instance->next.EndFrame(session, &submitted);
        if (XR_SUCCEEDED(result) || !appended || is_frame_independent(result)) {
            return result;
        }
        // The runtime refused the frame with the overlay's layer: the app's own frame goes
        // in its place. When that succeeds, the overlay was at fault and is off from now on;
        // when it fails too, the app's frame was, and the app gets its own error.
        const XrResult resubmitted = state->instance->next.EndFrame(session, frameEndInfo);
        if (XR_SUCCEEDED(resubmitted)) {
            std::lock_guard lock(state->overlay_mutex);
            const std::string what =
                "the runtime refused the frame with the overlay's layer (XrResult " +
                std::to_string(result) + "); the app's frame was submitted alone";
            turn_overlay_off(*state, what.c_str());
        }
        return resubmitted;
    });
}

}  // namespace physhand::layer
