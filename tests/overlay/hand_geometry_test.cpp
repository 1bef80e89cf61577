// The CPU half of the overlay: the capsule mesh and the instances built from a frame.

#include "hand_geometry.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

namespace physhand::overlay {
namespace {

using Point = std::array<double, 3>;

// Where capsule.vert puts a mesh vertex for a capsule along +Z from `start_z` to `end_z`.
Point place(const MeshVertex& vertex, double start_z, double end_z, double radius) {
    const auto& l = vertex.local;
    return {radius * l[0], radius * l[1], (l[3] < 0.5f ? start_z : end_z) + radius * l[2]};
}

Point sub(const Point& a, const Point& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Point cross(const Point& a, const Point& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Point& a, const Point& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void expect_outward(const Mesh& mesh, double start_z, double end_z) {
    ASSERT_EQ(mesh.indices.size() % 3, 0u);
    const double middle = 0.5 * (start_z + end_z);
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        std::array<Point, 3> p;
        for (size_t k = 0; k < 3; ++k) {
            ASSERT_LT(mesh.indices[i + k], mesh.vertices.size());
            p[k] = place(mesh.vertices[mesh.indices[i + k]], start_z, end_z, 1.0);
        }
        const Point normal = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        if (start_z == end_z && dot(normal, normal) < 1e-20) {
            continue;  // a sphere's side band has no length, hence no area
        }
        const Point centroid = {(p[0][0] + p[1][0] + p[2][0]) / 3,
                                (p[0][1] + p[1][1] + p[2][1]) / 3,
                                (p[0][2] + p[1][2] + p[2][2]) / 3 - middle};
        // Counter-clockwise seen from outside: the right-hand normal points away from
        // the axis (the pipeline culls the others as back faces).
        EXPECT_GT(dot(normal, centroid), 1e-6) << "triangle " << i / 3;
    }
}

TEST(CapsuleMesh, SphereAndCapsuleTrianglesAllFaceOutward) {
    const Mesh mesh = build_capsule_mesh(20, 6);
    EXPECT_EQ(mesh.vertices.size(), 20u * 14u);
    // Per quad band two triangles, one fewer at each pole band; 13 bands.
    EXPECT_EQ(mesh.indices.size(), 3u * 20u * (2 * 13 - 2));
    expect_outward(mesh, 0.0, 0.0);
    expect_outward(mesh, 0.0, 3.0);
}

TEST(CapsuleMesh, VerticesAreUnitDirections) {
    for (const MeshVertex& v : build_capsule_mesh(8, 3).vertices) {
        EXPECT_NEAR(std::hypot(v.local[0], v.local[1], v.local[2]), 1.0, 1e-6);
        EXPECT_TRUE(v.local[3] == 0.0f || v.local[3] == 1.0f);
    }
}

TEST(BoxMesh, FacesAreSquaresFacingOutAlongTheirNormals) {
    const Mesh mesh = build_box_mesh();
    ASSERT_EQ(mesh.vertices.size(), 24u);
    ASSERT_EQ(mesh.indices.size(), 36u);
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        std::array<Point, 3> p;
        for (size_t k = 0; k < 3; ++k) {
            const MeshVertex& v = mesh.vertices[mesh.indices[i + k]];
            EXPECT_EQ(v.local[3], kBoxVertex);
            p[k] = {v.local[0], v.local[1], v.local[2]};
        }
        const MeshVertex& first = mesh.vertices[mesh.indices[i]];
        const Point normal = {first.normal[0], first.normal[1], first.normal[2]};
        // Every corner on the face the normal names, and the winding counter-clockwise
        // seen from outside.
        for (const Point& corner : p) EXPECT_DOUBLE_EQ(dot(corner, normal), 1.0);
        const Point winding = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        EXPECT_DOUBLE_EQ(dot(winding, normal), 4.0) << "triangle " << i / 3;
    }
}

Solid capsule(Vec3 start, Vec3 end, float radius) {
    Solid solid;
    solid.start = start;
    solid.end = end;
    solid.radius = radius;
    return solid;
}

Solid box(Vec3 centre, Quat orientation, Vec3 half_extents) {
    Solid solid;
    solid.kind = Solid::Kind::Box;
    solid.start = centre;
    solid.orientation = orientation;
    solid.half_extents = half_extents;
    return solid;
}

class BuildInstances : public ::testing::Test {
  protected:
    void SetUp() override {
        frame_.parents.fill(-1);
        // The ghost is pressed 2 cm behind the physical hand.
        for (Hand& hand : frame_.hands) {
            for (int j = 0; j < kJointCount; ++j) {
                hand.physical.positions[j] = {0.01f * j, 0.0f, -0.5f};
                hand.ghost.positions[j] = {0.01f * j, 0.0f, -0.52f};
                hand.ghost.radii[j] = hand.physical.radii[j] = 0.01f;
            }
        }
    }

    DrawCounts build() { return build_instances(frame_, out_); }

    Frame frame_;
    std::array<PrimitiveInstance, kMaxInstances> out_{};
};

TEST_F(BuildInstances, NothingActiveNothingDrawn) {
    const DrawCounts counts = build();
    EXPECT_EQ(counts.total(), 0u);
}

TEST_F(BuildInstances, JointsAndOneBonePerParentedJoint) {
    frame_.hands[0].physical_active = true;
    frame_.hands[1].ghost_active = true;
    frame_.parents[1] = 0;
    frame_.parents[2] = 1;
    const DrawCounts counts = build();
    EXPECT_EQ(counts.physical_capsules, 26u + 2u);
    EXPECT_EQ(counts.ghost, 26u + 2u);
    const PrimitiveInstance& bone = out_[26];
    EXPECT_FLOAT_EQ(bone.start[0], 0.0f);
    EXPECT_FLOAT_EQ(bone.end[0], 0.01f);
    EXPECT_FLOAT_EQ(bone.end[3], 0.01f * frame_.settings.bone_radius_scale);
}

TEST_F(BuildInstances, EveryJointAndBoneOfBothHandsFits) {
    for (Hand& hand : frame_.hands) {
        hand.ghost_active = hand.physical_active = true;
    }
    for (int j = 0; j < kJointCount; ++j) {
        frame_.parents[j] = (j + 1) % kJointCount;
    }
    const DrawCounts counts = build();
    EXPECT_EQ(counts.total(), static_cast<uint32_t>(kMaxInstances));
}

TEST_F(BuildInstances, ContactTintOnlyOnTouchingPhysicalJointsWhenOn) {
    frame_.hands[1].physical_active = true;
    frame_.hands[1].ghost_active = true;
    frame_.hands[1].in_contact[4] = true;
    frame_.settings.contact_tint = {1.0f, 0.0f, 0.0f};
    frame_.settings.hand_colors[1] = {0.0f, 1.0f, 0.0f};
    DrawCounts counts = build();
    EXPECT_EQ(out_[4].color, (std::array<float, 4>{1.0f, 0.0f, 0.0f, 1.0f}));
    EXPECT_EQ(out_[5].color, (std::array<float, 4>{0.0f, 1.0f, 0.0f, 1.0f}));
    EXPECT_EQ(out_[counts.physical_capsules + 4].color,
              (std::array<float, 4>{0.0f, 1.0f, 0.0f, frame_.settings.ghost_alpha}));
    frame_.settings.tint = false;
    counts = build();
    EXPECT_EQ(out_[4].color, (std::array<float, 4>{0.0f, 1.0f, 0.0f, 1.0f}));
}

TEST_F(BuildInstances, BonesWithAnEndJointInContactAreTinted) {
    Hand& hand = frame_.hands[1];
    hand.physical_active = true;
    hand.in_contact[5] = true;
    frame_.parents[5] = 4;  // the bones of joints 5, 6 and 7, after the 26 joints
    frame_.parents[6] = 5;
    frame_.parents[7] = 6;
    frame_.settings.contact_tint = {1.0f, 0.0f, 0.0f};
    frame_.settings.hand_colors[1] = {0.0f, 1.0f, 0.0f};
    const DrawCounts counts = build();
    ASSERT_EQ(counts.physical_capsules, static_cast<uint32_t>(kJointCount + 3));
    const std::array<float, 4> tint{1.0f, 0.0f, 0.0f, 1.0f}, hand_color{0.0f, 1.0f, 0.0f, 1.0f};
    EXPECT_EQ(out_[kJointCount].color, tint);            // 4-5: its child end touches
    EXPECT_EQ(out_[kJointCount + 1].color, tint);        // 5-6: its parent end touches
    EXPECT_EQ(out_[kJointCount + 2].color, hand_color);  // 6-7: neither end touches
}

TEST_F(BuildInstances, GhostPartsWhereThePhysicalOnesAreAreLeftOut) {
    Hand& hand = frame_.hands[0];
    hand.physical_active = hand.ghost_active = true;
    frame_.parents[1] = 0;
    frame_.parents[2] = 1;
    frame_.parents[3] = 2;
    hand.ghost = hand.physical;
    hand.ghost.positions[2].y += 0.01f;  // only joint 2 pressed away
    const DrawCounts counts = build();
    EXPECT_EQ(counts.physical_capsules, 26u + 3u);
    EXPECT_EQ(counts.ghost, 1u + 2u) << "joint 2 and its bones to 1 and 3";
    EXPECT_EQ(out_[counts.physical_capsules].start[1], 0.01f);
    hand.physical_active = false;
    EXPECT_EQ(build().ghost, 26u + 3u) << "nothing hides the ghost";
}

TEST_F(BuildInstances, UnusableJointsAndTheirBonesAreLeftOut) {
    frame_.hands[0].physical_active = true;
    frame_.parents[1] = 0;
    frame_.parents[2] = 1;
    frame_.parents[3] = 40;  // not a joint
    frame_.hands[0].physical.positions[0].x = std::numeric_limits<float>::infinity();
    frame_.hands[0].physical.radii[5] = 0.0f;
    const DrawCounts counts = build();
    EXPECT_EQ(counts.physical_capsules, 24u + 1u);  // bone 1-2 only
}

TEST_F(BuildInstances, SolidsReplaceThePhysicalJointsCapsulesBeforeBoxes) {
    frame_.parents[1] = 0;
    for (Hand& hand : frame_.hands) hand.physical_active = true;
    Hand& right = frame_.hands[1];
    right.ghost_active = true;
    right.solid_count = 3;
    right.solids[0] =
        box({0.0f, 0.0f, -0.5f}, {0.0f, 0.0f, 0.70710677f, 0.70710677f}, {0.04f, 0.01f, 0.05f});
    right.solids[0].in_contact = true;
    right.solids[1] = capsule({0.0f, 0.0f, -0.5f}, {0.0f, 0.03f, -0.5f}, 0.008f);
    right.solids[2] = capsule({0.1f, 0.0f, -0.5f}, {0.1f, 0.0f, -0.5f}, 0.01f);
    frame_.settings.contact_tint = {1.0f, 0.0f, 0.0f};
    frame_.settings.hand_colors[1] = {0.0f, 1.0f, 0.0f};
    const DrawCounts counts = build();
    // The left hand has no solids: its 26 joints and one bone, then the right's capsules.
    ASSERT_EQ(counts.physical_capsules, 26u + 1u + 2u);
    ASSERT_EQ(counts.physical_boxes, 1u);
    EXPECT_EQ(counts.ghost, 26u + 1u);
    const PrimitiveInstance& capsule = out_[27];
    EXPECT_EQ(capsule.end[1], 0.03f);
    EXPECT_EQ(capsule.start[3], 0.008f);
    EXPECT_EQ(capsule.end[3], 0.008f);
    EXPECT_EQ(capsule.color, (std::array<float, 4>{0.0f, 1.0f, 0.0f, 1.0f}));
    const PrimitiveInstance& box = out_[counts.physical_capsules];
    EXPECT_EQ(box.start[2], -0.5f);
    EXPECT_EQ(box.end[0], 0.04f);
    EXPECT_EQ(box.end[2], 0.05f);
    EXPECT_EQ(box.orientation[3], 0.70710677f);
    EXPECT_EQ(box.color, (std::array<float, 4>{1.0f, 0.0f, 0.0f, 1.0f})) << "it touches";
    // The ghost is thinner than the joints it follows.
    const PrimitiveInstance& ghost = out_[counts.physical_capsules + counts.physical_boxes];
    EXPECT_FLOAT_EQ(ghost.start[3], kGhostThickness * 0.01f);
}

TEST_F(BuildInstances, UnusableSolidsAreLeftOut) {
    Hand& hand = frame_.hands[0];
    hand.physical_active = true;
    hand.solid_count = 4;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    hand.solids[0] = capsule({0.0f, 0.0f, -0.5f}, {0.0f, 0.0f, -0.5f}, 0.0f);
    hand.solids[1] = capsule({nan, 0.0f, -0.5f}, {0.0f, 0.0f, -0.5f}, 0.01f);
    hand.solids[2] = box({0.0f, 0.0f, -0.5f}, {0.0f, 0.0f, 0.0f, 0.0f}, {0.01f, 0.01f, 0.01f});
    hand.solids[3] = box({0.0f, 0.0f, -0.5f}, {}, {0.01f, -0.01f, 0.01f});
    EXPECT_EQ(build().total(), 0u);
    hand.solid_count = 1000;  // more than there is room for: only kMaxSolids are read
    EXPECT_EQ(build().total(), 0u);
}

TEST_F(BuildInstances, ColoursAreLinearAndGhostAlphaClamped) {
    frame_.hands[0].ghost_active = true;
    frame_.settings.hand_colors[0] = {0.5f, 1.0f, 0.0f};
    frame_.settings.ghost_alpha = 7.0f;
    build();
    EXPECT_NEAR(out_[0].color[0], 0.21404f, 1e-4);  // sRGB 0.5
    EXPECT_EQ(out_[0].color[1], 1.0f);
    EXPECT_EQ(out_[0].color[3], 1.0f);
    frame_.settings.ghost_alpha = 0.0f;
    EXPECT_EQ(build().ghost, 0u) << "an invisible ghost is not drawn";
}

}  // namespace
}  // namespace physhand::overlay
