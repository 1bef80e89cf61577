// Things at rest stay at rest: every dynamic collider kind, 1 to 50 cm, in each orientation it
// rests in, on a static box and on the floor plane, with no hand near, moves under 1 mm in
// 60 s at every substep count the drives use; on a static mesh, every box. Known and open: on a
// mesh 1 cm rods, capsules and tetrahedra and 2-5 cm rods lying fall through it (not played
// here; README).

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "simulation.h"

namespace physhand {
namespace {

constexpr double kGravity = 9.81;
constexpr double kTableTop = 0.75;
constexpr double kSeconds = 60.0;
constexpr double kMaxMotion = 0.001;  // m

struct Resting {
    std::string name;
    Collider collider;  // its lowest point at y = 0
};

Quat turn(const Vec3& axis, double degrees) {
    return Quat(Eigen::AngleAxisd(degrees * M_PI / 180.0, axis));
}

// The kinds in the orientations they rest in, `size` across at their widest.
std::vector<Resting> resting_colliders(double size) {
    const double r = size / 2;
    std::vector<Resting> out;
    const auto add = [&](const std::string& name, const Shape& shape, const Quat& orientation,
                         double lowest) {
        Collider c;
        c.id = name;
        c.shape = shape;
        c.motion = Motion::Dynamic;
        c.mass = std::max(0.01, 500.0 * size * size * size);  // about wood
        c.pose = {Vec3(0, lowest, 0), orientation};
        out.push_back(
            {name + " " + std::to_string(static_cast<int>(std::lround(size * 100))) + " cm", c});
    };
    Shape box;
    box.half_extents = Vec3(r, r * 0.5, r * 0.75);
    add("box on its largest face", box, Quat::Identity(), r * 0.5);
    add("box on its smallest face", box, turn(Vec3::UnitZ(), 90), r);
    add("box on its middle face", box, turn(Vec3::UnitX(), 90), r * 0.75);
    Shape sphere;
    sphere.kind = ShapeKind::Sphere;
    sphere.radius = r;
    add("sphere", sphere, Quat::Identity(), r);
    Shape capsule;
    capsule.kind = ShapeKind::Capsule;
    capsule.radius = r * 0.3;
    capsule.half_height = r * 0.7;
    add("capsule lying along x", capsule, turn(Vec3::UnitZ(), 90), r * 0.3);
    add("capsule lying along z", capsule, turn(Vec3::UnitX(), 90), r * 0.3);
    Shape rod;
    rod.kind = ShapeKind::Cylinder;
    rod.radius = r * 0.2;
    rod.half_height = r;
    add("rod standing", rod, Quat::Identity(), r);
    add("rod lying along x", rod, turn(Vec3::UnitZ(), 90), r * 0.2);
    add("rod lying along z", rod, turn(Vec3::UnitX(), 90), r * 0.2);
    Shape disc = rod;
    disc.radius = r;
    disc.half_height = r * 0.2;
    add("disc", disc, Quat::Identity(), r * 0.2);
    Shape tetrahedron;
    tetrahedron.kind = ShapeKind::Convex;
    tetrahedron.vertices = {{-r, 0, -r}, {r, 0, -r}, {0, 0, r}, {0, r, 0}};
    add("tetrahedron on its base", tetrahedron, Quat::Identity(), 0.0);
    return out;
}

enum class Support { Box, Plane };

Collider support(Support kind) {
    Collider c;
    c.id = "support";
    if (kind == Support::Box) {
        c.shape.half_extents = Vec3(1.0, 0.02, 1.0);
        c.pose.position = Vec3(0, kTableTop - 0.02, 0);
    } else {
        c.shape.kind = ShapeKind::Plane;
        c.shape.normal = Vec3::UnitY();
        c.shape.offset = kTableTop;
    }
    return c;
}

// Where `c` is, frame by frame (from 1), relative to where it was put on `support`, left alone
// for `frames` frames at 90 Hz.
std::vector<Vec3> left_alone(int substeps, const Collider& support, const Collider& c, int frames) {
    SimulationSettings settings;
    settings.drive.substeps = substeps;
    Simulation sim(settings, Vec3(0, -kGravity, 0));
    sim.add_collider(support);
    const ColliderHandle handle = sim.add_collider(c);
    const Vec3 start = sim.body_state(handle)->pose.position;
    const std::array<HandPose, 2> no_hands{};
    std::vector<Vec3> offsets;
    for (int f = 1; f <= frames; ++f) {
        sim.step_to(f / 90.0, no_hands);
        offsets.push_back(sim.body_state(handle)->pose.position - start);
    }
    return offsets;
}

class RestingColliders : public ::testing::TestWithParam<int> {};

TEST_P(RestingColliders, StayWhereTheyArePut) {
    const int substeps = GetParam();
    const double h = 1.0 / (90.0 * substeps);
    for (const Support kind : {Support::Box, Support::Plane}) {
        for (const double size : {0.01, 0.02, 0.05, 0.12, 0.2, 0.5}) {
            for (const Resting& r : resting_colliders(size)) {
                SCOPED_TRACE(r.name + (kind == Support::Box ? " on the box" : " on the plane"));
                Collider c = r.collider;
                c.pose.position.y() += kTableTop;
                const std::vector<Vec3> offsets =
                    left_alone(substeps, support(kind), c, static_cast<int>(kSeconds * 90));
                // Box on box: Bullet's box-box test finds no contact until the two overlap,
                // so a box left a rounding error above the table falls for the first
                // substep (g h^2, 1.2 mm at 90 Hz) before it is held.
                const bool first_may_fall = kind == Support::Box && c.shape.kind == ShapeKind::Box;
                if (first_may_fall) {
                    EXPECT_LE(offsets.front().norm(), kGravity * h * h + 1e-5);
                }
                double moved = 0.0;
                for (std::size_t f = first_may_fall ? 1 : 0; f < offsets.size(); ++f)
                    moved = std::max(moved, offsets[f].norm());
                EXPECT_LT(moved, kMaxMotion);
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Substeps, RestingColliders, ::testing::Values(1, 2, 4, 8));

// A table top as a modelling tool exports one: two triangles per 25 cm cell.
Collider mesh_table() {
    constexpr int kCells = 8;
    Collider c;
    c.id = "mesh table";
    c.shape.kind = ShapeKind::Mesh;
    for (int i = 0; i <= kCells; ++i) {
        for (int k = 0; k <= kCells; ++k) {
            c.shape.vertices.push_back(
                Vec3(-1.0 + 2.0 * i / kCells, kTableTop, -1.0 + 2.0 * k / kCells));
        }
    }
    for (int i = 0; i < kCells; ++i) {
        for (int k = 0; k < kCells; ++k) {
            const int a = i * (kCells + 1) + k;
            const int b = a + kCells + 1;
            c.shape.indices.push_back({a, a + 1, b + 1});
            c.shape.indices.push_back({a, b + 1, b});
        }
    }
    return c;
}

// On a static mesh things lie on its surface, not a margin above it (before: every one here
// rested 1 mm high, at every substep count). Known and open (issue 19), not asserted: on a mesh
// things dip up to 1.2 mm in their first frames and wander sideways up to 2 mm in 10 s, and a
// 2-5 cm rod lying on a mesh rolls away or falls through it.
TEST_P(RestingColliders, LieOnAMeshAtItsSurface) {
    const int substeps = GetParam();
    for (const double size : {0.05, 0.12, 0.2}) {
        for (const Resting& r : resting_colliders(size)) {
            if (r.name.starts_with("rod lying")) continue;
            SCOPED_TRACE(r.name);
            Collider c = r.collider;
            c.pose.position += Vec3(0.06, kTableTop, 0.1);  // inside one triangle
            constexpr int kFrames = 10 * 90;
            const std::vector<Vec3> offsets = left_alone(substeps, mesh_table(), c, kFrames);
            double height = 0.0;  // mean over the last 5 s, from where it was put
            for (int f = kFrames / 2; f < kFrames; ++f) height += offsets[f].y() / (kFrames / 2);
            EXPECT_LT(std::abs(height), 0.3 * kMaxMotion);
        }
    }
}

// Boxes of every size on a mesh, each on each of its faces, left alone for 60 s: none falls
// through it, and with 4 or more substeps none moves over 1 mm (1 and 2 substeps: a 5-50 cm box
// lying on its largest face wanders up to 8.5 mm across the triangles). Before World clipped a
// box's face against the triangles, 1 cm boxes fell through the mesh at 1 and 2 substeps, and
// at 4 and 8 boxes of 2-50 cm wandered up to 47 mm.
TEST_P(RestingColliders, BoxesStayOnAMesh) {
    const int substeps = GetParam();
    const double most = substeps >= 4 ? kMaxMotion : 10 * kMaxMotion;
    for (const double size : {0.01, 0.02, 0.05, 0.12, 0.2, 0.5}) {
        for (const Resting& r : resting_colliders(size)) {
            if (r.collider.shape.kind != ShapeKind::Box) continue;
            SCOPED_TRACE(r.name);
            Collider c = r.collider;
            c.pose.position += Vec3(0.06, kTableTop, 0.1);
            const std::vector<Vec3> offsets =
                left_alone(substeps, mesh_table(), c, static_cast<int>(kSeconds * 90));
            double moved = 0.0;
            for (const Vec3& o : offsets) moved = std::max(moved, o.norm());
            EXPECT_LT(moved, most);
        }
    }
}

}  // namespace
}  // namespace physhand
