#include <openxr/openxr.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "dispatch.h"
#include "frame_clock.h"
#include "layer_log.h"
#include "recording.h"
#include "sessions.h"
#include "xr_util.h"

// xrLocateHandJointsEXT returns the physical hand: the runtime's hand (the ghost) drives
// the session's simulation, and the app gets the simulated joints.
namespace physhand::layer {

namespace {

constexpr std::pair<Joint, XrHandJointEXT> kJointPairs[] = {
    {Joint::Palm, XR_HAND_JOINT_PALM_EXT},
    {Joint::Wrist, XR_HAND_JOINT_WRIST_EXT},
    {Joint::ThumbMetacarpal, XR_HAND_JOINT_THUMB_METACARPAL_EXT},
    {Joint::ThumbProximal, XR_HAND_JOINT_THUMB_PROXIMAL_EXT},
    {Joint::ThumbDistal, XR_HAND_JOINT_THUMB_DISTAL_EXT},
    {Joint::ThumbTip, XR_HAND_JOINT_THUMB_TIP_EXT},
    {Joint::IndexMetacarpal, XR_HAND_JOINT_INDEX_METACARPAL_EXT},
    {Joint::IndexProximal, XR_HAND_JOINT_INDEX_PROXIMAL_EXT},
    {Joint::IndexIntermediate, XR_HAND_JOINT_INDEX_INTERMEDIATE_EXT},
    {Joint::IndexDistal, XR_HAND_JOINT_INDEX_DISTAL_EXT},
    {Joint::IndexTip, XR_HAND_JOINT_INDEX_TIP_EXT},
    {Joint::MiddleMetacarpal, XR_HAND_JOINT_MIDDLE_METACARPAL_EXT},
    {Joint::MiddleProximal, XR_HAND_JOINT_MIDDLE_PROXIMAL_EXT},
    {Joint::MiddleIntermediate, XR_HAND_JOINT_MIDDLE_INTERMEDIATE_EXT},
    {Joint::MiddleDistal, XR_HAND_JOINT_MIDDLE_DISTAL_EXT},
    {Joint::MiddleTip, XR_HAND_JOINT_MIDDLE_TIP_EXT},
    {Joint::RingMetacarpal, XR_HAND_JOINT_RING_METACARPAL_EXT},
    {Joint::RingProximal, XR_HAND_JOINT_RING_PROXIMAL_EXT},
    {Joint::RingIntermediate, XR_HAND_JOINT_RING_INTERMEDIATE_EXT},
    {Joint::RingDistal, XR_HAND_JOINT_RING_DISTAL_EXT},
    {Joint::RingTip, XR_HAND_JOINT_RING_TIP_EXT},
    {Joint::LittleMetacarpal, XR_HAND_JOINT_LITTLE_METACARPAL_EXT},
    {Joint::LittleProximal, XR_HAND_JOINT_LITTLE_PROXIMAL_EXT},
    {Joint::LittleIntermediate, XR_HAND_JOINT_LITTLE_INTERMEDIATE_EXT},
    {Joint::LittleDistal, XR_HAND_JOINT_LITTLE_DISTAL_EXT},
    {Joint::LittleTip, XR_HAND_JOINT_LITTLE_TIP_EXT},
};

// Joint arrays are copied between the physics and OpenXR by index.
constexpr bool joints_match() {
    for (const auto& [joint, xr_joint] : kJointPairs) {
        if (static_cast<int>(joint) != static_cast<int>(xr_joint)) return false;
    }
    return std::size(kJointPairs) == kJointCount;
}
static_assert(kJointCount == XR_HAND_JOINT_COUNT_EXT);
static_assert(joints_match(), "physhand::Joint must equal XrHandJointEXT, joint by joint");

using JointLocations = std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT>;

struct GhostSample {
    bool active = false;
    JointLocations joints{};
};

std::size_t side_index(HandSide side) {
    return static_cast<std::size_t>(side);
}

// The runtime's hand in the layer's frame. A failed call or a joint without a valid pose
// makes the hand inactive, which the simulation treats as tracking loss.
GhostSample sample_ghost(const SessionState& session, XrHandTrackerEXT tracker, XrTime time) {
    GhostSample sample;
    XrHandJointsLocateInfoEXT info{};
    info.type = XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT;
    info.baseSpace = session.frame;
    info.time = time;
    XrHandJointLocationsEXT locations{};
    locations.type = XR_TYPE_HAND_JOINT_LOCATIONS_EXT;
    locations.jointCount = XR_HAND_JOINT_COUNT_EXT;
    locations.jointLocations = sample.joints.data();
    const XrResult result = session.instance->next.LocateHandJointsEXT(tracker, &info, &locations);
    if (XR_FAILED(result)) {
        log_once("sampling the tracked hand failed with XrResult " + std::to_string(result) +
                 "; the hand counts as not tracked");
        return {};
    }
    sample.active =
        locations.isActive && std::all_of(sample.joints.begin(), sample.joints.end(),
                                          [](const XrHandJointLocationEXT& j) {
                                              return (j.locationFlags & kPoseValid) == kPoseValid;
                                          });
    return sample;
}

HandPose to_hand_pose(const GhostSample& sample) {
    HandPose hand;
    hand.active = sample.active;
    for (std::size_t i = 0; i < kJointCount; ++i) {
        hand.joints[i] = to_pose(sample.joints[i].pose);
        hand.radii[i] = sample.joints[i].radius;
    }
    return hand;
}

// Takes the layer's own structure out of an output chain for the call down (the runtime
// does not know it) and puts it back when done.
class ChainSplice {
  public:
    ChainSplice(void* head, XrStructureType type) : prev_(static_cast<XrBaseOutStructure*>(head)) {
        for (; prev_->next != nullptr; prev_ = prev_->next) {
            if (prev_->next->type == type) {
                removed_ = prev_->next;
                prev_->next = removed_->next;
                return;
            }
        }
    }
    ~ChainSplice() {
        if (removed_ != nullptr) prev_->next = removed_;
    }
    ChainSplice(const ChainSplice&) = delete;
    ChainSplice& operator=(const ChainSplice&) = delete;

    XrBaseOutStructure* removed() const { return removed_; }

  private:
    XrBaseOutStructure* prev_;
    XrBaseOutStructure* removed_ = nullptr;
};

// A call the layer answers in full: the 26 joints asked for (and their velocities, if),
// nothing chained to the locate info (such as XR_EXT_hand_joints_motion_range, which changes
// what the runtime reports in ways the physical hand does not model). Anything else gets the
// runtime's answer alone, as the runtime gave it.
bool is_default_locate(const XrHandJointsLocateInfoEXT& info,
                       const XrHandJointLocationsEXT& locations,
                       const XrHandJointVelocitiesEXT* velocities) {
    return info.next == nullptr && locations.jointCount == XR_HAND_JOINT_COUNT_EXT &&
           locations.jointLocations != nullptr &&
           (velocities == nullptr || (velocities->jointCount == XR_HAND_JOINT_COUNT_EXT &&
                                      velocities->jointVelocities != nullptr));
}

// The runtime's answer, as the ghost; the hand counts as not simulated until shown to be.
// Another joint set's poses are not the ghost's joints, so they are not reported as such.
void report_ghost(const XrHandJointLocationsEXT& locations,
                  XrHandJointsPhysicalStatePHYSHAND& physical) {
    physical.ghostIsActive = locations.isActive;
    physical.isSimulated = XR_FALSE;
    const bool ghost_joints =
        locations.jointCount == XR_HAND_JOINT_COUNT_EXT && locations.jointLocations != nullptr;
    for (std::size_t i = 0; i < kJointCount; ++i) {
        if (physical.ghostPoses != nullptr && ghost_joints)
            physical.ghostPoses[i] = locations.jointLocations[i].pose;
        if (physical.inContact != nullptr) physical.inContact[i] = XR_FALSE;
        if (physical.springForce != nullptr) physical.springForce[i] = 0.0f;
    }
}

void report_contacts(const PhysicalHandState& hand, XrHandJointsPhysicalStatePHYSHAND& physical) {
    physical.isSimulated = XR_TRUE;
    for (std::size_t i = 0; i < kJointCount; ++i) {
        if (physical.inContact != nullptr)
            physical.inContact[i] = hand.in_contact[i] ? XR_TRUE : XR_FALSE;
        if (physical.springForce != nullptr) {
            physical.springForce[i] = static_cast<float>(hand.drive_force[i]);
        }
    }
}

XrHandCollisionShapeKindPHYSHAND shape_kind(HandSolid::Kind kind) {
    switch (kind) {
        case HandSolid::Kind::Capsule:
            return XR_HAND_COLLISION_SHAPE_KIND_CAPSULE_PHYSHAND;
        case HandSolid::Kind::Box:
            return XR_HAND_COLLISION_SHAPE_KIND_BOX_PHYSHAND;
        case HandSolid::Kind::Sphere:
            break;
    }
    return XR_HAND_COLLISION_SHAPE_KIND_SPHERE_PHYSHAND;
}

// The hand's bodies in the app's base space (`frame`: the layer's frame there), by the
// two-call idiom.
XrResult write_shapes(const HandSolids& solids, const Pose& frame,
                      XrHandCollisionShapesPHYSHAND& out) {
    out.shapeCountOutput = static_cast<uint32_t>(solids.count);
    if (out.shapeCapacityInput == 0) return XR_SUCCESS;
    if (out.shapeCapacityInput < solids.count) return XR_ERROR_SIZE_INSUFFICIENT;
    for (std::size_t i = 0; i < solids.count; ++i) {
        const HandSolid& solid = solids.parts[i];
        XrHandCollisionShapePHYSHAND& shape = out.shapes[i];
        shape.kind = shape_kind(solid.kind);
        shape.pose = to_xr(frame * solid.pose);
        shape.size = to_xr(solid.size);
        shape.inContact = solid.in_contact ? XR_TRUE : XR_FALSE;
    }
    return XR_SUCCESS;
}

// The simulated joints in the app's base space; `frame` is the layer's frame there.
void write_physical(const PhysicalHandState& hand, const Pose& frame, XrSpaceLocationFlags flags,
                    bool ghost_active, XrHandJointLocationsEXT& locations,
                    XrHandJointVelocitiesEXT* velocities) {
    const bool active = hand.joints.active && (flags & kPoseValid) == kPoseValid;
    // A hand held still through a tracking dropout is valid, but not tracked.
    const XrSpaceLocationFlags joint_flags =
        !active ? 0 : (ghost_active ? flags : flags & ~kPoseTracked);
    locations.isActive = active ? XR_TRUE : XR_FALSE;
    for (std::size_t i = 0; i < kJointCount; ++i) {
        XrHandJointLocationEXT& out = locations.jointLocations[i];
        out.locationFlags = joint_flags;
        if (!active) continue;
        out.pose = to_xr(frame * hand.joints.joints[i]);
        out.radius = static_cast<float>(hand.joints.radii[i]);
    }
    if (velocities == nullptr) return;
    for (std::size_t i = 0; i < kJointCount; ++i) {
        XrHandJointVelocityEXT& out = velocities->jointVelocities[i];
        out.velocityFlags =
            active ? XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT : 0;
        if (!active) continue;
        out.linearVelocity = to_xr(frame.orientation * hand.linear_velocity[i]);
        out.angularVelocity = to_xr(frame.orientation * hand.angular_velocity[i]);
    }
}

}  // namespace

void SessionState::advance(XrTime time) {
    // Compared as XrTime: the simulation's own clock is rounded to its substeps, so a
    // repeated time can look later than it and would sample the hands again for nothing.
    if (epoch && time <= advanced_to) return;
    if (!epoch) {
        // Physics frames fall on whole periods of the runtime's clock, so the same tracking
        // gives the same physics whatever the display rate and wherever its first frame falls.
        const std::int64_t period = frame_period_ns(simulation->settings().frame_rate_hz);
        const XrTime aligned = time - ((time % period) + period) % period;
        // XrTime 0 is no time at all: a clock under a period from its origin starts on time.
        epoch = aligned > 0 ? aligned : time;
    }
    advanced_to = time;
    // Seconds since the epoch: XrTime counts nanoseconds from an arbitrary origin, too large
    // for the simulation's double seconds to stay exact.
    const double t = clock_seconds(time - *epoch);
    // Each physics frame samples the runtime at its own time, and the display time last,
    // so the physics is the same whatever rate the app displays at (Simulation::step_sampling).
    simulation->step_sampling(t, [&](double sample_t) {
        // Whole nanoseconds, as both the display time and physics frames are.
        const XrTime at = *epoch + std::llround(sample_t * 1e9);
        ghosts = {};
        for (const HandSide side : kHandSides) {
            const std::vector<XrHandTrackerEXT>& side_trackers = trackers[side_index(side)];
            // The app's own tracker first, so that its results never depend on the layer's.
            const XrHandTrackerEXT tracker =
                side_trackers.empty() ? own_trackers[side_index(side)] : side_trackers.front();
            if (tracker == XR_NULL_HANDLE) continue;  // never tracked: stays inactive
            // Both hands at the same time, whichever hand the app asked for.
            const GhostSample sample = sample_ghost(*this, tracker, at);
            ghosts[side_index(side)] = to_hand_pose(sample);
            if (recorder) recorder->write(side, sample_t, sample.joints);
        }
        return ghosts;
    });
}

XRAPI_ATTR XrResult XRAPI_CALL CreateHandTrackerEXT(XrSession session,
                                                    const XrHandTrackerCreateInfoEXT* createInfo,
                                                    XrHandTrackerEXT* handTracker) {
    return guarded("xrCreateHandTrackerEXT", [&] {
        const std::shared_ptr<SessionState> state = find_session(session);
        if (!state) return XR_ERROR_HANDLE_INVALID;
        const XrResult result =
            state->instance->next.CreateHandTrackerEXT(session, createInfo, handTracker);
        if (XR_FAILED(result)) return result;
        // The runtime accepted createInfo, so it is valid.
        const HandSide side =
            createInfo->hand == XR_HAND_LEFT_EXT ? HandSide::Left : HandSide::Right;
        const bool simulated = createInfo->handJointSet == XR_HAND_JOINT_SET_DEFAULT_EXT &&
                               createInfo->next == nullptr;
        try {
            add_tracker(*handTracker, {state, side, simulated});
            std::lock_guard lock(state->mutex);
            if (simulated) state->trackers[side_index(side)].push_back(*handTracker);
        } catch (...) {
            remove_tracker(*handTracker);
            state->instance->next.DestroyHandTrackerEXT(*handTracker);
            *handTracker = XR_NULL_HANDLE;
            throw;
        }
        return result;
    });
}

XRAPI_ATTR XrResult XRAPI_CALL DestroyHandTrackerEXT(XrHandTrackerEXT handTracker) {
    return guarded("xrDestroyHandTrackerEXT", [&] {
        const std::optional<TrackerRef> ref = find_tracker(handTracker);
        if (!ref) return XR_ERROR_HANDLE_INVALID;
        remove_tracker(handTracker);
        {
            std::lock_guard lock(ref->session->mutex);
            std::erase(ref->session->trackers[side_index(ref->side)], handTracker);
        }
        return ref->session->instance->next.DestroyHandTrackerEXT(handTracker);
    });
}

XRAPI_ATTR XrResult XRAPI_CALL LocateHandJointsEXT(XrHandTrackerEXT handTracker,
                                                   const XrHandJointsLocateInfoEXT* locateInfo,
                                                   XrHandJointLocationsEXT* locations) {
    return guarded("xrLocateHandJointsEXT", [&] {
        const std::optional<TrackerRef> ref = find_tracker(handTracker);
        if (!ref) return XR_ERROR_HANDLE_INVALID;
        if (locateInfo == nullptr || locations == nullptr ||
            locateInfo->type != XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT ||
            locations->type != XR_TYPE_HAND_JOINT_LOCATIONS_EXT) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        SessionState& session = *ref->session;

        // The runtime answers in the app's own terms first: that is the ghost, and, for a
        // hand the layer does not simulate, exactly what the app gets.
        XrHandJointsPhysicalStatePHYSHAND* physical = nullptr;
        XrHandCollisionShapesPHYSHAND* shapes = nullptr;
        XrResult result;
        {
            const ChainSplice state_splice(locations, XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND);
            const ChainSplice shapes_splice(locations, XR_TYPE_HAND_COLLISION_SHAPES_PHYSHAND);
            physical = reinterpret_cast<XrHandJointsPhysicalStatePHYSHAND*>(state_splice.removed());
            shapes = reinterpret_cast<XrHandCollisionShapesPHYSHAND*>(shapes_splice.removed());
            if ((physical != nullptr && physical->jointCount != XR_HAND_JOINT_COUNT_EXT) ||
                (shapes != nullptr && shapes->shapeCapacityInput > 0 &&
                 shapes->shapes == nullptr)) {
                return XR_ERROR_VALIDATION_FAILURE;
            }
            result = session.instance->next.LocateHandJointsEXT(handTracker, locateInfo, locations);
        }
        if (XR_FAILED(result)) return result;
        if (physical != nullptr) report_ghost(*locations, *physical);
        if (shapes != nullptr) shapes->shapeCountOutput = 0;
        auto* velocities = find_in_chain<XrHandJointVelocitiesEXT>(
            locations->next, XR_TYPE_HAND_JOINT_VELOCITIES_EXT);
        if (!ref->simulated || !is_default_locate(*locateInfo, *locations, velocities)) {
            return result;
        }

        std::lock_guard lock(session.mutex);
        if (!session.alive || !session.simulation) return result;
        session.advance(locateInfo->time);
        const PhysicalHandState& hand = session.simulation->hand(ref->side);
        if (!hand.simulated && shapes == nullptr) return result;
        Pose frame;
        XrSpaceLocationFlags flags = 0;
        const XrResult located =
            session.frame_in_space(locateInfo->baseSpace, locateInfo->time, frame, flags);
        if (XR_FAILED(located)) return located;
        if (shapes != nullptr && (flags & kPoseValid) == kPoseValid) {
            const XrResult written =
                write_shapes(session.simulation->hand_solids(ref->side), frame, *shapes);
            if (XR_FAILED(written)) return written;
        }
        if (!hand.simulated) return result;
        if (physical != nullptr) report_contacts(hand, *physical);
        write_physical(hand, frame, flags, locations->isActive, *locations, velocities);
        return result;
    });
}

}  // namespace physhand::layer
