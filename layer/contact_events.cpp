#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <cmath>
#include <stdexcept>

#include "dispatch.h"
#include "layer_log.h"
#include "sessions.h"
#include "xr_util.h"

// The extension's contact events: the simulation's log of hand-collider contacts, turned on
// per session and read by the app in its own spaces.
namespace physhand::layer {

namespace {

XrPhysicalContactEventKindPHYSHAND to_xr(ContactEvent::Kind kind) {
    switch (kind) {
        case ContactEvent::Kind::Begin:
            return XR_PHYSICAL_CONTACT_EVENT_KIND_BEGIN_PHYSHAND;
        case ContactEvent::Kind::Persist:
            return XR_PHYSICAL_CONTACT_EVENT_KIND_PERSIST_PHYSHAND;
        case ContactEvent::Kind::End:
            break;
    }
    return XR_PHYSICAL_CONTACT_EVENT_KIND_END_PHYSHAND;
}

// The app's handle of a simulation collider; XR_NULL_HANDLE for the config file's own
// colliders and those destroyed since.
XrPhysicalColliderPHYSHAND app_handle(const SessionState& state, ColliderHandle collider) {
    for (const auto& [handle, record] : state.colliders) {
        if (record.handle == collider) return handle;
    }
    return XR_NULL_HANDLE;
}

}  // namespace

XRAPI_ATTR XrResult XRAPI_CALL SetPhysicalContactReportingPHYSHAND(
    XrSession session, const XrPhysicalContactReportingInfoPHYSHAND* reportingInfo) {
    return guarded("xrSetPhysicalContactReportingPHYSHAND", [&] {
        LockedSession locked = lock_session(find_session(session));
        if (XR_FAILED(locked.result)) return locked.result;
        if (reportingInfo == nullptr ||
            reportingInfo->type != XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND ||
            reportingInfo->eventCapacity > ContactEventLog::kMaxCapacity) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const std::size_t capacity = reportingInfo->eventCapacity == 0
                                         ? ContactEventLog::kDefaultCapacity
                                         : reportingInfo->eventCapacity;
        locked.state->simulation->contact_events().enable(
            reportingInfo->persistEvents != XR_FALSE, capacity,
            reportingInfo->colliderContacts != XR_FALSE);
        return XR_SUCCESS;
    });
}

XRAPI_ATTR XrResult XRAPI_CALL GetPhysicalContactEventsPHYSHAND(
    XrSession session, const XrPhysicalContactEventsGetInfoPHYSHAND* getInfo,
    XrPhysicalContactEventsPHYSHAND* events) {
    return guarded("xrGetPhysicalContactEventsPHYSHAND", [&] {
        LockedSession locked = lock_session(find_session(session));
        if (XR_FAILED(locked.result)) return locked.result;
        if (getInfo == nullptr || events == nullptr ||
            getInfo->type != XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND ||
            events->type != XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND ||
            (events->eventCapacityInput > 0 && events->events == nullptr)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        SessionState& state = *locked.state;
        Pose frame;
        XrSpaceLocationFlags flags = 0;
        const XrResult result =
            state.frame_in_space(getInfo->baseSpace, getInfo->time, frame, flags);
        if (XR_FAILED(result)) return result;
        if ((flags & kPoseValid) != kPoseValid) return XR_ERROR_POSE_INVALID;
        ContactEventLog& log = state.simulation->contact_events();
        if (!log.enabled()) log.enable(false, ContactEventLog::kDefaultCapacity);
        const std::size_t count = log.events().size();
        events->eventCountOutput = static_cast<std::uint32_t>(count);
        events->lostEventCount =
            static_cast<std::uint32_t>(std::min<std::uint64_t>(log.lost(), UINT32_MAX));
        if (events->eventCapacityInput == 0) return XR_SUCCESS;
        if (events->eventCapacityInput < count) return XR_ERROR_SIZE_INSUFFICIENT;
        const XrTime epoch = state.epoch.value_or(0);
        for (std::size_t i = 0; i < count; ++i) {
            const ContactEvent& e = log.events()[i];
            XrPhysicalContactEventPHYSHAND& out = events->events[i];
            out.kind = to_xr(e.kind);
            const bool hand = e.other == 0;
            out.hand = !hand                      ? static_cast<XrHandEXT>(0)
                       : e.hand == HandSide::Left ? XR_HAND_LEFT_EXT
                                                  : XR_HAND_RIGHT_EXT;
            out.joint = static_cast<XrHandJointEXT>(index_of(e.joint));
            out.collider = app_handle(state, e.collider);
            out.otherCollider = hand ? XR_NULL_HANDLE : app_handle(state, e.other);
            out.time = epoch + static_cast<XrTime>(std::llround(e.time_s * 1e9));
            out.point = to_xr(frame * e.point);
            out.normal = to_xr(frame.orientation * e.normal);
            out.impulse = static_cast<float>(e.impulse);
            out.linearImpulse = to_xr(frame.orientation * e.impulse_on_collider);
            out.approachSpeed = static_cast<float>(e.approach_speed);
        }
        log.drop_oldest(count);
        log.clear_lost();
        return result;
    });
}

}  // namespace physhand::layer
