#include "touch_feedback.h"

#include <algorithm>
#include <cmath>

namespace physhand::sample {

double surface_distance(const Shape& shape, const Pose& pose, const Vec3& point) {
    const Vec3 p = pose.inverse() * point;  // in the collider's frame
    switch (shape.kind) {
        case ShapeKind::Box:
            return (p.cwiseAbs() - shape.half_extents).cwiseMax(0.0).norm();
        case ShapeKind::Sphere:
            return std::max(p.norm() - shape.radius, 0.0);
        case ShapeKind::Capsule: {
            const Vec3 axis_point(0, std::clamp(p.y(), -shape.half_height, shape.half_height), 0);
            return std::max((p - axis_point).norm() - shape.radius, 0.0);
        }
        case ShapeKind::Cylinder: {
            const double radial = std::max(std::hypot(p.x(), p.z()) - shape.radius, 0.0);
            const double axial = std::max(std::abs(p.y()) - shape.half_height, 0.0);
            return std::hypot(radial, axial);
        }
        case ShapeKind::Plane:
            return std::max(shape.normal.normalized().dot(p) - shape.offset, 0.0);
        case ShapeKind::Convex:
        case ShapeKind::Mesh:
            break;
    }
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : shape.vertices) centre += v;
    centre /= static_cast<double>(shape.vertices.size());
    double radius = 0.0;
    for (const Vec3& v : shape.vertices) radius = std::max(radius, (v - centre).norm());
    return std::max((p - centre).norm() - radius, 0.0);
}

float object_alpha(bool touched, double gap_m, double hover_m) {
    if (touched) return kTouchedAlpha;
    // No hover distance: nothing fades before a touch (and 0/0 below is never reached).
    if (!(hover_m > 0.0) || !(gap_m < hover_m)) return 1.0f;
    const auto closeness = static_cast<float>(1.0 - std::max(gap_m, 0.0) / hover_m);
    return 1.0f - (1.0f - kTouchedAlpha) * closeness;
}

}  // namespace physhand::sample
