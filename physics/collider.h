#pragma once

#include <array>
#include <string>
#include <vector>

#include "pose.h"

namespace physhand {

// A collider as scene files and the layer's config describe it (docs/scene-format.md,
// COLLIDER) and as the simulation takes it.
enum class ShapeKind { Box, Sphere, Capsule, Cylinder, Convex, Mesh, Plane };
enum class Motion { Static, Kinematic, Dynamic };

struct Shape {
    ShapeKind kind = ShapeKind::Box;
    Vec3 half_extents = Vec3::Zero();         // box
    double radius = 0.0;                      // sphere, capsule, cylinder
    double half_height = 0.0;                 // capsule, cylinder (straight part, along local +Y)
    std::vector<Vec3> vertices;               // convex, mesh
    std::vector<std::array<int, 3>> indices;  // mesh
    Vec3 normal = Vec3::UnitY();              // plane
    double offset = 0.0;                      // plane: points p with normal·p = offset
};

struct TimedPose {
    double t = 0.0;
    Pose pose;
};

struct Collider {
    std::string id;
    Shape shape;
    Motion motion = Motion::Static;
    double mass = 0.0;  // dynamic only
    double friction = 0.8;
    double restitution = 0.0;
    Pose pose;
    std::vector<TimedPose> path;  // kinematic only; sorted by t

    // Where a kinematic collider's path puts it at time t (its pose if it has no path).
    Pose pose_at(double t) const;
};

}  // namespace physhand
