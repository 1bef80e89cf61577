#include "float_transport.h"

namespace physhand {

namespace {

double f(double v) {
    return static_cast<double>(static_cast<float>(v));
}
// Through Eigen's cast: GCC 12 at -O2 folded a component-wise double->float->double of a
// Vector3d away for x and y (seen in the generated code), leaving them unrounded.
Vec3 f(const Vec3& v) {
    return v.cast<float>().cast<double>();
}

}  // namespace

Vec3 round_to_float(const Vec3& v) {
    return f(v);
}

Pose round_to_float(const Pose& pose) {
    return {f(pose.position), pose.orientation.cast<float>().cast<double>()};
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
