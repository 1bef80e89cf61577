#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <atomic>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dispatch.h"
#include "frame_clock.h"
#include "layer_log.h"
#include "sessions.h"
#include "xr_util.h"

// The extension's collider functions: the app's proxy colliders in the session's
// simulation, with poses converted between the app's spaces and the layer's frame.
namespace physhand::layer {

namespace {

std::atomic<std::uint64_t> collider_count{0};

// The create info as the physics' Collider, pose aside. Only what the physics cannot see
// is checked here (pointers, counts, enum values); sizes, mass, friction and the rest are
// checked by Simulation::add_collider, whose std::invalid_argument the caller turns into
// XR_ERROR_VALIDATION_FAILURE.
XrResult to_collider(const XrPhysicalColliderCreateInfoPHYSHAND& info, Collider& collider) {
    Shape& shape = collider.shape;
    switch (raw_enum(info.shape)) {
        case raw(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND):
            shape.kind = ShapeKind::Box;
            shape.half_extents = to_vec3(info.halfExtents);
            break;
        case raw(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND):
            shape.kind = ShapeKind::Sphere;
            shape.radius = info.radius;
            break;
        case raw(XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND):
        case raw(XR_PHYSICAL_COLLIDER_SHAPE_CYLINDER_PHYSHAND):
            shape.kind = info.shape == XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND
                             ? ShapeKind::Capsule
                             : ShapeKind::Cylinder;
            shape.radius = info.radius;
            shape.half_height = info.halfHeight;
            break;
        case raw(XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND):
        case raw(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND):
            shape.kind = info.shape == XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND
                             ? ShapeKind::Convex
                             : ShapeKind::Mesh;
            if (info.vertexCount > 0 && info.vertices == nullptr)
                return XR_ERROR_VALIDATION_FAILURE;
            shape.vertices.reserve(info.vertexCount);
            for (std::uint32_t i = 0; i < info.vertexCount; ++i) {
                shape.vertices.push_back(to_vec3(info.vertices[i]));
            }
            if (shape.kind == ShapeKind::Mesh) {
                if (info.indexCount % 3 != 0 || (info.indexCount > 0 && info.indices == nullptr)) {
                    return XR_ERROR_VALIDATION_FAILURE;
                }
                shape.indices.reserve(info.indexCount / 3);
                for (std::uint32_t i = 0; i < info.indexCount; i += 3) {
                    // Out-of-range indices (also those beyond int) are the physics' to reject.
                    shape.indices.push_back({static_cast<int>(info.indices[i]),
                                             static_cast<int>(info.indices[i + 1]),
                                             static_cast<int>(info.indices[i + 2])});
                }
            }
            break;
        case raw(XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND): {
            shape.kind = ShapeKind::Plane;
            shape.normal = to_vec3(info.planeNormal);
            shape.offset = info.planeOffset;
            // The physics wants a unit normal; scaling both keeps dot(n, p) = offset.
            const double norm = shape.normal.norm();
            if (norm > 0) {
                shape.normal /= norm;
                shape.offset /= norm;
            }
            break;
        }
        default:
            return XR_ERROR_VALIDATION_FAILURE;
    }
    switch (raw_enum(info.motion)) {
        case raw(XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND):
            collider.motion = Motion::Static;
            break;
        case raw(XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND):
            collider.motion = Motion::Kinematic;
            break;
        case raw(XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND):
            collider.motion = Motion::Dynamic;
            break;
        default:
            return XR_ERROR_VALIDATION_FAILURE;
    }
    collider.mass = collider.motion == Motion::Dynamic ? info.mass : 0.0;  // ignored otherwise
    collider.friction = info.friction;
    collider.restitution = info.restitution;
    return XR_SUCCESS;
}

XrPhysicalColliderFlagsPHYSHAND to_flags(const BodyState& body) {
    XrPhysicalColliderFlagsPHYSHAND flags = 0;
    if (body.touched_by[static_cast<int>(HandSide::Left)]) {
        flags |= XR_PHYSICAL_COLLIDER_TOUCHED_BY_LEFT_BIT_PHYSHAND;
    }
    if (body.touched_by[static_cast<int>(HandSide::Right)]) {
        flags |= XR_PHYSICAL_COLLIDER_TOUCHED_BY_RIGHT_BIT_PHYSHAND;
    }
    if (body.asleep) flags |= XR_PHYSICAL_COLLIDER_ASLEEP_BIT_PHYSHAND;
    return flags;
}

}  // namespace

XRAPI_ATTR XrResult XRAPI_CALL CreatePhysicalColliderPHYSHAND(
    XrSession session, const XrPhysicalColliderCreateInfoPHYSHAND* createInfo,
    XrPhysicalColliderPHYSHAND* collider) {
    return guarded("xrCreatePhysicalColliderPHYSHAND", [&] {
        LockedSession locked = lock_session(find_session(session));
        if (XR_FAILED(locked.result)) return locked.result;
        if (createInfo == nullptr || collider == nullptr ||
            createInfo->type != XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        Collider description;
        XrResult result = to_collider(*createInfo, description);
        if (XR_FAILED(result)) return result;
        result = check_pose(createInfo->pose);
        if (XR_FAILED(result)) return result;
        SessionState& state = *locked.state;
        Pose space;
        result = state.space_in_frame(createInfo->space, createInfo->time, space);
        if (XR_FAILED(result)) return result;
        description.pose = space * to_pose(createInfo->pose);
        // One name for all: the physics' messages about it then repeat, and are logged once.
        description.id = "app collider";

        ColliderHandle handle = 0;
        try {
            handle = state.simulation->add_collider(description);
        } catch (const std::invalid_argument& e) {
            log_failure("xrCreatePhysicalColliderPHYSHAND", e.what());
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const auto xr_handle = handle_from_id<XrPhysicalColliderPHYSHAND>(++collider_count);
        try {
            state.colliders.emplace(xr_handle, ColliderRecord{handle, description.motion});
            add_collider(xr_handle, locked.state);
        } catch (...) {
            state.colliders.erase(xr_handle);
            state.simulation->remove_collider(handle);
            throw;
        }
        *collider = xr_handle;
        return XR_SUCCESS;
    });
}

XRAPI_ATTR XrResult XRAPI_CALL
DestroyPhysicalColliderPHYSHAND(XrPhysicalColliderPHYSHAND collider) {
    return guarded("xrDestroyPhysicalColliderPHYSHAND", [&] {
        LockedSession locked = lock_session(find_collider(collider));
        if (XR_FAILED(locked.result)) return locked.result;
        const auto it = locked.state->colliders.find(collider);
        if (it == locked.state->colliders.end()) return XR_ERROR_HANDLE_INVALID;
        locked.state->simulation->remove_collider(it->second.handle);
        locked.state->colliders.erase(it);
        remove_collider(collider);
        return XR_SUCCESS;
    });
}

XRAPI_ATTR XrResult XRAPI_CALL SetPhysicalColliderPosePHYSHAND(
    XrPhysicalColliderPHYSHAND collider, const XrPhysicalColliderPoseInfoPHYSHAND* poseInfo) {
    return guarded("xrSetPhysicalColliderPosePHYSHAND", [&] {
        LockedSession locked = lock_session(find_collider(collider));
        if (XR_FAILED(locked.result)) return locked.result;
        const auto it = locked.state->colliders.find(collider);
        if (it == locked.state->colliders.end()) return XR_ERROR_HANDLE_INVALID;
        const ColliderRecord& record = it->second;
        if (poseInfo == nullptr || poseInfo->type != XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (poseInfo->teleport) {
            if (!is_finite(poseInfo->linearVelocity) || !is_finite(poseInfo->angularVelocity)) {
                return XR_ERROR_VALIDATION_FAILURE;
            }
        } else if (record.motion != Motion::Kinematic) {
            return XR_ERROR_VALIDATION_FAILURE;  // only kinematic colliders follow targets
        }
        XrResult result = check_pose(poseInfo->pose);
        if (XR_FAILED(result)) return result;
        Pose space;
        result = locked.state->space_in_frame(poseInfo->space, poseInfo->time, space);
        if (XR_FAILED(result)) return result;
        const Pose target = space * to_pose(poseInfo->pose);
        Simulation& simulation = *locked.state->simulation;
        bool done = false;
        if (poseInfo->teleport) {
            const bool dynamic = record.motion == Motion::Dynamic;  // only these take velocities
            done = simulation.teleport(
                record.handle, target,
                dynamic ? space.orientation * to_vec3(poseInfo->linearVelocity) : Vec3::Zero(),
                dynamic ? space.orientation * to_vec3(poseInfo->angularVelocity) : Vec3::Zero());
        } else {
            // Timed on the simulation's clock once it runs, so the collider moves evenly
            // through the physics frames up to the time the app gave.
            const std::optional<XrTime>& epoch = locked.state->epoch;
            done = epoch ? simulation.set_kinematic_target(record.handle, target,
                                                           clock_seconds(poseInfo->time - *epoch))
                         : simulation.set_kinematic_target(record.handle, target);
        }
        return done ? XR_SUCCESS : XR_ERROR_RUNTIME_FAILURE;
    });
}

XRAPI_ATTR XrResult XRAPI_CALL LocatePhysicalCollidersPHYSHAND(
    XrSession session, const XrPhysicalCollidersLocateInfoPHYSHAND* locateInfo,
    XrPhysicalColliderLocationsPHYSHAND* locations) {
    return guarded("xrLocatePhysicalCollidersPHYSHAND", [&] {
        LockedSession locked = lock_session(find_session(session));
        if (XR_FAILED(locked.result)) return locked.result;
        if (locateInfo == nullptr || locations == nullptr ||
            locateInfo->type != XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND ||
            locations->type != XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND ||
            locations->locationCount != locateInfo->colliderCount) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const std::uint32_t count = locateInfo->colliderCount;
        if (count > 0 && (locateInfo->colliders == nullptr || locations->locations == nullptr)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        auto* impulses = find_in_chain<XrPhysicalColliderImpulsesPHYSHAND>(
            locations->next, XR_TYPE_PHYSICAL_COLLIDER_IMPULSES_PHYSHAND);
        if (impulses &&
            (impulses->impulseCount != count || (count > 0 && impulses->impulses == nullptr))) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        SessionState& state = *locked.state;
        // Every handle is checked before anything changes.
        std::vector<ColliderHandle> handles(count);
        for (std::uint32_t i = 0; i < count; ++i) {
            const auto it = state.colliders.find(locateInfo->colliders[i]);
            if (it == state.colliders.end()) return XR_ERROR_HANDLE_INVALID;
            handles[i] = it->second.handle;
        }
        Pose frame;
        XrSpaceLocationFlags flags = 0;
        const XrResult result =
            state.frame_in_space(locateInfo->baseSpace, locateInfo->time, frame, flags);
        if (XR_FAILED(result)) return result;
        state.advance(locateInfo->time);
        const bool located = (flags & kPoseValid) == kPoseValid;
        for (std::uint32_t i = 0; i < count; ++i) {
            const std::optional<BodyState> body = state.simulation->body_state(handles[i]);
            if (!body) return XR_ERROR_RUNTIME_FAILURE;
            XrPhysicalColliderLocationPHYSHAND& out = locations->locations[i];
            out.locationFlags = located ? flags : 0;
            out.pose = to_xr(located ? frame * body->pose : Pose{});
            out.linearVelocity =
                to_xr(located ? frame.orientation * body->linear_velocity : Vec3::Zero());
            out.angularVelocity =
                to_xr(located ? frame.orientation * body->angular_velocity : Vec3::Zero());
            out.flags = to_flags(*body);
            if (!impulses) continue;
            // Kept for a later read while it cannot be given in the app's space.
            const HandImpulse given =
                located ? state.simulation->take_hand_impulse(handles[i]) : HandImpulse{};
            impulses->impulses[i].linearImpulse = to_xr(frame.orientation * given.linear);
            impulses->impulses[i].angularImpulse = to_xr(frame.orientation * given.angular);
        }
        return result;
    });
}

}  // namespace physhand::layer
