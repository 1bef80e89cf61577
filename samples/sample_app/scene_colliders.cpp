#include "scene_colliders.h"

#include <algorithm>
#include <cstdint>

#include "xr_check.h"
#include "xr_convert.h"

namespace physhand::sample {

namespace {

XrPhysicalColliderShapePHYSHAND xr_shape(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::Box:
            return XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND;
        case ShapeKind::Sphere:
            return XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND;
        case ShapeKind::Capsule:
            return XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND;
        case ShapeKind::Cylinder:
            return XR_PHYSICAL_COLLIDER_SHAPE_CYLINDER_PHYSHAND;
        case ShapeKind::Convex:
            return XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND;
        case ShapeKind::Mesh:
            return XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND;
        case ShapeKind::Plane:
            return XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND;
    }
    return XR_PHYSICAL_COLLIDER_SHAPE_MAX_ENUM_PHYSHAND;  // not reached: every kind is named
}

XrPhysicalColliderMotionPHYSHAND xr_motion(Motion motion) {
    switch (motion) {
        case Motion::Static:
            return XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND;
        case Motion::Kinematic:
            return XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND;
        case Motion::Dynamic:
            return XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND;
    }
    return XR_PHYSICAL_COLLIDER_MOTION_MAX_ENUM_PHYSHAND;  // not reached
}

// The create info of a scene collider. Its vertex and index arrays point into `vertices`
// and `indices`, which must outlive the call that uses it.
XrPhysicalColliderCreateInfoPHYSHAND create_info(const Collider& c, XrSpace stage, XrTime time,
                                                 std::vector<XrVector3f>& vertices,
                                                 std::vector<std::uint32_t>& indices) {
    const Shape& s = c.shape;
    for (const Vec3& v : s.vertices) vertices.push_back(to_xr(v));
    for (const auto& triangle : s.indices) {
        for (int i : triangle) indices.push_back(static_cast<std::uint32_t>(i));
    }
    XrPhysicalColliderCreateInfoPHYSHAND info{};
    info.type = XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND;
    info.shape = xr_shape(s.kind);
    info.motion = xr_motion(c.motion);
    info.halfExtents = to_xr(s.half_extents);
    info.radius = static_cast<float>(s.radius);
    info.halfHeight = static_cast<float>(s.half_height);
    info.vertexCount = static_cast<std::uint32_t>(vertices.size());
    info.vertices = vertices.data();
    info.indexCount = static_cast<std::uint32_t>(indices.size());
    info.indices = indices.data();
    info.planeNormal = to_xr(s.normal);
    info.planeOffset = static_cast<float>(s.offset);
    info.mass = static_cast<float>(c.mass);
    info.friction = static_cast<float>(c.friction);
    info.restitution = static_cast<float>(c.restitution);
    info.space = stage;
    info.pose = to_xr(c.pose);
    info.time = time;
    return info;
}

}  // namespace

ColliderFunctions ColliderFunctions::load(XrInstance instance) {
    return {
        load_function<PFN_xrCreatePhysicalColliderPHYSHAND>(instance,
                                                            "xrCreatePhysicalColliderPHYSHAND"),
        load_function<PFN_xrDestroyPhysicalColliderPHYSHAND>(instance,
                                                             "xrDestroyPhysicalColliderPHYSHAND"),
        load_function<PFN_xrSetPhysicalColliderPosePHYSHAND>(instance,
                                                             "xrSetPhysicalColliderPosePHYSHAND"),
        load_function<PFN_xrLocatePhysicalCollidersPHYSHAND>(instance,
                                                             "xrLocatePhysicalCollidersPHYSHAND"),
    };
}

SceneColliders::SceneColliders(const Scene& scene, const ColliderFunctions& functions,
                               XrInstance instance, XrSession session, XrSpace stage, XrTime time)
    : scene_(scene),
      functions_(functions),
      instance_(instance),
      session_(session),
      stage_(stage),
      engine_(scene) {
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
        const Collider c = as_declared(scene, i);
        std::vector<XrVector3f> vertices;
        std::vector<std::uint32_t> indices;
        const XrPhysicalColliderCreateInfoPHYSHAND info =
            create_info(c, stage, time, vertices, indices);
        XrPhysicalColliderPHYSHAND collider = XR_NULL_HANDLE;
        xr_check(instance, functions.create(session, &info, &collider),
                 "xrCreatePhysicalColliderPHYSHAND(" + c.id + ")");
        owned_.emplace_back(collider, functions.destroy);
        handles_.push_back(collider);
    }
    locations_.resize(handles_.size());
    impulses_.resize(handles_.size());
}

void SceneColliders::follow(XrTime time, double t) {
    engine_.step(t - engine_t_);
    engine_t_ = t;
    for (std::size_t i = 0; i < scene_.colliders.size(); ++i) {
        const Collider& c = scene_.colliders[i];
        if (c.path.empty() && !engine_.simulates(i)) continue;
        XrPhysicalColliderPoseInfoPHYSHAND info{};
        info.type = XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND;
        info.space = stage_;
        info.time = time;
        info.pose = to_xr(engine_.simulates(i) ? engine_.state(i).pose : c.pose_at(t));
        info.teleport = XR_FALSE;
        xr_check(instance_, functions_.set_pose(handles_[i], &info),
                 "xrSetPhysicalColliderPosePHYSHAND(" + c.id + ")");
    }
}

const std::vector<XrPhysicalColliderLocationPHYSHAND>& SceneColliders::locate(XrTime time) {
    XrPhysicalCollidersLocateInfoPHYSHAND info{};
    info.type = XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND;
    info.baseSpace = stage_;
    info.time = time;
    info.colliderCount = static_cast<std::uint32_t>(handles_.size());
    info.colliders = handles_.data();
    XrPhysicalColliderImpulsesPHYSHAND impulses{};
    impulses.type = XR_TYPE_PHYSICAL_COLLIDER_IMPULSES_PHYSHAND;
    impulses.impulseCount = static_cast<std::uint32_t>(impulses_.size());
    impulses.impulses = impulses_.data();
    XrPhysicalColliderLocationsPHYSHAND locations{};
    locations.type = XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND;
    // Only a scene with objects of the app's own asks for impulses.
    if (!scene_.app_engine.empty()) locations.next = &impulses;
    locations.locationCount = static_cast<std::uint32_t>(locations_.size());
    locations.locations = locations_.data();
    xr_check(instance_, functions_.locate(session_, &info, &locations),
             "xrLocatePhysicalCollidersPHYSHAND");
    for (std::size_t i = 0; i < scene_.colliders.size(); ++i) {
        if (!engine_.simulates(i)) continue;
        engine_.apply(i, to_vec3(impulses_[i].linearImpulse), to_vec3(impulses_[i].angularImpulse));
    }
    return locations_;
}

std::optional<std::size_t> SceneColliders::index_of(XrPhysicalColliderPHYSHAND collider) const {
    const auto it = std::find(handles_.begin(), handles_.end(), collider);
    if (it == handles_.end()) return std::nullopt;
    return static_cast<std::size_t>(it - handles_.begin());
}

}  // namespace physhand::sample
