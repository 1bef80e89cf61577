#include <openxr/openxr.h>

#include <string>

#include "layer_log.h"
#include "sessions.h"

// The simulation's step once per frame, which apps that locate no hands (or not every
// frame) rely on for the overlay's hands and for a world that moves on.
namespace physhand::layer {

namespace {

XrHandTrackerEXT create_own_tracker(const SessionState& state, HandSide side) {
    XrHandTrackerCreateInfoEXT info{};
    info.type = XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT;
    info.hand = side == HandSide::Left ? XR_HAND_LEFT_EXT : XR_HAND_RIGHT_EXT;
    info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
    XrHandTrackerEXT tracker = XR_NULL_HANDLE;
    const XrResult result =
        state.instance->next.CreateHandTrackerEXT(state.session, &info, &tracker);
    if (XR_FAILED(result)) {
        log_once("xrEndFrame: the layer's own hand tracker failed with XrResult " +
                 std::to_string(result) + "; hands the app does not track stay inactive");
        return XR_NULL_HANDLE;
    }
    return tracker;
}

}  // namespace

// Called at xrEndFrame for its displayTime, not at xrWaitFrame for the predicted time:
// by xrEndFrame the app has moved its colliders, set its drive and located its hands for
// the frame (at that same time, so this steps nothing more), which keeps an app that
// locates hands getting exactly what it gets without this step; and displayTime is the
// time the overlay draws the hands for. At xrWaitFrame the frame's updates are still to
// come, and the wait may run on another thread than the app's frame.
void SessionState::step_frame(XrTime display_time) {
    if (!simulation || display_time <= 0) return;
    // Nothing would show the step: sessions without an overlay or colliders pay nothing.
    if (!vulkan && simulation->collider_count() == 0) return;
    for (const HandSide side : kHandSides) {
        const auto i = static_cast<std::size_t>(side);
        if (!hand_tracking || !trackers[i].empty() || own_trackers[i] != XR_NULL_HANDLE) continue;
        own_trackers[i] = create_own_tracker(*this, side);
        // Not tried again every frame once the runtime refused.
        if (own_trackers[i] == XR_NULL_HANDLE) hand_tracking = false;
    }
    advance(display_time);
}

void SessionState::destroy_own_trackers() noexcept {
    for (XrHandTrackerEXT& tracker : own_trackers) {
        if (tracker != XR_NULL_HANDLE) instance->next.DestroyHandTrackerEXT(tracker);
        tracker = XR_NULL_HANDLE;
    }
}

}  // namespace physhand::layer
