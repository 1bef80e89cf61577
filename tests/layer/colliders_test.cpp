// The extension's colliders: every shape and motion, created, moved, simulated and read
// back.

#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

constexpr double kGravity = 9.81;
constexpr double kFrame = 1.0 / 90.0;

// 30 degrees about +Y.
constexpr XrQuaternionf kTurned = {0.0f, 0.25881904f, 0.0f, 0.96592583f};

void expect_pose_near(const XrPosef& actual, const XrPosef& expected, double tolerance = 1e-5) {
    EXPECT_LT(distance(actual.position, expected.position), tolerance);
    const XrQuaternionf& a = actual.orientation;
    const XrQuaternionf& b = expected.orientation;
    const double dot =
        double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z + double(a.w) * b.w;
    EXPECT_GT(std::abs(dot), 1.0 - 1e-6);
}

void expect_at_rest(const XrPhysicalColliderLocationPHYSHAND& location, double tolerance = 1e-6) {
    EXPECT_LT(distance(location.linearVelocity, {0, 0, 0}), tolerance);
    EXPECT_LT(distance(location.angularVelocity, {0, 0, 0}), tolerance);
}

constexpr XrSpaceLocationFlags kLocated =
    XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
    XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;

class Colliders : public LayerTest {
  protected:
    void SetUp() override {
        LayerTest::SetUp();
        use_scene(still_hands_scene());
        ASSERT_EQ(create_instance(), XR_SUCCESS);
        start_session();
        start_ = frame();
        // The simulation's clock starts at the first time anything is located; colliders
        // created at that time are then exactly where they were put.
        std::vector<XrPhysicalColliderLocationPHYSHAND> none;
        ASSERT_EQ(locate_colliders({}, stage_, start_, none), XR_SUCCESS);
    }
    XrTime start_ = 0;
};

using ShapeMotion = std::tuple<XrPhysicalColliderShapePHYSHAND, XrPhysicalColliderMotionPHYSHAND>;

class EveryShapeAndMotion : public Colliders, public ::testing::WithParamInterface<ShapeMotion> {};

// Created in LOCAL (1.6 m above the STAGE origin), read back in both spaces; then static
// stays put, kinematic follows its target, dynamic falls freely.
TEST_P(EveryShapeAndMotion, IsCreatedWhereAskedAndMovesAsItsMotionSays) {
    const auto [shape, motion] = GetParam();
    const XrPosef in_local = pose_at(0.3f, -0.6f, -0.8f, kTurned);
    const XrPosef in_stage = pose_at(0.3f, 1.0f, -0.8f, kTurned);
    auto info = collider_info(shape, motion, local_, in_local, start_);
    const bool static_only = shape == XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND ||
                             shape == XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND;
    if (static_only && motion != XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND) {
        XrPhysicalColliderPHYSHAND collider = XR_NULL_HANDLE;
        EXPECT_EQ(api().create_collider(session_, &info, &collider), XR_ERROR_VALIDATION_FAILURE);
        EXPECT_EQ(collider, XR_NULL_HANDLE);
        return;
    }
    const auto collider = create_collider(info);
    ASSERT_NE(collider, XR_NULL_HANDLE);

    std::vector<XrPhysicalColliderLocationPHYSHAND> located;
    ASSERT_EQ(locate_colliders({collider}, local_, start_, located), XR_SUCCESS);
    EXPECT_EQ(located[0].locationFlags & kLocated, kLocated);
    expect_pose_near(located[0].pose, in_local);
    expect_at_rest(located[0]);
    EXPECT_EQ(located[0].flags & (XR_PHYSICAL_COLLIDER_TOUCHED_BY_LEFT_BIT_PHYSHAND |
                                  XR_PHYSICAL_COLLIDER_TOUCHED_BY_RIGHT_BIT_PHYSHAND),
              0u);
    const auto start = locate_collider(collider, start_);
    expect_pose_near(start.pose, in_stage);

    const int count = 45;
    switch (motion) {
        case XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND: {
            const auto later = locate_collider(collider, simulate_frames(count));
            EXPECT_TRUE(same_bits(later.pose, start.pose));
            expect_at_rest(later);
            break;
        }
        case XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND: {
            const XrPosef target = pose_at(0.4f, 1.1f, -0.8f);
            auto pose_info = xr<XrPhysicalColliderPoseInfoPHYSHAND>(
                XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND);
            pose_info.space = stage_;
            pose_info.time = start_;
            pose_info.pose = target;
            ASSERT_EQ(api().set_pose(collider, &pose_info), XR_SUCCESS);
            // Not there before the next step, there at its end, moving on the way.
            expect_pose_near(locate_collider(collider, start_).pose, in_stage);
            const auto moved = locate_collider(collider, simulate_frames(1));
            expect_pose_near(moved.pose, target);
            // (Its velocity reads 0: the layer reports velocities of dynamic colliders only.)
            EXPECT_TRUE(is_finite(moved.linearVelocity));
            // Then it stays there.
            const auto later = locate_collider(collider, simulate_frames(count));
            expect_pose_near(later.pose, target);
            expect_at_rest(later, 1e-3);
            break;
        }
        case XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND: {
            const auto later = locate_collider(collider, simulate_frames(count));
            // It falls from the physics frame before the first display time: shown at display
            // times off the physics' 90 Hz grid (no frame loop), up to a frame longer.
            const double t = count * kFrame;
            const double fall = start.pose.position.y - later.pose.position.y;
            EXPECT_GT(fall, 0.97 * 0.5 * kGravity * t * t);
            EXPECT_LT(fall, 1.03 * 0.5 * kGravity * (t + kFrame) * (t + kFrame));
            EXPECT_GT(-later.linearVelocity.y, 0.97 * kGravity * t);
            EXPECT_LT(-later.linearVelocity.y, 1.03 * kGravity * (t + kFrame));
            EXPECT_NEAR(later.pose.position.x, start.pose.position.x, 1e-4);
            EXPECT_NEAR(later.pose.position.z, start.pose.position.z, 1e-4);
            EXPECT_FALSE(later.flags & XR_PHYSICAL_COLLIDER_ASLEEP_BIT_PHYSHAND);
            break;
        }
        default:
            FAIL();
    }
}

INSTANTIATE_TEST_SUITE_P(
    Colliders, EveryShapeAndMotion,
    ::testing::Combine(::testing::Values(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_SHAPE_CYLINDER_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND),
                       ::testing::Values(XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND,
                                         XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND)),
    [](const auto& info) {
        const auto motion = std::get<1>(info.param);
        return std::string(shape_name(std::get<0>(info.param))) +
               (motion == XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND      ? "Static"
                : motion == XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND ? "Kinematic"
                                                                           : "Dynamic");
    });

// A dynamic box dropped on a static one lands on it, comes to rest and falls asleep;
// a teleport wakes it.
TEST_F(Colliders, DynamicColliderFallsOntoAStaticOneRestsAndSleeps) {
    const auto desk = create_desk();
    auto info = collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND, stage_,
                              pose_at(0.0f, kDeskTop + 0.2f, -0.4f), start_);
    info.halfExtents = {0.03f, 0.03f, 0.03f};
    const auto box = create_collider(info);

    const auto falling = locate_collider(box, simulate_frames(10));
    EXPECT_LT(falling.linearVelocity.y, -0.5f);
    EXPECT_FALSE(falling.flags & XR_PHYSICAL_COLLIDER_ASLEEP_BIT_PHYSHAND);

    const auto landed = locate_collider(box, simulate_frames(4 * 90));
    EXPECT_NEAR(landed.pose.position.y, kDeskTop + 0.03f, 0.002);
    EXPECT_NEAR(landed.pose.position.x, 0.0f, 0.002);
    EXPECT_NEAR(landed.pose.position.z, -0.4f, 0.002);
    EXPECT_LT(distance(landed.linearVelocity, {0, 0, 0}), 0.01);
    EXPECT_TRUE(landed.flags & XR_PHYSICAL_COLLIDER_ASLEEP_BIT_PHYSHAND);
    // No hand came near either of them.
    const auto desk_location = locate_collider(desk, now());
    EXPECT_EQ(desk_location.flags & (XR_PHYSICAL_COLLIDER_TOUCHED_BY_LEFT_BIT_PHYSHAND |
                                     XR_PHYSICAL_COLLIDER_TOUCHED_BY_RIGHT_BIT_PHYSHAND),
              0u);
    expect_pose_near(desk_location.pose, {{0, 0, 0, 1}, kDeskCenter});

    auto teleport =
        xr<XrPhysicalColliderPoseInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND);
    teleport.space = stage_;
    teleport.time = now();
    teleport.pose = pose_at(0.0f, kDeskTop + 0.3f, -0.4f);
    teleport.teleport = XR_TRUE;
    ASSERT_EQ(api().set_pose(box, &teleport), XR_SUCCESS);
    const auto woken = locate_collider(box, now());
    EXPECT_FALSE(woken.flags & XR_PHYSICAL_COLLIDER_ASLEEP_BIT_PHYSHAND);
    const auto refalling = locate_collider(box, simulate_frames(5));
    EXPECT_LT(refalling.pose.position.y, kDeskTop + 0.3f - 0.005f);
}

// Teleport places any collider at once; a dynamic one takes the given velocities, the
// others ignore them.
TEST_F(Colliders, TeleportPlacesAnyColliderAndGivesDynamicOnesVelocity) {
    std::vector<XrPhysicalColliderPHYSHAND> colliders;
    for (const auto motion : {XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND}) {
        colliders.push_back(
            create_collider(collider_info(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND, motion,
                                          stage_, pose_at(-1.0f, 2.0f, -2.0f), start_)));
    }
    // Teleports happen at the simulation's time: it is brought to `time` first.
    const XrTime time = simulate_frames(3);
    auto teleport =
        xr<XrPhysicalColliderPoseInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND);
    teleport.space = local_;  // velocities in LOCAL's axes, which are STAGE's
    teleport.time = time;
    teleport.teleport = XR_TRUE;
    teleport.linearVelocity = {1.0f, 2.0f, 0.0f};
    teleport.angularVelocity = {0.0f, 0.0f, 3.0f};
    for (std::size_t i = 0; i < colliders.size(); ++i) {
        teleport.pose = pose_at(0.5f * static_cast<float>(i), 0.5f, -1.0f, kTurned);
        ASSERT_EQ(api().set_pose(colliders[i], &teleport), XR_SUCCESS);
    }
    std::vector<XrPhysicalColliderLocationPHYSHAND> at_once;
    ASSERT_EQ(locate_colliders(colliders, stage_, time, at_once), XR_SUCCESS);
    for (std::size_t i = 0; i < colliders.size(); ++i) {
        SCOPED_TRACE("collider " + std::to_string(i));
        expect_pose_near(at_once[i].pose,
                         pose_at(0.5f * static_cast<float>(i), 2.1f, -1.0f, kTurned));
    }
    expect_at_rest(at_once[0]);
    expect_at_rest(at_once[1]);
    EXPECT_LT(distance(at_once[2].linearVelocity, {1.0f, 2.0f, 0.0f}), 1e-5);
    EXPECT_LT(distance(at_once[2].angularVelocity, {0.0f, 0.0f, 3.0f}), 1e-5);

    std::vector<XrPhysicalColliderLocationPHYSHAND> after;
    ASSERT_EQ(locate_colliders(colliders, stage_, simulate_frames(1), after), XR_SUCCESS);
    EXPECT_TRUE(same_bits(after[0].pose, at_once[0].pose));
    EXPECT_TRUE(same_bits(after[1].pose, at_once[1].pose));
    EXPECT_NEAR(after[2].pose.position.x - at_once[2].pose.position.x, 1.0 * kFrame, 1e-4);
    EXPECT_NEAR(after[2].linearVelocity.y, 2.0 - kGravity * kFrame, 1e-3);
    EXPECT_NEAR(after[2].angularVelocity.z, 3.0, 1e-3);
}

// A kinematic collider moved into a dynamic one pushes it, and is not pushed back.
TEST_F(Colliders, KinematicColliderPushesADynamicOne) {
    create_collider(collider_info(XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND,
                                  XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND, stage_,
                                  identity_pose(), start_));
    auto ball_info = collider_info(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND,
                                   XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND, stage_,
                                   pose_at(0.0f, 0.05f, -1.0f), start_);
    const auto ball = create_collider(ball_info);
    const auto pusher = create_collider(collider_info(
        XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND, XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND,
        stage_, pose_at(-0.3f, 0.05f, -1.0f), start_));
    simulate_frames(30);  // the ball settles on the floor
    auto target =
        xr<XrPhysicalColliderPoseInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND);
    target.space = stage_;
    for (int f = 1; f <= 45; ++f) {
        target.time = now();
        target.pose = pose_at(-0.3f + 0.01f * static_cast<float>(f), 0.05f, -1.0f);
        ASSERT_EQ(api().set_pose(pusher, &target), XR_SUCCESS);
        simulate_frames(1);
    }
    std::vector<XrPhysicalColliderLocationPHYSHAND> located;
    ASSERT_EQ(locate_colliders({ball, pusher}, stage_, now(), located), XR_SUCCESS);
    expect_pose_near(located[1].pose, pose_at(0.15f, 0.05f, -1.0f));
    EXPECT_GT(located[0].pose.position.x, 0.15f + 0.05f + 0.05f - 0.005f);  // ahead of it
    EXPECT_GT(located[0].linearVelocity.x, 0.1f);
    EXPECT_NEAR(located[0].pose.position.y, 0.05f, 0.005f);  // still on the floor
}

using ColliderLifecycle = LayerTest;

// A destroyed collider is gone: its handle is invalid and the hand no longer meets it.
TEST_F(ColliderLifecycle, DestroyedColliderIsGoneFromTheSimulation) {
    use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const auto desk = create_desk();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    for (int f = 0; f < 120; ++f) ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
    ASSERT_EQ(hand.physical.isSimulated, XR_TRUE);
    ASSERT_TRUE(hand.any_contact());

    EXPECT_EQ(api().destroy_collider(desk), XR_SUCCESS);
    EXPECT_EQ(api().destroy_collider(desk), XR_ERROR_HANDLE_INVALID);
    std::vector<XrPhysicalColliderLocationPHYSHAND> located;
    EXPECT_EQ(locate_colliders({desk}, stage_, now(), located), XR_ERROR_HANDLE_INVALID);
    // With nothing near, the hand is the ghost again.
    for (int f = 0; f < 30; ++f) ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
    EXPECT_EQ(hand.physical.isSimulated, XR_FALSE);
    for (std::uint32_t j = 0; j < kJointCount; ++j) {
        EXPECT_TRUE(same_bits(hand.joints[j].pose, hand.ghost[j]));
    }
}

}  // namespace
}  // namespace physhand::layer_test
