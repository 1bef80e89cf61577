#include "float_transport.h"

namespace physhand {

namespace {

double f(double v) {
    return static_cast<double>(static_cast<float>(v));
}
Vec3 f(const Vec3& v) {
    return {f(v.x()), f(v.y()), f(v.z())};
}

}  // namespace

Pose round_to_float(const Pose& pose) {
    const Quat& q = pose.orientation;
    return {f(pose.position), Quat(f(q.w()), f(q.x()), f(q.y()), f(q.z()))};
}

HandPose round_to_float(const HandPose& hand) {
    HandPose out = hand;
    for (std::size_t j = 0; j < kJointCount; ++j) {
        out.joints[j] = round_to_float(hand.joints[j]);
        out.radii[j] = f(hand.radii[j]);
    }
    return out;
}

Collider round_to_float(const Collider& c) {
    Collider out = c;
    Shape& s = out.shape;
    s.half_extents = f(s.half_extents);
    s.radius = f(s.radius);
    s.half_height = f(s.half_height);
    for (Vec3& v : s.vertices) v = f(v);
    s.normal = f(s.normal);
    s.offset = f(s.offset);
    out.mass = f(c.mass);
    out.friction = f(c.friction);
    out.restitution = f(c.restitution);
    out.pose = round_to_float(c.pose);
    for (TimedPose& p : out.path) p.pose = round_to_float(p.pose);
    return out;
}

}  // namespace physhand
