#pragma once

#include <Eigen/Geometry>

namespace physhand {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

// A rigid transform; quaternions are kept normalised by every producer.
struct Pose {
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();

    Pose operator*(const Pose& rhs) const {
        return {position + orientation * rhs.position, orientation * rhs.orientation};
    }
    Vec3 operator*(const Vec3& point) const { return position + orientation * point; }
    Pose inverse() const {
        Quat inv = orientation.conjugate();
        return {-(inv * position), inv};
    }
};

inline bool is_finite(const Vec3& v) {
    return v.allFinite();
}
inline bool is_finite(const Quat& q) {
    return q.coeffs().allFinite();
}
inline bool is_finite(const Pose& p) {
    return is_finite(p.position) && is_finite(p.orientation);
}

// Reflection through the YZ plane (x -> -x), keeping each frame right-handed: a right hand's
// joint frames become the left hand's (XR_EXT_hand_tracking gives both the same axes).
inline Pose mirror_x(const Pose& p) {
    const Quat& q = p.orientation;
    return {Vec3(-p.position.x(), p.position.y(), p.position.z()),
            Quat(q.w(), q.x(), -q.y(), -q.z())};
}

// Linear position, shortest-path slerp orientation.
inline Pose interpolate(const Pose& a, const Pose& b, double s) {
    return {a.position + (b.position - a.position) * s, a.orientation.slerp(s, b.orientation)};
}

// Where `p` is `dt` later, moving on at the given velocities (world frame).
inline Pose moved_on(const Pose& p, const Vec3& linear_velocity, const Vec3& angular_velocity,
                     double dt) {
    Pose out{p.position + dt * linear_velocity, p.orientation};
    const Vec3 turn = dt * angular_velocity;
    const double angle = turn.norm();
    if (angle > 0.0)
        out.orientation =
            (Quat(Eigen::AngleAxisd(angle, turn / angle)) * p.orientation).normalized();
    return out;
}

// The rotation vector (axis times angle, shortest way) taking `from` to `to`, world frame.
inline Vec3 rotation_between(const Quat& from, const Quat& to) {
    Quat delta = to * from.conjugate();
    if (delta.w() < 0) delta.coeffs() = -delta.coeffs();
    const Eigen::AngleAxisd aa(delta.normalized());
    return aa.angle() * aa.axis();
}

}  // namespace physhand
