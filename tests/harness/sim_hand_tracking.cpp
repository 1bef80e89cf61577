// XR_EXT_hand_tracking: the tracked hands of the scene (physhand::TrackedHands, the same
// ghost hands the physics-only runner sees), expressed in the caller's base space.

#include <Eigen/Geometry>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

// physics/ numbers its joints as XR_EXT_hand_tracking does, so joint i is reported as is.
static_assert(kJointCount == XR_HAND_JOINT_COUNT_EXT);
static_assert(index_of(Joint::Palm) == XR_HAND_JOINT_PALM_EXT &&
              index_of(Joint::Wrist) == XR_HAND_JOINT_WRIST_EXT &&
              index_of(Joint::ThumbTip) == XR_HAND_JOINT_THUMB_TIP_EXT &&
              index_of(Joint::LittleTip) == XR_HAND_JOINT_LITTLE_TIP_EXT);

// Step of the backward difference that gives joint velocities.
constexpr double kVelocityStep = 1e-3;

// The angular velocity that turns `from` into `to` in `dt`, in the frame both are given in.
Vec3 angular_velocity(const Quat& from, const Quat& to, double dt) {
    Quat delta = to * from.conjugate();
    if (delta.w() < 0) delta.coeffs() = -delta.coeffs();  // the shorter way round
    Eigen::AngleAxisd rotation(delta);
    return rotation.axis() * (rotation.angle() / dt);
}

bool has_joint_array(uint32_t count, const void* joints) {
    return count == XR_HAND_JOINT_COUNT_EXT && joints != nullptr;
}

}  // namespace

XrResult xrCreateHandTrackerEXT(XrSession session, const XrHandTrackerCreateInfoEXT* createInfo,
                                XrHandTrackerEXT* handTracker) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT) || handTracker == nullptr ||
            createInfo->handJointSet != XR_HAND_JOINT_SET_DEFAULT_EXT) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        HandSide side;
        switch (createInfo->hand) {
            case XR_HAND_LEFT_EXT:
                side = HandSide::Left;
                break;
            case XR_HAND_RIGHT_EXT:
                side = HandSide::Right;
                break;
            default:
                return XR_ERROR_VALIDATION_FAILURE;
        }
        *handTracker = rt.hand_trackers.add({session, side});
        return XR_SUCCESS;
    });
}

XrResult xrDestroyHandTrackerEXT(XrHandTrackerEXT handTracker) {
    return guarded([&](Runtime& rt) {
        if (rt.hand_trackers.find(handTracker) == nullptr) return XR_ERROR_HANDLE_INVALID;
        rt.hand_trackers.erase(handTracker);
        return XR_SUCCESS;
    });
}

XrResult xrLocateHandJointsEXT(XrHandTrackerEXT handTracker,
                               const XrHandJointsLocateInfoEXT* locateInfo,
                               XrHandJointLocationsEXT* locations) {
    return guarded([&](Runtime& rt) {
        const HandTrackerData* tracker = rt.hand_trackers.find(handTracker);
        if (tracker == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(locateInfo, XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT) ||
            !has_type(locations, XR_TYPE_HAND_JOINT_LOCATIONS_EXT)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const SpaceData* base = rt.spaces.find(locateInfo->baseSpace);
        if (base == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (base->session != tracker->session) return XR_ERROR_VALIDATION_FAILURE;
        if (locateInfo->time <= 0) return XR_ERROR_TIME_INVALID;
        auto* velocities = find_in_chain<XrHandJointVelocitiesEXT>(
            locations->next, XR_TYPE_HAND_JOINT_VELOCITIES_EXT);
        if (!has_joint_array(locations->jointCount, locations->jointLocations) ||
            (velocities != nullptr &&
             !has_joint_array(velocities->jointCount, velocities->jointVelocities))) {
            return XR_ERROR_VALIDATION_FAILURE;
        }

        const InstanceData& instance =
            *rt.instances.find(rt.sessions.find(tracker->session)->instance);
        const double t = scene_time(locateInfo->time);
        HandPose hand;  // inactive unless the scene tracks this hand now
        if (instance.scene) hand = instance.scene->hands.ghost(tracker->side, t);
        std::optional<Pose> base_pose = space_in_stage(*base);
        const bool located = hand.active && base_pose.has_value();
        const Pose stage_to_base = base_pose ? base_pose->inverse() : Pose{};

        locations->isActive = hand.active ? XR_TRUE : XR_FALSE;
        for (std::size_t i = 0; i < kJointCount; ++i) {
            XrHandJointLocationEXT& out = locations->jointLocations[i];
            out.locationFlags = located ? kLocatedFlags : 0;
            out.pose = to_xr(located ? stage_to_base * hand.joints[i] : Pose{});
            out.radius = located ? static_cast<float>(hand.radii[i]) : 0.0f;
        }
        if (velocities == nullptr) return XR_SUCCESS;

        HandPose before;
        if (located) before = instance.scene->hands.ghost(tracker->side, t - kVelocityStep);
        const bool has_velocity = located && before.active;
        for (std::size_t i = 0; i < kJointCount; ++i) {
            XrHandJointVelocityEXT& out = velocities->jointVelocities[i];
            Vec3 linear = Vec3::Zero();
            Vec3 angular = Vec3::Zero();
            if (has_velocity) {
                const Pose &now = hand.joints[i], &then = before.joints[i];
                linear = (now.position - then.position) / kVelocityStep;
                angular = angular_velocity(then.orientation, now.orientation, kVelocityStep);
            }
            out.velocityFlags = has_velocity ? kVelocityFlags : 0;
            out.linearVelocity = to_xr(stage_to_base.orientation * linear);
            out.angularVelocity = to_xr(stage_to_base.orientation * angular);
        }
        return XR_SUCCESS;
    });
}

}  // namespace physhand::sim
