// XR_EXT_hand_tracking: the tracked hands of the scene (physhand::TrackedHands, the same
// ghost hands the physics-only runner sees), expressed in the caller's base space.

#include <Eigen/Geometry>
#include <algorithm>

#include "sim_joint_sets.h"
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

// The elbow of the forearm joint set: this far behind the wrist (+Z points away from the
// fingers), turned as the wrist is.
constexpr double kForearmLength = 0.25;

// How far apart thumb and index tips pinch fully, and stop pinching (XR_FB_hand_tracking_aim).
constexpr double kPinchClosed = 0.01;
constexpr double kPinchOpen = 0.06;

// Joint i of a joint set: the 26 of the default set, then the elbow.
Pose joint_in_set(const HandPose& hand, std::size_t i) {
    if (i < kJointCount) return hand.joints[i];
    return hand[Joint::Wrist] * Pose{Vec3(0, 0, kForearmLength), Quat::Identity()};
}

bool has_joint_array(uint32_t count, uint32_t expected, const void* joints) {
    return count == expected && joints != nullptr;
}

// XR_FB_hand_tracking_aim: aimed along the index finger's first bone, pinching as the thumb
// and index tips close.
void report_aim(const HandPose& hand, bool located, const Pose& stage_to_base,
                XrHandTrackingAimStateFB& aim) {
    aim.status = 0;
    aim.aimPose = to_xr(Pose{});
    aim.pinchStrengthIndex = aim.pinchStrengthMiddle = aim.pinchStrengthRing =
        aim.pinchStrengthLittle = 0.0f;
    if (!located) return;
    const double gap = (hand[Joint::ThumbTip].position - hand[Joint::IndexTip].position).norm();
    const double pinch = std::clamp((kPinchOpen - gap) / (kPinchOpen - kPinchClosed), 0.0, 1.0);
    aim.status = XR_HAND_TRACKING_AIM_COMPUTED_BIT_FB | XR_HAND_TRACKING_AIM_VALID_BIT_FB |
                 (pinch >= 1.0 ? XR_HAND_TRACKING_AIM_INDEX_PINCHING_BIT_FB : 0);
    aim.aimPose = to_xr(stage_to_base * hand[Joint::IndexProximal]);
    aim.pinchStrengthIndex = static_cast<float>(pinch);
}

}  // namespace

XrResult xrCreateHandTrackerEXT(XrSession session, const XrHandTrackerCreateInfoEXT* createInfo,
                                XrHandTrackerEXT* handTracker) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT) || handTracker == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const InstanceData& instance = *rt.instances.find(rt.sessions.find(session)->instance);
        uint32_t joint_count = XR_HAND_JOINT_COUNT_EXT;
        if (createInfo->handJointSet == kForearmJointSet && instance.forearm) {
            joint_count = kForearmJointCount;
        } else if (createInfo->handJointSet != XR_HAND_JOINT_SET_DEFAULT_EXT) {
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
        *handTracker = rt.hand_trackers.add({session, side, joint_count});
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
        const uint32_t count = tracker->joint_count;
        if (!has_joint_array(locations->jointCount, count, locations->jointLocations) ||
            (velocities != nullptr &&
             !has_joint_array(velocities->jointCount, count, velocities->jointVelocities))) {
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
        for (std::size_t i = 0; i < count; ++i) {
            const Pose joint = joint_in_set(hand, i);
            const double radius = hand.radii[i < kJointCount ? i : index_of(Joint::Wrist)];
            XrHandJointLocationEXT& out = locations->jointLocations[i];
            out.locationFlags = located ? kLocatedFlags : 0;
            out.pose = to_xr(located ? stage_to_base * joint : Pose{});
            out.radius = located ? static_cast<float>(radius) : 0.0f;
        }
        auto* aim = find_in_chain<XrHandTrackingAimStateFB>(locations->next,
                                                            XR_TYPE_HAND_TRACKING_AIM_STATE_FB);
        if (aim != nullptr && instance.hand_aim) report_aim(hand, located, stage_to_base, *aim);
        if (velocities == nullptr) return XR_SUCCESS;

        HandPose before;
        if (located) before = instance.scene->hands.ghost(tracker->side, t - kVelocityStep);
        const bool has_velocity = located && before.active;
        for (std::size_t i = 0; i < count; ++i) {
            XrHandJointVelocityEXT& out = velocities->jointVelocities[i];
            Vec3 linear = Vec3::Zero();
            Vec3 angular = Vec3::Zero();
            if (has_velocity) {
                const Pose now = joint_in_set(hand, i), then = joint_in_set(before, i);
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
