// The sample's touch and hover feedback: surface distances per shape and the alpha they give.

#include "touch_feedback.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace physhand::sample {
namespace {

constexpr double kTolerance = 1e-12;

Shape box(const Vec3& half_extents) {
    Shape s;
    s.kind = ShapeKind::Box;
    s.half_extents = half_extents;
    return s;
}

Shape round_shape(ShapeKind kind, double radius, double half_height) {
    Shape s;
    s.kind = kind;
    s.radius = radius;
    s.half_height = half_height;
    return s;
}

TEST(SurfaceDistance, BoxToFaceEdgeAndInside) {
    const Shape s = box(Vec3(0.1, 0.2, 0.3));
    const Pose at{Vec3(1, 2, 3), Quat::Identity()};
    EXPECT_NEAR(surface_distance(s, at, Vec3(1.15, 2, 3)), 0.05, kTolerance);
    EXPECT_NEAR(surface_distance(s, at, Vec3(1, 1.7, 3)), 0.1, kTolerance);
    // Beyond an edge: to the edge, not to either face's plane.
    EXPECT_NEAR(surface_distance(s, at, Vec3(1.13, 2.24, 3)), 0.05, kTolerance);
    EXPECT_EQ(surface_distance(s, at, Vec3(1.05, 2.1, 2.8)), 0.0);
}

TEST(SurfaceDistance, BoxIsMeasuredInItsOwnFrame) {
    const Shape s = box(Vec3(0.5, 0.01, 0.01));  // a long bar along its local X
    const Pose turned{Vec3::Zero(), Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()))};
    // Turned about Z, the bar lies along the scene's Y.
    EXPECT_NEAR(surface_distance(s, turned, Vec3(0, 0.4, 0)), 0.0, kTolerance);
    EXPECT_NEAR(surface_distance(s, turned, Vec3(0.4, 0, 0)), 0.39, kTolerance);
}

TEST(SurfaceDistance, Sphere) {
    const Shape s = round_shape(ShapeKind::Sphere, 0.025, 0);
    const Pose at{Vec3(0, 1, 0), Quat::Identity()};
    EXPECT_NEAR(surface_distance(s, at, Vec3(0.03, 1.04, 0)), 0.025, kTolerance);
    EXPECT_EQ(surface_distance(s, at, Vec3(0.01, 1, 0)), 0.0);
}

TEST(SurfaceDistance, CapsuleSideAndCap) {
    const Shape s = round_shape(ShapeKind::Capsule, 0.02, 0.1);
    const Pose at{};
    EXPECT_NEAR(surface_distance(s, at, Vec3(0.05, 0.07, 0)), 0.03, kTolerance);
    EXPECT_NEAR(surface_distance(s, at, Vec3(0, -0.15, 0)), 0.03, kTolerance);
    EXPECT_EQ(surface_distance(s, at, Vec3(0, 0.11, 0.01)), 0.0);
}

TEST(SurfaceDistance, CylinderSideFlatEndAndRim) {
    const Shape s = round_shape(ShapeKind::Cylinder, 0.05, 0.1);
    const Pose at{};
    EXPECT_NEAR(surface_distance(s, at, Vec3(0, 0.05, 0.08)), 0.03, kTolerance);
    // Over the flat end, unlike a capsule's round cap.
    EXPECT_NEAR(surface_distance(s, at, Vec3(0.04, 0.13, 0)), 0.03, kTolerance);
    EXPECT_NEAR(surface_distance(s, at, Vec3(0.08, 0.14, 0)), 0.05, kTolerance);
    EXPECT_EQ(surface_distance(s, at, Vec3(0.03, -0.09, 0.03)), 0.0);
}

TEST(SurfaceDistance, PlaneAboveAndBelow) {
    Shape s;
    s.kind = ShapeKind::Plane;
    s.normal = Vec3(0, 2, 0);  // not unit: normalised
    s.offset = 0.5;
    EXPECT_NEAR(surface_distance(s, Pose{}, Vec3(3, 0.7, -4)), 0.2, kTolerance);
    EXPECT_EQ(surface_distance(s, Pose{}, Vec3(0, 0.4, 0)), 0.0);
}

TEST(SurfaceDistance, ConvexHullToItsBoundingSphere) {
    Shape s;
    s.kind = ShapeKind::Convex;
    s.vertices = {Vec3(0.1, 0, 0), Vec3(-0.1, 0, 0), Vec3(0, 0.1, 0), Vec3(0, -0.1, 0)};
    const Pose at{Vec3(0, 0, -1), Quat::Identity()};
    EXPECT_NEAR(surface_distance(s, at, Vec3(0, 0, -0.7)), 0.2, kTolerance);
    EXPECT_EQ(surface_distance(s, at, Vec3(0.05, 0.05, -1)), 0.0);
}

TEST(ObjectAlpha, TouchedIsTranslucentWhateverTheGap) {
    EXPECT_EQ(object_alpha(true, 1.0, 0.03), kTouchedAlpha);
    EXPECT_EQ(object_alpha(true, -0.01, 0.03), kTouchedAlpha);
    EXPECT_EQ(object_alpha(true, std::numeric_limits<double>::infinity(), 0.0), kTouchedAlpha);
}

TEST(ObjectAlpha, FadesLinearlyWithinTheHoverDistance) {
    EXPECT_EQ(object_alpha(false, 0.03, 0.03), 1.0f);
    EXPECT_EQ(object_alpha(false, 0.5, 0.03), 1.0f);
    EXPECT_EQ(object_alpha(false, std::numeric_limits<double>::infinity(), 0.03), 1.0f);
    EXPECT_FLOAT_EQ(object_alpha(false, 0.015, 0.03), (1.0f + kTouchedAlpha) / 2);
    EXPECT_FLOAT_EQ(object_alpha(false, 0.0, 0.03), kTouchedAlpha);
    // Overlapping yet not touched (between two steps): no more than touched.
    EXPECT_FLOAT_EQ(object_alpha(false, -0.005, 0.03), kTouchedAlpha);
    EXPECT_LT(object_alpha(false, 0.01, 0.03), object_alpha(false, 0.02, 0.03));
}

TEST(ObjectAlpha, NoHoverDistanceFadesNothingUntouched) {
    for (const double gap : {-0.01, 0.0, 0.01, std::numeric_limits<double>::infinity()}) {
        const float alpha = object_alpha(false, gap, 0.0);
        EXPECT_EQ(alpha, 1.0f) << "gap " << gap;
    }
}

}  // namespace
}  // namespace physhand::sample
