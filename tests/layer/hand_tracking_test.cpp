// xrLocateHandJointsEXT through the layer: trackers, what a located hand carries, gating,
// idempotent locates, a hand blocked by a collider, tracking loss.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

constexpr XrSpaceLocationFlags kValidBits =
    XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
constexpr XrSpaceLocationFlags kTrackedBits =
    XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
constexpr XrSpaceVelocityFlags kVelocityBits =
    XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT;

int frames_until(double seconds) {
    return static_cast<int>(std::lround(seconds * 90.0));
}

// On the desk, not in it.
constexpr double kOnDesk = kDeskTop + kThinnestHandBody - kMaxPenetration;

// Every joint located: valid (and tracked when `tracked`), finite, unit orientation, a
// plausible radius, valid finite velocities.
void expect_well_formed(const HandJoints& hand, bool tracked) {
    ASSERT_TRUE(hand.locations.isActive);
    for (std::uint32_t j = 0; j < kJointCount; ++j) {
        SCOPED_TRACE("joint " + std::to_string(j));
        const XrHandJointLocationEXT& joint = hand.joints[j];
        EXPECT_EQ(joint.locationFlags & kValidBits, kValidBits);
        EXPECT_EQ(joint.locationFlags & kTrackedBits, tracked ? kTrackedBits : 0);
        EXPECT_TRUE(is_finite(joint.pose));
        EXPECT_LT(std::abs(unit_error(joint.pose.orientation)), 1e-5);
        EXPECT_TRUE(std::isfinite(joint.radius));
        EXPECT_GT(joint.radius, 0.003f);
        EXPECT_LT(joint.radius, 0.03f);
        const XrHandJointVelocityEXT& velocity = hand.joint_velocities[j];
        EXPECT_EQ(velocity.velocityFlags & kVelocityBits, kVelocityBits);
        EXPECT_TRUE(is_finite(velocity.linearVelocity));
        EXPECT_TRUE(is_finite(velocity.angularVelocity));
        EXPECT_LT(distance(velocity.linearVelocity, {0, 0, 0}), 5.0);
        EXPECT_LT(distance(velocity.angularVelocity, {0, 0, 0}), 50.0);
    }
}

class HandTracking : public LayerTest {};

TEST_F(HandTracking, TrackerIsCreatedLocatedAndDestroyed) {
    use_scene(still_hands_scene());
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    ASSERT_NE(right, XR_NULL_HANDLE);
    HandJoints joints;
    ASSERT_EQ(locate(right, stage_, frame(), joints), XR_SUCCESS);
    EXPECT_TRUE(joints.locations.isActive);
    EXPECT_NEAR(joints.pose(XR_HAND_JOINT_WRIST_EXT).position.y, 1.2, 1e-5);

    const auto destroy = function<PFN_xrDestroyHandTrackerEXT>("xrDestroyHandTrackerEXT");
    EXPECT_EQ(destroy(right), XR_SUCCESS);
    EXPECT_EQ(locate(right, stage_, frame(), joints), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(destroy(right), XR_ERROR_HANDLE_INVALID);
}

// Both hands moving, the right one pressing on the desk (simulated), the left one in the
// air (gated): every joint is valid, finite and carries velocities, and the velocities
// agree with the motion.
TEST_F(HandTracking, JointsRadiiAndVelocitiesAreFiniteAndValid) {
    use_scene(scene_with_hands(
        {{"right", pressing_hand(0.1)},
         {"left", keyframed_hand({{0.0, {-0.3, 1.2, -0.3}}, {1.0, {-0.1, 1.3, -0.35}}}, 0.5)}}));
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    create_desk();
    const XrHandTrackerEXT trackers[] = {hand_tracker(XR_HAND_LEFT_EXT),
                                         hand_tracker(XR_HAND_RIGHT_EXT)};
    std::array<std::optional<XrVector3f>, 2> previous_tip;
    bool right_simulated = false;
    for (int f = 0; f < frames_until(1.5); ++f) {
        const XrTime time = frame();
        for (int side = 0; side < 2; ++side) {
            SCOPED_TRACE(std::string(side == 0 ? "left" : "right") + " hand, frame " +
                         std::to_string(f));
            HandJoints hand;
            ASSERT_EQ(locate(trackers[side], stage_, time, hand), XR_SUCCESS);
            expect_well_formed(hand, true);
            EXPECT_TRUE(hand.physical.ghostIsActive);
            if (side == 1) right_simulated |= hand.physical.isSimulated == XR_TRUE;
            // Velocity against the frame-to-frame motion, for a hand the layer leaves alone.
            const XrVector3f& tip = hand.pose(XR_HAND_JOINT_INDEX_TIP_EXT).position;
            if (previous_tip[side] && !hand.physical.isSimulated) {
                const XrVector3f& v =
                    hand.joint_velocities[XR_HAND_JOINT_INDEX_TIP_EXT].linearVelocity;
                const XrVector3f moved = {(tip.x - previous_tip[side]->x) * 90.0f,
                                          (tip.y - previous_tip[side]->y) * 90.0f,
                                          (tip.z - previous_tip[side]->z) * 90.0f};
                EXPECT_LT(distance(v, moved), 0.05);
            }
            previous_tip[side] = tip;
        }
    }
    EXPECT_TRUE(right_simulated);
}

// A hand with no collider near it is the runtime's hand, bit for bit, velocities included:
// the same as with the layer off.
TEST_F(HandTracking, GatedHandsAreExactlyTheRuntimes) {
    use_scene(scene_with_hands(
        {{"right", keyframed_hand({{0.0, {0.2, 1.2, -0.3}}, {1.0, {0.1, 1.4, -0.5}}}, 0.3)},
         {"left", keyframed_hand({{0.0, {-0.3, 1.2, -0.3}}, {1.0, {-0.1, 1.3, -0.35}}}, 0.5)}}));
    const int count = frames_until(1.2);
    const RunResult ghost = record_run(LayerMode::Disabled, count);
    ASSERT_EQ(ghost.right.size(), static_cast<std::size_t>(count));

    use_layer(LayerMode::Implicit);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrHandTrackerEXT left = hand_tracker(XR_HAND_LEFT_EXT);
    for (int f = 0; f < count; ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        const XrTime time = frame();
        for (const auto& [tracker, expected] :
             {std::pair{right, &ghost.right[f]}, std::pair{left, &ghost.left[f]}}) {
            HandJoints hand;
            ASSERT_EQ(locate(tracker, stage_, time, hand), XR_SUCCESS);
            HandSample got;
            got.is_active = hand.locations.isActive;
            got.joints = hand.joints;
            got.velocities = hand.joint_velocities;
            EXPECT_TRUE(same_bits(got, *expected));
            EXPECT_EQ(hand.physical.isSimulated, XR_FALSE);
            EXPECT_EQ(hand.physical.ghostIsActive, XR_TRUE);
            for (std::uint32_t j = 0; j < kJointCount; ++j) {
                EXPECT_TRUE(same_bits(hand.ghost[j], hand.joints[j].pose));
                EXPECT_EQ(hand.in_contact[j], XR_FALSE);
                EXPECT_EQ(hand.spring_force[j], 0.0f);
            }
        }
    }
}

// Locating again at the same time returns the same state bit for bit and steps nothing: a
// falling collider stays where it was; an earlier time does not step back either.
TEST_F(HandTracking, LocatingTheSameTimeTwiceStepsNothing) {
    use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    create_desk();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrTime start = frame();
    const auto ball = create_collider(collider_info(
        XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND, XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND,
        stage_, pose_at(0.6f, 1.8f, -0.6f), start));  // beside the desk
    const XrTime time = simulate_frames(frames_until(0.9));

    HandJoints first, second;
    ASSERT_EQ(locate(right, stage_, time, first), XR_SUCCESS);
    ASSERT_EQ(first.physical.isSimulated, XR_TRUE);  // the desk is within reach
    const auto ball_first = locate_collider(ball, time);
    ASSERT_EQ(locate(right, stage_, time, second), XR_SUCCESS);
    const auto ball_second = locate_collider(ball, time);

    EXPECT_EQ(std::memcmp(first.joints.data(), second.joints.data(), sizeof(first.joints)), 0);
    EXPECT_EQ(std::memcmp(first.joint_velocities.data(), second.joint_velocities.data(),
                          sizeof(first.joint_velocities)),
              0);
    EXPECT_EQ(std::memcmp(first.ghost.data(), second.ghost.data(), sizeof(first.ghost)), 0);
    EXPECT_EQ(std::memcmp(first.spring_force.data(), second.spring_force.data(),
                          sizeof(first.spring_force)),
              0);
    EXPECT_TRUE(same_bits(ball_first.pose, ball_second.pose));
    EXPECT_TRUE(same_bits(ball_first.linearVelocity, ball_second.linearVelocity));
    EXPECT_LT(ball_first.linearVelocity.y, -1.0f);  // it is falling

    // One frame later it has fallen further; asking about the earlier time again steps
    // nothing backwards.
    const XrTime next = frame();
    const auto ball_next = locate_collider(ball, next);
    EXPECT_LT(ball_next.pose.position.y, ball_first.pose.position.y - 0.005f);
    const auto ball_back = locate_collider(ball, time);
    EXPECT_TRUE(same_bits(ball_back.pose, ball_next.pose));
}

// The ghost palm sinks into the desk; the physical one stays on it.
TEST_F(HandTracking, HandIsBlockedByAStaticBox) {
    use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    frame();
    const auto desk = create_desk();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    double lowest = std::numeric_limits<double>::infinity();
    HandJoints hand;
    for (int f = 0; f < frames_until(2.0); ++f) {
        ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
        lowest = std::min(lowest, lowest_joint_over_desk(hand.joints));
    }
    // The ghost palm is well inside the desk, within its footprint.
    const XrPosef& ghost_palm = hand.ghost_pose(XR_HAND_JOINT_PALM_EXT);
    EXPECT_LT(ghost_palm.position.y, kDeskTop - 0.01f);
    EXPECT_GT(ghost_palm.position.y, kDeskTop - 2 * kDeskHalfExtents.y);
    EXPECT_LT(std::abs(ghost_palm.position.z - kDeskCenter.z), kDeskHalfExtents.z);
    // The physical hand is on the desk, not in it, and says so.
    const XrHandJointLocationEXT& palm = hand.joints[XR_HAND_JOINT_PALM_EXT];
    EXPECT_GE(palm.pose.position.y, kOnDesk);
    EXPECT_GE(lowest, kOnDesk);
    EXPECT_EQ(hand.physical.isSimulated, XR_TRUE);
    EXPECT_TRUE(hand.any_contact());
    EXPECT_GT(*std::max_element(hand.spring_force.begin(), hand.spring_force.end()), 1.0f);
    const auto flags = locate_collider(desk, now()).flags;
    EXPECT_TRUE(flags & XR_PHYSICAL_COLLIDER_TOUCHED_BY_RIGHT_BIT_PHYSHAND);
    EXPECT_FALSE(flags & XR_PHYSICAL_COLLIDER_TOUCHED_BY_LEFT_BIT_PHYSHAND);
}

// Radii as returned are what collides: every joint's sphere, drawn where it is returned,
// stays on the desk the hand rests on (the runtime's wrist is 18 mm round, the palm box it
// lies in 19 mm thick), but for the ball of the thumb, lower than the palm box: the joints'
// closing, after the contacts, pulls it down after the palm, 6.1 mm into the desk
// (docs/design.md). The ghost's are the runtime's own.
TEST_F(HandTracking, ReturnedJointSpheresRestOnTheDeskNotInIt) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    double deepest = 0.0, thumb_base = 0.0;
    int simulated = 0;
    for (int f = 0; f < frames_until(2.0); ++f) {
        ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
        if (!hand.physical.isSimulated) continue;  // far from the desk: the runtime's hand
        ++simulated;
        for (std::size_t j = 0; j < hand.joints.size(); ++j) {
            const XrHandJointLocationEXT& joint = hand.joints[j];
            const XrVector3f& p = joint.pose.position;
            if (std::abs(p.x - kDeskCenter.x) > kDeskHalfExtents.x ||
                std::abs(p.z - kDeskCenter.z) > kDeskHalfExtents.z) {
                continue;
            }
            double& depth = j == XR_HAND_JOINT_THUMB_METACARPAL_EXT ? thumb_base : deepest;
            depth = std::max(depth, kDeskTop - (p.y - double(joint.radius)));
        }
    }
    EXPECT_GT(simulated, frames_until(1.0));
    // As deep as the hand's bodies may go (the runtime's wrist sphere went 8 mm in).
    EXPECT_LT(deepest, kMaxPenetration);
    EXPECT_LT(thumb_base, 0.008);
    EXPECT_TRUE(hand.any_contact());
}

// Losing tracking briefly: the physical hand holds, valid but not tracked, stays finite,
// and follows the ghost again afterwards.
TEST_F(HandTracking, TrackingDropoutKeepsTheHandFiniteAndItRecovers) {
    auto scene = scene_with_hands({{"right", pressing_hand(0.1)}});
    scene["tracking"] = {{"dropouts", {{{"hand", "right"}, {"from_s", 1.5}, {"to_s", 1.7}}}}};
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene));
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    int lost_frames = 0;
    HandJoints hand;
    for (int f = 0; f < frames_until(2.5); ++f) {
        SCOPED_TRACE("frame " + std::to_string(f));
        ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
        if (!hand.physical.ghostIsActive) {
            ++lost_frames;
            // Within the grace period the hand holds still rather than letting go.
            expect_well_formed(hand, false);
        } else {
            expect_well_formed(hand, true);
        }
        EXPECT_GE(lowest_joint_over_desk(hand.joints), kOnDesk);
    }
    EXPECT_GE(lost_frames, 15);
    EXPECT_EQ(hand.physical.ghostIsActive, XR_TRUE);
    EXPECT_EQ(hand.physical.isSimulated, XR_TRUE);
    EXPECT_TRUE(hand.any_contact());
}

// The simulation follows the first tracker of a hand; when it goes, the next one takes
// over and the hand stays physical.
TEST_F(HandTracking, ASecondTrackerOfAHandKeepsWorkingWhenTheFirstIsDestroyed) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT first = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrHandTrackerEXT second = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints a, b;
    for (int f = 0; f < frames_until(1.0); ++f) {
        const XrTime time = frame();
        ASSERT_EQ(locate(first, stage_, time, a), XR_SUCCESS);
        ASSERT_EQ(locate(second, stage_, time, b), XR_SUCCESS);
        EXPECT_EQ(std::memcmp(a.joints.data(), b.joints.data(), sizeof(a.joints)), 0);
    }
    EXPECT_EQ(function<PFN_xrDestroyHandTrackerEXT>("xrDestroyHandTrackerEXT")(first), XR_SUCCESS);
    for (int f = 0; f < frames_until(1.0); ++f) {
        ASSERT_EQ(locate(second, stage_, frame(), b), XR_SUCCESS);
        expect_well_formed(b, true);
    }
    EXPECT_EQ(b.physical.isSimulated, XR_TRUE);
    EXPECT_TRUE(b.any_contact());
    EXPECT_LT(b.ghost_pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop - 0.01f);
    EXPECT_GE(lowest_joint_over_desk(b.joints), kOnDesk);
}

// A hand the runtime never tracks stays inactive, colliders or not.
TEST_F(HandTracking, AnUntrackedHandStaysInactive) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT left = hand_tracker(XR_HAND_LEFT_EXT);
    HandJoints hand;
    for (int f = 0; f < 30; ++f) {
        ASSERT_EQ(locate(left, stage_, frame(), hand), XR_SUCCESS);
        EXPECT_EQ(hand.locations.isActive, XR_FALSE);
        EXPECT_EQ(hand.physical.ghostIsActive, XR_FALSE);
        EXPECT_EQ(hand.physical.isSimulated, XR_FALSE);
        for (const auto& joint : hand.joints) EXPECT_EQ(joint.locationFlags, 0u);
    }
}

}  // namespace
}  // namespace physhand::layer_test
