#pragma once

#include <openxr/openxr.h>

#include "pose.h"

// Between the scene's doubles and OpenXR's floats. Plain casts both ways, with nothing
// renormalised: the physics-only runner rounds the scene the same way
// (scene/float_transport.h), so both paths simulate the very same world.
namespace physhand::sample {

inline XrVector3f to_xr(const Vec3& v) {
    return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}
inline XrPosef to_xr(const Pose& p) {
    const Quat& q = p.orientation;
    return {{static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
             static_cast<float>(q.w())},
            to_xr(p.position)};
}

inline Vec3 to_vec3(const XrVector3f& v) {
    return {v.x, v.y, v.z};
}
inline Pose to_pose(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    return {to_vec3(p.position), Quat(q.w, q.x, q.y, q.z)};
}

}  // namespace physhand::sample
