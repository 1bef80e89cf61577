// Lifetimes and concurrency: sessions destroyed with live children, instances created
// again, two threads locating hands while the frame loop runs, and drive changes.

#include <algorithm>
#include <barrier>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

constexpr int kPressFrames = 150;  // the hands are on the desk from frame 90 on

nlohmann::json both_hands_pressing() {
    return scene_with_hands({{"left", pressing_hand(-0.2)}, {"right", pressing_hand(0.2)}});
}

float max_spring_force(const HandJoints& hand) {
    return *std::max_element(hand.spring_force.begin(), hand.spring_force.end());
}

class Lifecycle : public LayerTest {};

// Destroying a session takes its trackers and colliders with it; the instance goes on.
TEST_F(Lifecycle, DestroyingASessionInvalidatesItsTrackersAndColliders) {
    use_scene(both_hands_pressing());
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    frame();
    const auto desk = create_desk();
    const auto ball = create_collider(collider_info(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND,
                                                    XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND,
                                                    stage_, pose_at(0, 1.5f, -0.5f), now()));
    const XrHandTrackerEXT left = hand_tracker(XR_HAND_LEFT_EXT);
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    for (int f = 0; f < 100; ++f) {
        const XrTime time = frame();
        ASSERT_EQ(locate(left, stage_, time, hand), XR_SUCCESS);
        ASSERT_EQ(locate(right, stage_, time, hand), XR_SUCCESS);
    }
    ASSERT_EQ(hand.physical.isSimulated, XR_TRUE);
    const XrSession dead = session_;
    const XrSpace dead_stage = stage_;
    const XrTime time = now();
    destroy_session();  // while running, with everything alive

    EXPECT_EQ(locate(right, dead_stage, time, hand), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(function<PFN_xrDestroyHandTrackerEXT>("xrDestroyHandTrackerEXT")(left),
              XR_ERROR_HANDLE_INVALID);
    std::vector<XrPhysicalColliderLocationPHYSHAND> located;
    EXPECT_EQ(locate_colliders({desk, ball}, dead_stage, time, located, dead),
              XR_ERROR_HANDLE_INVALID);
    auto pose =
        xr<XrPhysicalColliderPoseInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND);
    pose.space = dead_stage;
    pose.time = time;
    pose.pose = identity_pose();
    pose.teleport = XR_TRUE;
    EXPECT_EQ(api().set_pose(ball, &pose), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().destroy_collider(desk), XR_ERROR_HANDLE_INVALID);
    auto info = collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND, dead_stage,
                              identity_pose(), time);
    XrPhysicalColliderPHYSHAND collider = XR_NULL_HANDLE;
    EXPECT_EQ(api().create_collider(dead, &info, &collider), XR_ERROR_HANDLE_INVALID);
    auto drive = xr<XrHandDriveInfoPHYSHAND>(XR_TYPE_HAND_DRIVE_INFO_PHYSHAND);
    EXPECT_EQ(api().set_drive(dead, &drive), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(xrDestroySession(dead), XR_ERROR_HANDLE_INVALID);

    // A new session of the same instance starts from scratch.
    start_session();
    const XrHandTrackerEXT again = hand_tracker(XR_HAND_RIGHT_EXT);
    ASSERT_EQ(locate(again, stage_, frame(), hand), XR_SUCCESS);
    EXPECT_TRUE(hand.locations.isActive);
    EXPECT_EQ(hand.physical.isSimulated, XR_FALSE);  // no desk in this one
    EXPECT_EQ(locate_colliders({desk}, stage_, now(), located), XR_ERROR_HANDLE_INVALID);
}

// Instances come and go; each new one works exactly as the first (the same results, bit
// for bit), whether the previous one was shut down in order or destroyed with everything
// still alive.
TEST_F(Lifecycle, InstanceCanBeDestroyedAndCreatedAgain) {
    use_scene(both_hands_pressing());
    std::vector<std::vector<HandSample>> runs;
    for (int run = 0; run < 3; ++run) {
        SCOPED_TRACE("instance " + std::to_string(run));
        ASSERT_EQ(create_instance(), XR_SUCCESS);
        start_session();
        frame();
        create_desk();
        const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
        std::vector<HandSample> samples;
        for (int f = 0; f < kPressFrames; ++f) samples.push_back(sample(right, frame()));
        HandJoints hand;
        ASSERT_EQ(locate(right, stage_, now(), hand), XR_SUCCESS);
        EXPECT_EQ(hand.physical.isSimulated, XR_TRUE);
        EXPECT_TRUE(hand.any_contact());
        runs.push_back(std::move(samples));
        if (run == 1) {
            destroy_instance();  // session, tracker and desk still alive
        } else {
            end_session();
            destroy_instance();
        }
    }
    for (std::size_t run = 1; run < runs.size(); ++run) {
        for (int f = 0; f < kPressFrames; ++f) {
            EXPECT_TRUE(same_bits(runs[run][f], runs[0][f])) << "run " << run << " frame " << f;
        }
    }
}

// The frame loop runs on the main thread, which also reads the desk back each frame, while
// one thread locates the left hand and another the right, at the same time, every frame.
// Nothing fails, and the hands are exactly those of the same app run on one thread.
TEST_F(Lifecycle, TwoThreadsLocateTheLeftAndRightHandsAtOnce) {
    use_scene(both_hands_pressing());
    constexpr int kFrames = 240;

    // One thread first.
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    frame();
    create_desk();
    std::array<XrHandTrackerEXT, 2> trackers = {hand_tracker(XR_HAND_LEFT_EXT),
                                                hand_tracker(XR_HAND_RIGHT_EXT)};
    std::array<std::vector<HandSample>, 2> expected;
    for (int f = 0; f < kFrames; ++f) {
        const XrTime time = frame();
        for (int side = 0; side < 2; ++side) {
            expected[side].push_back(sample(trackers[side], time, Chain::Physical));
        }
    }
    end_session();
    destroy_instance();

    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    frame();
    const auto desk = create_desk();
    trackers = {hand_tracker(XR_HAND_LEFT_EXT), hand_tracker(XR_HAND_RIGHT_EXT)};
    const auto locate_fn = function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT");
    XrTime shared_time = 0;
    std::barrier sync(3);
    struct Outcome {
        std::vector<HandSample> samples;
        std::vector<XrResult> failures;
        int contact_frames = 0;
    };
    std::array<Outcome, 2> outcomes;
    const auto worker = [&](int side) {
        Outcome& out = outcomes[side];
        HandJoints hand;
        for (int f = 0; f < kFrames; ++f) {
            sync.arrive_and_wait();  // a frame's time is out
            auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
            info.baseSpace = stage_;
            info.time = shared_time;
            hand.locations.next = &hand.velocities;
            hand.locations.jointCount = kJointCount;
            hand.locations.jointLocations = hand.joints.data();
            hand.velocities.next = &hand.physical;
            hand.velocities.jointCount = kJointCount;
            hand.velocities.jointVelocities = hand.joint_velocities.data();
            hand.physical.jointCount = kJointCount;
            hand.physical.ghostPoses = hand.ghost.data();
            hand.physical.inContact = hand.in_contact.data();
            hand.physical.springForce = hand.spring_force.data();
            const XrResult result = locate_fn(trackers[side], &info, &hand.locations);
            if (XR_FAILED(result)) out.failures.push_back(result);
            HandSample s;
            s.is_active = hand.locations.isActive;
            s.joints = hand.joints;
            s.velocities = hand.joint_velocities;
            out.samples.push_back(s);
            out.contact_frames += hand.any_contact() ? 1 : 0;
            sync.arrive_and_wait();  // done with this frame
        }
    };
    std::thread left_thread(worker, 0);
    std::thread right_thread(worker, 1);
    XrPhysicalColliderFlagsPHYSHAND desk_flags = 0;
    for (int f = 0; f < kFrames; ++f) {
        shared_time = frame();
        sync.arrive_and_wait();
        desk_flags |= locate_collider(desk, shared_time).flags;
        sync.arrive_and_wait();
    }
    left_thread.join();
    right_thread.join();

    for (int side = 0; side < 2; ++side) {
        SCOPED_TRACE(side == 0 ? "left" : "right");
        EXPECT_TRUE(outcomes[side].failures.empty());
        ASSERT_EQ(outcomes[side].samples.size(), static_cast<std::size_t>(kFrames));
        EXPECT_GT(outcomes[side].contact_frames, kFrames / 4);
        for (int f = 0; f < kFrames; ++f) {
            EXPECT_TRUE(same_bits(outcomes[side].samples[f], expected[side][f])) << "frame " << f;
        }
    }
    EXPECT_TRUE(desk_flags & XR_PHYSICAL_COLLIDER_TOUCHED_BY_LEFT_BIT_PHYSHAND);
    EXPECT_TRUE(desk_flags & XR_PHYSICAL_COLLIDER_TOUCHED_BY_RIGHT_BIT_PHYSHAND);
}

// The right hand presses the desk again and again: down in 1 s, held 1.5 s, up in 0.5 s
// (20 cm above the desk: out of the layer's reach) and 0.5 s up, every kCycle seconds.
// Drives change while it is up.
constexpr double kCycle = 3.5;
nlohmann::json repeatedly_pressing_hand(int cycles) {
    std::vector<WristKey> keys;
    for (int c = 0; c < cycles; ++c) {
        const double t0 = kCycle * c;
        keys.push_back({t0, {0.1, 0.95, -0.3}});
        keys.push_back({t0 + 1.0, {0.1, 0.716, -0.3}});
        keys.push_back({t0 + 2.5, {0.1, 0.716, -0.3}});
        keys.push_back({t0 + 3.0, {0.1, 0.95, -0.3}});
    }
    return keyframed_hand(keys, 0.0);
}

// The default drive limits each body's force (20 N); the paper's drive is an unlimited
// spring (1000 N/m unless the app says otherwise): pressing 3 cm into the desk shows which
// one is on.
TEST_F(Lifecycle, HandDriveSwitchesToPaperAndBack) {
    ASSERT_NO_FATAL_FAILURE(
        start_with_desk(scene_with_hands({{"right", repeatedly_pressing_hand(4)}})));
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    int frame_count = 0;
    // One press cycle; returns the largest spring force, the hand as at the end of the hold.
    const auto press = [&](HandJoints& held) {
        float max_force = 0.0f;
        const int start = frame_count;
        for (; frame_count < start + static_cast<int>(kCycle * 90); ++frame_count) {
            EXPECT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
            for (std::uint32_t j = 0; j < kJointCount; ++j) {
                EXPECT_TRUE(is_finite(hand.joints[j].pose));
                EXPECT_TRUE(std::isfinite(hand.spring_force[j]));
            }
            max_force = std::max(max_force, max_spring_force(hand));
            // A second into the hold, half a second before the rise: where the frames lie on the
            // script's clock depends on how long the session took to start, and without a frame
            // loop that is the real clock's (sampled at the hold's last frame, the ghost had
            // risen 4.5 mm on a slower start).
            if (frame_count == start + 2 * 90) {
                EXPECT_EQ(locate(right, stage_, now(), held), XR_SUCCESS);
            }
        }
        EXPECT_EQ(held.physical.isSimulated, XR_TRUE);
        EXPECT_TRUE(held.any_contact());
        EXPECT_LT(held.ghost[XR_HAND_JOINT_PALM_EXT].position.y, kDeskTop - 0.01f);
        EXPECT_GE(lowest_joint_over_desk(held.joints),
                  kDeskTop + kThinnestHandBody - kMaxPenetration);
        EXPECT_EQ(hand.physical.isSimulated, XR_FALSE);  // up and away again
        return max_force;
    };
    // Held still on the desk, the paper's spring is its stiffness times the lag.
    const auto expect_spring = [](const HandJoints& held, double stiffness) {
        for (std::uint32_t j = 0; j < kJointCount; ++j) {
            const double lag = distance(held.joints[j].pose.position, held.ghost[j].position);
            EXPECT_NEAR(held.spring_force[j], stiffness * lag, 0.15 * stiffness * lag + 0.3)
                << "joint " << j;
        }
    };

    HandJoints held;
    const float default_force = press(held);
    EXPECT_GT(default_force, 1.0f);
    EXPECT_LE(default_force, 20.0f + 1e-3f);

    ASSERT_EQ(set_drive(XR_HAND_DRIVE_KIND_PAPER_PHYSHAND), XR_SUCCESS);
    EXPECT_GT(press(held), 20.0f);
    expect_spring(held, 1000.0);

    auto info = xr<XrHandDriveInfoPHYSHAND>(XR_TYPE_HAND_DRIVE_INFO_PHYSHAND);
    info.drive = XR_HAND_DRIVE_KIND_PAPER_PHYSHAND;
    info.stiffness = 500.0f;
    ASSERT_EQ(api().set_drive(session_, &info), XR_SUCCESS);
    press(held);
    expect_spring(held, 500.0);

    ASSERT_EQ(set_drive(XR_HAND_DRIVE_KIND_DEFAULT_PHYSHAND), XR_SUCCESS);
    const float back_force = press(held);
    EXPECT_GT(back_force, 1.0f);
    EXPECT_LE(back_force, 20.0f + 1e-3f);
}

// Known bug (physics/simulation.cpp, Simulation::set_drive): a drive change rebuilds the
// hands and re-seats them at the ghost with contacts off "until clear"; a ghost held inside
// the desk is never clear, so the physical hand sinks into the desk and stays there for as
// long as the user presses. Enable once the rebuilt hand is seated where the old one was.
TEST_F(Lifecycle, DriveChangeWhilePressingKeepsTheHandOnTheDesk) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    for (int f = 0; f < 150; ++f) ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
    ASSERT_TRUE(hand.any_contact());
    ASSERT_EQ(set_drive(XR_HAND_DRIVE_KIND_PAPER_PHYSHAND), XR_SUCCESS);
    for (int f = 0; f < 90; ++f) {
        ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
        EXPECT_GE(lowest_joint_over_desk(hand.joints),
                  kDeskTop + kThinnestHandBody - kMaxPenetration)
            << "frame " << f;
    }
    EXPECT_TRUE(hand.any_contact());
}

}  // namespace
}  // namespace physhand::layer_test
