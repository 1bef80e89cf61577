#pragma once

#include <openxr/openxr.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "pose.h"

// Conversions between OpenXR and physics types, and the checks every entry point applies
// to what an app passes in.
namespace physhand::layer {

inline Vec3 to_vec3(const XrVector3f& v) {
    return {v.x, v.y, v.z};
}
inline XrVector3f to_xr(const Vec3& v) {
    return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

// Exactly the floats given, not renormalised: the physics normalises what needs it (its
// input guards, Bullet's transforms), the same way for the layer and for the physics-only
// runner, so both simulate bit-identical worlds from the same scene.
inline Pose to_pose(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    return {to_vec3(p.position), Quat(q.w, q.x, q.y, q.z)};
}
inline XrPosef to_xr(const Pose& p) {
    const Quat& q = p.orientation;
    return {{static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
             static_cast<float>(q.w())},
            to_xr(p.position)};
}

inline constexpr XrSpaceLocationFlags kPoseValid =
    XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
inline constexpr XrSpaceLocationFlags kPoseTracked =
    XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;

inline bool is_finite(float f) {
    return std::isfinite(f);
}
inline bool is_finite(const XrVector3f& v) {
    return is_finite(v.x) && is_finite(v.y) && is_finite(v.z);
}
inline bool is_finite(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    return is_finite(p.position) && is_finite(q.x) && is_finite(q.y) && is_finite(q.z) &&
           is_finite(q.w);
}

// An app's pose: NaN/Inf is malformed input; a finite quaternion off unit length is an
// invalid pose, as the core specification answers for reference spaces. The tolerance
// is generous because apps build quaternions in float.
inline XrResult check_pose(const XrPosef& p) {
    if (!is_finite(p)) return XR_ERROR_VALIDATION_FAILURE;
    const XrQuaternionf& q = p.orientation;
    const double norm2 =
        double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z + double(q.w) * q.w;
    return std::abs(norm2 - 1.0) <= 1e-2 ? XR_SUCCESS : XR_ERROR_POSE_INVALID;
}

// An enum field as the app wrote it. C lets any int through, and loading a value outside a
// C++ enum's range is undefined behaviour (UBSan -fsanitize=enum aborts on it), so an app's
// enums are read as their underlying integer before they are compared.
template <typename Enum>
std::underlying_type_t<Enum> raw_enum(const Enum& field) {
    std::underlying_type_t<Enum> value;
    std::memcpy(&value, &field, sizeof(value));
    return value;
}
template <typename Enum>
constexpr std::underlying_type_t<Enum> raw(Enum value) {
    return static_cast<std::underlying_type_t<Enum>>(value);
}

// The first structure of `type` in an output chain, or null.
template <typename T>
T* find_in_chain(void* next, XrStructureType type) {
    for (auto* s = static_cast<XrBaseOutStructure*>(next); s != nullptr; s = s->next) {
        if (s->type == type) return reinterpret_cast<T*>(s);
    }
    return nullptr;
}

// Handles the layer hands out are counters, never reused, so a stale handle stays invalid.
template <typename Handle>
Handle handle_from_id(std::uint64_t id) {
    if constexpr (std::is_pointer_v<Handle>) {
        return reinterpret_cast<Handle>(static_cast<std::uintptr_t>(id));
    } else {
        return static_cast<Handle>(id);
    }
}

}  // namespace physhand::layer
