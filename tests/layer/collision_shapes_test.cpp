// XrHandCollisionShapesPHYSHAND (spec version 2): the bodies a physical hand collides as,
// chained to xrLocateHandJointsEXT, by the two-call idiom.

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

using Shapes = std::array<XrHandCollisionShapePHYSHAND, kJointCount>;

class CollisionShapes : public LayerTest {
  protected:
    // Locates `tracker` in STAGE at `time` with the shapes chained (capacity `capacity`,
    // into shapes_ unless `null_array`); the joints go to joints_.
    XrResult locate_shapes(XrHandTrackerEXT tracker, XrTime time, std::uint32_t capacity,
                           bool null_array = false) {
        auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
        info.baseSpace = stage_;
        info.time = time;
        shapes_info_ = xr<XrHandCollisionShapesPHYSHAND>(XR_TYPE_HAND_COLLISION_SHAPES_PHYSHAND);
        shapes_info_.shapeCapacityInput = capacity;
        shapes_info_.shapeCountOutput = 0xDEAD;
        shapes_info_.shapes = null_array ? nullptr : shapes_.data();
        auto locations = xr<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
        locations.next = &shapes_info_;
        locations.jointCount = kJointCount;
        locations.jointLocations = joints_.data();
        const XrResult result = function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")(
            tracker, &info, &locations);
        EXPECT_EQ(locations.next, &shapes_info_) << "the app's chain is left as it was";
        return result;
    }

    // The distance from `p` to the shape: to a sphere's centre, a capsule's axis or a box's
    // centre.
    static double to_core(const XrHandCollisionShapePHYSHAND& shape, const XrVector3f& p) {
        const XrVector3f& c = shape.pose.position;
        if (shape.kind != XR_HAND_COLLISION_SHAPE_KIND_CAPSULE_PHYSHAND) return distance(c, p);
        const XrQuaternionf& q = shape.pose.orientation;
        // The pose's Z axis.
        const std::array<double, 3> z = {2 * (q.x * q.z + q.w * q.y), 2 * (q.y * q.z - q.w * q.x),
                                         1 - 2 * (q.x * q.x + q.y * q.y)};
        const std::array<double, 3> d = {p.x - c.x, p.y - c.y, p.z - c.z};
        const double along = std::clamp(d[0] * z[0] + d[1] * z[1] + d[2] * z[2],
                                        -double(shape.size.z), double(shape.size.z));
        return std::hypot(d[0] - along * z[0], d[1] - along * z[1], d[2] - along * z[2]);
    }

    // Every joint lies on the core of some shape.
    void expect_joints_on_shapes(std::uint32_t count) const {
        for (std::uint32_t j = 0; j < kJointCount; ++j) {
            if (j == XR_HAND_JOINT_PALM_EXT || j == XR_HAND_JOINT_WRIST_EXT ||
                (j >= XR_HAND_JOINT_INDEX_METACARPAL_EXT && j % 5 == 1)) {
                continue;  // carried by the palm box, inside it
            }
            double nearest = 1.0;
            for (std::uint32_t i = 0; i < count; ++i) {
                nearest = std::min(nearest, to_core(shapes_[i], joints_[j].pose.position));
            }
            EXPECT_LT(nearest, 2e-5) << "joint " << j;
        }
    }

    XrHandCollisionShapesPHYSHAND shapes_info_{};
    Shapes shapes_{};
    std::array<XrHandJointLocationEXT, kJointCount> joints_{};
};

// The default drive's hand pressed on the desk: a palm box lying flat just above it, where the
// ball of the thumb (the thumb's first capsule, thicker than the box), touching the desk,
// holds it, and a capsule per finger bone through the returned joints; asked for its count
// first.
TEST_F(CollisionShapes, ThePressedHandIsAPalmBoxOnTheDeskAndABonesCapsules) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrTime time = simulate_frames(120);
    ASSERT_EQ(locate_shapes(right, time, 0), XR_SUCCESS);
    ASSERT_EQ(shapes_info_.shapeCountOutput, 16u);
    ASSERT_EQ(locate_shapes(right, time, 16), XR_SUCCESS);
    ASSERT_EQ(shapes_info_.shapeCountOutput, 16u);
    const XrHandCollisionShapePHYSHAND& palm = shapes_[0];
    ASSERT_EQ(palm.kind, XR_HAND_COLLISION_SHAPE_KIND_BOX_PHYSHAND);
    EXPECT_TRUE(shapes_[1].inContact);
    // Lying flat: its underside is half its thickness (y) below its centre.
    EXPECT_NEAR(palm.pose.position.y - palm.size.y, kDeskTop, kMaxPenetration);
    EXPECT_GT(palm.pose.position.y - palm.size.y, kDeskTop);
    for (std::uint32_t i = 1; i < 16; ++i) {
        EXPECT_EQ(shapes_[i].kind, XR_HAND_COLLISION_SHAPE_KIND_CAPSULE_PHYSHAND);
        EXPECT_GT(shapes_[i].size.x, 0.003f);
        EXPECT_GT(shapes_[i].size.z, 0.005f);
        EXPECT_LT(std::abs(unit_error(shapes_[i].pose.orientation)), 1e-5);
    }
    expect_joints_on_shapes(16);
}

// The joint-sphere drives' hands are a sphere per joint, as large as the joint's radius.
TEST_F(CollisionShapes, TheImplicitDrivesHandIsASpherePerJoint) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    ASSERT_EQ(set_drive(XR_HAND_DRIVE_KIND_IMPLICIT_PHYSHAND), XR_SUCCESS);
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrTime time = simulate_frames(120);
    ASSERT_EQ(locate_shapes(right, time, kJointCount), XR_SUCCESS);
    ASSERT_EQ(shapes_info_.shapeCountOutput, kJointCount);
    for (std::uint32_t j = 0; j < kJointCount; ++j) {
        EXPECT_EQ(shapes_[j].kind, XR_HAND_COLLISION_SHAPE_KIND_SPHERE_PHYSHAND);
        EXPECT_LT(distance(shapes_[j].pose.position, joints_[j].pose.position), 1e-6);
        EXPECT_FLOAT_EQ(shapes_[j].size.x, joints_[j].radius);
    }
}

// Far from every collider the hand is the runtime's, and its shapes are where its bodies
// would be on it.
TEST_F(CollisionShapes, AHandFarFromCollidersHasTheShapesItWouldHave) {
    use_scene(still_hands_scene());
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrTime time = frame();
    ASSERT_EQ(locate_shapes(right, time, kJointCount), XR_SUCCESS);
    ASSERT_EQ(shapes_info_.shapeCountOutput, 16u);
    expect_joints_on_shapes(16);
}

TEST_F(CollisionShapes, AnUntrackedHandHasNone) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT left = hand_tracker(XR_HAND_LEFT_EXT);
    ASSERT_EQ(locate_shapes(left, frame(), kJointCount), XR_SUCCESS);
    EXPECT_EQ(shapes_info_.shapeCountOutput, 0u);
}

// The two-call idiom's errors: too small an array, and none at all.
TEST_F(CollisionShapes, TooSmallOrMissingArraysAreRefused) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrTime time = frame();
    EXPECT_EQ(locate_shapes(right, time, 5), XR_ERROR_SIZE_INSUFFICIENT);
    EXPECT_EQ(shapes_info_.shapeCountOutput, 16u);
    EXPECT_EQ(locate_shapes(right, time, kJointCount, true), XR_ERROR_VALIDATION_FAILURE);
}

}  // namespace
}  // namespace physhand::layer_test
