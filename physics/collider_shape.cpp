#include "collider_shape.h"

#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <LinearMath/btConvexHullComputer.h>
#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "bullet_convert.h"

namespace physhand {

namespace {

// Bullet's 4 cm default margin is larger than a hand-sized object: thin margins keep
// boxes square-cornered and contacts where the surface is.
constexpr btScalar kMargin = 0.001f;

[[noreturn]] void fail(const Collider& c, const std::string& what) {
    throw std::invalid_argument("collider \"" + c.id + "\": " + what);
}

// Bullet simulates in float: past these bounds a body's inverse mass or inertia, or its
// weight, overflows, and its first contact turns its state into NaN (found by fuzzing the
// extension, tests/fuzz).
constexpr double kMinSize = 1e-4, kMaxSize = 1e4;  // m
constexpr double kMinMass = 1e-6, kMaxMass = 1e6;  // kg

void require_within(const Collider& c, double v, double lo, double hi, const char* field,
                    const char* unit) {
    if (!(v >= lo && v <= hi)) {
        std::ostringstream what;
        what << field << " must be within [" << lo << ", " << hi << "] " << unit;
        fail(c, what.str());
    }
}

void require_size(const Collider& c, double v, const char* field) {
    require_within(c, v, kMinSize, kMaxSize, field, "m");
}

// How far the vertices reach out of the line and the plane through the farthest of them:
// under kMinSize, a hull has no volume (all vertices in one place, on a line or in a plane).
double hull_thickness(const std::vector<Vec3>& v) {
    const auto farthest = [&](auto&& distance) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < v.size(); ++i) {
            if (distance(v[i]) > distance(v[best])) best = i;
        }
        return std::pair{v[best], distance(v[best])};
    };
    const Vec3 a = v.front();
    const auto [b, length] = farthest([&](const Vec3& p) { return (p - a).norm(); });
    if (length < kMinSize) return length;
    const Vec3 axis = (b - a) / length;
    const auto [c, width] = farthest([&](const Vec3& p) { return (p - a).cross(axis).norm(); });
    if (width < kMinSize) return width;
    const Vec3 normal = axis.cross(c - a).normalized();
    return farthest([&](const Vec3& p) { return std::abs((p - a).dot(normal)); }).second;
}

}  // namespace

ColliderShape::ColliderShape() = default;
ColliderShape::~ColliderShape() = default;
ColliderShape::ColliderShape(ColliderShape&&) noexcept = default;
ColliderShape& ColliderShape::operator=(ColliderShape&&) noexcept = default;

void validate_collider(const Collider& c) {
    const Shape& s = c.shape;
    if (!std::all_of(s.vertices.begin(), s.vertices.end(),
                     [](const Vec3& v) { return is_finite(v) && v.norm() <= kMaxSize; })) {
        std::ostringstream what;
        what << "vertices must be finite and within " << kMaxSize << " m of the origin";
        fail(c, what.str());
    }
    switch (s.kind) {
        case ShapeKind::Box:
            for (int i = 0; i < 3; ++i) require_size(c, s.half_extents[i], "half_extents");
            break;
        case ShapeKind::Sphere:
            require_size(c, s.radius, "radius");
            break;
        case ShapeKind::Capsule:
            require_size(c, s.radius, "radius");
            require_within(c, s.half_height, 0.0, kMaxSize, "half_height", "m");
            break;
        case ShapeKind::Cylinder:
            require_size(c, s.radius, "radius");
            require_size(c, s.half_height, "half_height");
            break;
        case ShapeKind::Convex:
            if (s.vertices.size() < 4) fail(c, "a convex hull needs at least 4 vertices");
            if (!(hull_thickness(s.vertices) >= kMinSize)) {
                fail(c, "vertices span no volume (all in one place, on a line or in a plane)");
            }
            break;
        case ShapeKind::Mesh:
            if (s.vertices.size() < 3 || s.indices.empty()) {
                fail(c, "a mesh needs at least 3 vertices and 1 triangle");
            }
            for (const auto& tri : s.indices) {
                for (int i : tri) {
                    if (i < 0 || static_cast<std::size_t>(i) >= s.vertices.size()) {
                        fail(c, "mesh index " + std::to_string(i) + " out of range");
                    }
                }
            }
            if (std::none_of(s.indices.begin(), s.indices.end(), [&](const auto& tri) {
                    const Vec3& a = s.vertices[static_cast<std::size_t>(tri[0])];
                    const Vec3& b = s.vertices[static_cast<std::size_t>(tri[1])];
                    const Vec3& d = s.vertices[static_cast<std::size_t>(tri[2])];
                    return (b - a).cross(d - a).norm() / 2 >= kMinSize * kMinSize;
                })) {
                fail(c, "every mesh triangle has zero area");
            }
            break;
        case ShapeKind::Plane:
            if (!is_finite(s.normal) || s.normal.norm() < 1e-9 || !std::isfinite(s.offset)) {
                fail(c, "plane normal must be finite and non-zero");
            }
            break;
    }
    if ((s.kind == ShapeKind::Mesh || s.kind == ShapeKind::Plane) && c.motion != Motion::Static) {
        fail(c, "mesh and plane colliders must be static");
    }
    if (c.motion == Motion::Dynamic) {
        require_within(c, c.mass, kMinMass, kMaxMass, "mass", "kg");
    } else if (c.mass != 0.0) {
        fail(c, "mass is only for dynamic colliders");
    }
    if (!std::isfinite(c.friction) || c.friction < 0.0) fail(c, "friction must be >= 0");
    if (!std::isfinite(c.restitution) || c.restitution < 0.0 || c.restitution > 1.0) {
        fail(c, "restitution must be within [0, 1]");
    }
    if (!is_finite(c.pose) || c.pose.orientation.norm() < 1e-9) {
        fail(c, "pose must be finite with a non-zero quaternion");
    }
}

ColliderShape make_collider_shape(const Collider& c) {
    validate_collider(c);
    const Shape& s = c.shape;
    ColliderShape out;
    switch (s.kind) {
        case ShapeKind::Box:
            out.shape = std::make_unique<btBoxShape>(to_bt(s.half_extents));
            break;
        case ShapeKind::Sphere:
            out.shape = std::make_unique<btSphereShape>(static_cast<btScalar>(s.radius));
            break;
        case ShapeKind::Capsule:
            out.shape = std::make_unique<btCapsuleShape>(static_cast<btScalar>(s.radius),
                                                         static_cast<btScalar>(2 * s.half_height));
            break;
        case ShapeKind::Cylinder:
            out.shape = std::make_unique<btCylinderShape>(
                btVector3(static_cast<btScalar>(s.radius), static_cast<btScalar>(s.half_height),
                          static_cast<btScalar>(s.radius)));
            break;
        case ShapeKind::Convex: {
            // Bullet's hull collides kMargin outside its points: moved in by as much, so that
            // the surface is where the points put it (it rested 1 mm high on a table). A hull
            // thinner than 8 margins shrinks less, by a quarter of its least depth.
            std::vector<double> coords;
            for (const Vec3& v : s.vertices) coords.insert(coords.end(), {v.x(), v.y(), v.z()});
            btConvexHullComputer inner;
            inner.compute(coords.data(), 3 * sizeof(double), static_cast<int>(s.vertices.size()),
                          kMargin, 0.25f);
            auto hull = std::make_unique<btConvexHullShape>();
            for (int i = 0; i < inner.vertices.size(); ++i)
                hull->addPoint(inner.vertices[i], false);
            hull->recalcLocalAabb();
            hull->optimizeConvexHull();
            out.shape = std::move(hull);
            break;
        }
        case ShapeKind::Mesh: {
            for (const Vec3& v : s.vertices) {
                for (int i = 0; i < 3; ++i) out.mesh_vertices.push_back(static_cast<float>(v[i]));
            }
            for (const auto& tri : s.indices)
                out.mesh_indices.insert(out.mesh_indices.end(), tri.begin(), tri.end());
            out.mesh_interface = std::make_unique<btTriangleIndexVertexArray>(
                static_cast<int>(s.indices.size()), out.mesh_indices.data(), 3 * sizeof(int),
                static_cast<int>(s.vertices.size()), out.mesh_vertices.data(), 3 * sizeof(float));
            out.shape = std::make_unique<btBvhTriangleMeshShape>(out.mesh_interface.get(), true);
            break;
        }
        case ShapeKind::Plane:
            out.shape = std::make_unique<btStaticPlaneShape>(to_bt(s.normal.normalized()),
                                                             static_cast<btScalar>(s.offset));
            break;
    }
    // A triangle has no inside to keep a margin in: Bullet's triangles collide their margin
    // outside the surface, and everything rested kMargin above a mesh (a hand pressed on a
    // table made of triangles buzzed at 0.74 mm RMS, 0.20 mm without; press_table).
    if (s.kind == ShapeKind::Mesh) {
        out.shape->setMargin(0.0f);
    } else if (s.kind != ShapeKind::Sphere && s.kind != ShapeKind::Capsule) {
        out.shape->setMargin(kMargin);
    }
    // A box's faces, for World's face-against-triangle contacts: against a mesh's triangles, which
    // have no inside, Bullet's one point per pair found by GJK let a box rock, and 1 cm boxes
    // sank through the triangle they lay on.
    if (s.kind == ShapeKind::Box && c.motion == Motion::Dynamic)
        static_cast<btBoxShape&>(*out.shape).initializePolyhedralFeatures();
    return out;
}

double min_half_extent(const btCollisionShape& shape) {
    btVector3 lo, hi;
    shape.getAabb(btTransform::getIdentity(), lo, hi);
    const btVector3 half = (hi - lo) * 0.5f;
    return std::min({half.x(), half.y(), half.z()});
}

}  // namespace physhand
