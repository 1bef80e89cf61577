#include "shape_meshes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace physhand::sample {

namespace {

constexpr int kSegments = 20;  // around every round shape
constexpr int kRings = 12;     // pole to pole of a sphere or capsule (even: an equator ring)
constexpr double kPlaneHalfSize = 10.0;

}  // namespace

void MeshSet::begin() {
    first_vertex_ = vertices_.size();
    first_index_ = indices_.size();
}

MeshRange MeshSet::finish() {
    return {static_cast<std::uint32_t>(first_index_),
            static_cast<std::uint32_t>(indices_.size() - first_index_),
            static_cast<std::int32_t>(first_vertex_)};
}

std::uint32_t MeshSet::vertex(const Vec3& position, const Vec3& normal) {
    vertices_.push_back({{static_cast<float>(position.x()), static_cast<float>(position.y()),
                          static_cast<float>(position.z())},
                         {static_cast<float>(normal.x()), static_cast<float>(normal.y()),
                          static_cast<float>(normal.z())}});
    return static_cast<std::uint32_t>(vertices_.size() - first_vertex_ - 1);
}

// Counter-clockwise a, b, c, d seen from outside.
void MeshSet::quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    indices_.insert(indices_.end(), {a, b, c, a, c, d});
}

MeshRange MeshSet::add_box(const Vec3& half_extents, const Vec3& centre) {
    begin();
    for (int axis = 0; axis < 3; ++axis) {
        for (const double sign : {-1.0, 1.0}) {
            Vec3 normal = Vec3::Zero();
            normal[axis] = sign;
            // u x v = normal, so the corners below run counter-clockwise seen from outside.
            Vec3 u = Vec3::Zero(), v = Vec3::Zero();
            u[(axis + 1) % 3] = 1.0;
            v[(axis + 2) % 3] = sign;
            const Vec3 face = centre + normal.cwiseProduct(half_extents);
            const Vec3 du = u.cwiseProduct(half_extents), dv = v.cwiseProduct(half_extents);
            const std::uint32_t a = vertex(face - du - dv, normal);
            const std::uint32_t b = vertex(face + du - dv, normal);
            const std::uint32_t c = vertex(face + du + dv, normal);
            const std::uint32_t d = vertex(face - du + dv, normal);
            quad(a, b, c, d);
        }
    }
    return finish();
}

// Rings from the top pole down; the equator ring is doubled so that the two halves, moved
// apart by the straight part, are joined by a band.
MeshRange MeshSet::add_capsule(double radius, double half_height) {
    begin();
    const int rows = kRings + 2;
    for (int row = 0; row < rows; ++row) {
        const int ring = row <= kRings / 2 ? row : row - 1;
        const double polar = std::numbers::pi * ring / kRings;
        const double shift = row <= kRings / 2 ? half_height : -half_height;
        for (int s = 0; s <= kSegments; ++s) {
            const double azimuth = 2 * std::numbers::pi * s / kSegments;
            const Vec3 normal(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                              -std::sin(polar) * std::sin(azimuth));
            vertex(radius * normal + Vec3(0, shift, 0), normal);
        }
    }
    const auto at = [](int row, int s) {
        return static_cast<std::uint32_t>(row * (kSegments + 1) + s);
    };
    for (int row = 0; row + 1 < rows; ++row) {
        for (int s = 0; s < kSegments; ++s) {
            quad(at(row, s), at(row + 1, s), at(row + 1, s + 1), at(row, s + 1));
        }
    }
    return finish();
}

MeshRange MeshSet::add_cylinder(double radius, double half_height) {
    begin();
    for (const double sign : {1.0, -1.0}) {
        const Vec3 axis(0, sign, 0);
        const std::uint32_t centre = vertex(half_height * axis, axis);
        const std::uint32_t rim = centre + 1;
        for (int s = 0; s <= kSegments; ++s) {
            const double azimuth = 2 * std::numbers::pi * s / kSegments;
            const Vec3 out(std::cos(azimuth), 0, -std::sin(azimuth));
            vertex(radius * out + half_height * axis, axis);
        }
        for (std::uint32_t s = 0; s < kSegments; ++s) {
            if (sign > 0) {
                indices_.insert(indices_.end(), {centre, rim + s, rim + s + 1});
            } else {
                indices_.insert(indices_.end(), {centre, rim + s + 1, rim + s});
            }
        }
    }
    const auto side = static_cast<std::uint32_t>(vertices_.size() - first_vertex_);
    for (int s = 0; s <= kSegments; ++s) {
        const double azimuth = 2 * std::numbers::pi * s / kSegments;
        const Vec3 out(std::cos(azimuth), 0, -std::sin(azimuth));
        vertex(radius * out + Vec3(0, half_height, 0), out);
        vertex(radius * out - Vec3(0, half_height, 0), out);
    }
    for (std::uint32_t s = 0; s < kSegments; ++s) {
        const std::uint32_t top = side + 2 * s, next = top + 2;
        quad(top, top + 1, next + 1, next);
    }
    return finish();
}

MeshRange MeshSet::add_shape(const Shape& shape) {
    switch (shape.kind) {
        case ShapeKind::Box:
            return add_box(shape.half_extents, Vec3::Zero());
        case ShapeKind::Sphere:
            return add_capsule(shape.radius, 0.0);
        case ShapeKind::Capsule:
            return add_capsule(shape.radius, shape.half_height);
        case ShapeKind::Cylinder:
            return add_cylinder(shape.radius, shape.half_height);
        case ShapeKind::Convex: {
            Vec3 low = shape.vertices.front(), high = low;
            for (const Vec3& v : shape.vertices) {
                low = low.cwiseMin(v);
                high = high.cwiseMax(v);
            }
            return add_box((high - low) / 2, (high + low) / 2);
        }
        case ShapeKind::Mesh: {
            begin();
            for (const auto& triangle : shape.indices) {
                const Vec3& a = shape.vertices[triangle[0]];
                const Vec3& b = shape.vertices[triangle[1]];
                const Vec3& c = shape.vertices[triangle[2]];
                const Vec3 normal = (b - a).cross(c - a).normalized();
                const std::uint32_t first = vertex(a, normal);
                vertex(b, normal);
                vertex(c, normal);
                indices_.insert(indices_.end(), {first, first + 1, first + 2});
            }
            return finish();
        }
        case ShapeKind::Plane:
            break;
    }
    begin();
    const Vec3 normal = shape.normal.normalized();
    const Vec3 helper = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 u = helper.cross(normal).normalized() * kPlaneHalfSize;
    const Vec3 v = normal.cross(u);
    const Vec3 centre = normal * shape.offset;
    const std::uint32_t a = vertex(centre - u - v, normal);
    const std::uint32_t b = vertex(centre + u - v, normal);
    const std::uint32_t c = vertex(centre + u + v, normal);
    const std::uint32_t d = vertex(centre - u + v, normal);
    quad(a, b, c, d);
    return finish();
}

MeshRange MeshSet::add_unit_sphere() {
    return add_capsule(1.0, 0.0);
}

MeshRange MeshSet::add_unit_cylinder() {
    return add_cylinder(1.0, 1.0);
}

MeshRange MeshSet::add_unit_box() {
    return add_box(Vec3::Ones(), Vec3::Zero());
}

}  // namespace physhand::sample
