#include <gtest/gtest.h>

#include "simulation.h"
#include "test_scenes.h"
#include "world.h"

namespace physhand {
namespace {

using testing::static_box;

std::array<HandPose, 2> right_hand_at(const Vec3& wrist, double curl = 0.2) {
    return {HandPose{}, testing::right_hand(wrist, curl)};
}

TEST(Gating, AHandFarFromEveryColliderIsTheGhostExactly) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
    for (int f = 1; f <= 90; ++f) {
        const auto ghosts =
            right_hand_at(Vec3(0.1 * std::sin(f * 0.1), 1.2, -0.3), 0.3 + 0.2 * std::sin(f * 0.05));
        sim.step_to(f / 90.0, ghosts);
        const PhysicalHandState& h = sim.hand(HandSide::Right);
        ASSERT_TRUE(h.joints.active);
        EXPECT_FALSE(h.simulated);
        for (std::size_t j = 0; j < kJointCount; ++j) {
            EXPECT_EQ(h.joints.joints[j].position, ghosts[1].joints[j].position);
            EXPECT_EQ(h.joints.joints[j].orientation.coeffs(),
                      ghosts[1].joints[j].orientation.coeffs());
        }
    }
    EXPECT_EQ(sim.last_substeps(), 0);  // nothing in the world needed stepping
    EXPECT_FALSE(sim.hand(HandSide::Left).joints.active);
}

TEST(Gating, AHandNearAColliderIsSimulatedAndLeavesWhenFarAgain) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
    int f = 1;
    for (; f <= 30; ++f) sim.step_to(f / 90.0, right_hand_at(Vec3(0.1, 0.84, -0.3)));
    EXPECT_TRUE(sim.hand(HandSide::Right).simulated);
    EXPECT_GT(sim.last_substeps(), 0);
    for (; f <= 60; ++f) sim.step_to(f / 90.0, right_hand_at(Vec3(0.1, 1.3, -0.3)));
    EXPECT_FALSE(sim.hand(HandSide::Right).simulated);
}

TEST(Gating, SwitchedOffEveryTrackedHandIsSimulated) {
    SimulationSettings settings;
    settings.gating = false;
    Simulation sim(settings, Vec3(0, -9.81, 0));
    for (int f = 1; f <= 10; ++f) sim.step_to(f / 90.0, right_hand_at(Vec3(0.0, 1.5, 0.0)));
    EXPECT_TRUE(sim.hand(HandSide::Right).simulated);
}

TEST(Gating, AFloorPlaneOnlyCountsWhenTheHandIsNearIt) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    sim.add_collider(testing::floor_plane());
    sim.step_to(1 / 90.0, right_hand_at(Vec3(0, 1.0, 0)));
    EXPECT_FALSE(sim.hand(HandSide::Right).simulated);
    sim.step_to(2 / 90.0, right_hand_at(Vec3(0, 0.06, 0), 0.0));
    EXPECT_TRUE(sim.hand(HandSide::Right).simulated);
}

// How `thrown`, sent at `speed` from 12 cm in front of the open right hand's palm toward
// `aimed`, went: how deep the hand as shown went into it over half a second, and whether it
// came back out the way it came. The hand sleeps until then (nothing was near it).
struct ThrowAtTheOpenHand {
    double shown = 0.0;
    double penetration = 0.0;
    bool came_back = false;
};

ThrowAtTheOpenHand throw_at_the_open_hand(const DriveSettings& drive, Collider thrown, double speed,
                                          Joint aimed) {
    SimulationSettings settings;
    settings.drive = drive;
    Simulation sim(settings, Vec3::Zero());
    const auto ghosts = right_hand_at(Vec3(0, 1, 0), 0.0);
    sim.step_to(1 / 90.0, ghosts);
    EXPECT_FALSE(sim.hand(HandSide::Right).simulated);
    const HandSolids solids = sim.hand_solids(HandSide::Right);
    const HandSolid& palm = solids.parts[0];
    const Vec3 normal = palm.pose.orientation * Vec3(0, 1, 0);
    const Vec3 aim = aimed == Joint::Palm ? palm.pose.position
                                          : sim.hand(HandSide::Right).joints[aimed].position;
    thrown.pose.position = aim - normal * 0.12;
    const ColliderHandle handle = sim.add_collider(thrown);
    sim.teleport(handle, thrown.pose, normal * speed, Vec3::Zero());
    ThrowAtTheOpenHand result;
    for (int f = 2; f <= 45; ++f) {
        sim.step_to(f / 90.0, ghosts);
        result.shown = std::max(result.shown, sim.shown_depth(HandSide::Right));
        result.penetration = std::max(result.penetration, sim.last_max_penetration());
    }
    result.came_back = (sim.body_state(handle)->pose.position - aim).dot(normal) < 0.0;
    return result;
}

// A ball thrown at an open hand that sleeps: the hand must be awake and solid when the ball
// arrives, whatever the ball crosses in a frame (17 cm at 15 m/s). Before the gate looked
// ahead, the ball passed through the palm at 15 m/s and went 16 mm into it at 10 m/s (the hand
// woke inside it and let it through).
TEST(Gating, AThrownBallWakesTheHandBeforeItArrives) {
    for (const double speed : {10.0, 15.0}) {
        for (const Joint aimed : {Joint::Palm, Joint::IndexIntermediate}) {
            if (aimed == Joint::IndexIntermediate && speed > 10.0) continue;
            SCOPED_TRACE(std::to_string(speed) + " m/s at " + std::string(joint_name(aimed)));
            const ThrowAtTheOpenHand thrown = throw_at_the_open_hand(
                default_drive(), testing::dynamic_ball("ball", Vec3::Zero(), 0.015, 0.05), speed,
                aimed);
            EXPECT_TRUE(thrown.came_back);
            EXPECT_LT(thrown.shown, 0.005);
            EXPECT_LT(thrown.penetration, 0.005);
        }
    }
}

// The joined hand's closing draws the palm that a fast ball pushed back to its fingers, into
// the ball (Simulation::carry_what_the_joints_pushed): a ball or cube thrown into it went up to
// 28.9 mm in as shown before the ball was carried with it.
TEST(Gating, AnObjectThrownIntoTheJoinedHandStaysOutOfIt) {
    const std::vector<std::pair<std::string, Collider>> objects = {
        {"3 cm ball", testing::dynamic_ball("ball", Vec3::Zero(), 0.015, 0.05)},
        {"2 cm cube", testing::dynamic_box("cube", Vec3::Zero(), 0.01, 0.05)},
        {"4 cm cube", testing::dynamic_box("cube", Vec3::Zero(), 0.02, 0.05)}};
    for (const double speed : {10.0, 15.0}) {
        for (const Joint aimed : {Joint::Palm, Joint::IndexIntermediate}) {
            for (const auto& [name, object] : objects) {
                SCOPED_TRACE(name + " at " + std::to_string(speed) + " m/s at " +
                             std::string(joint_name(aimed)));
                const ThrowAtTheOpenHand thrown =
                    throw_at_the_open_hand(default_drive(), object, speed, aimed);
                EXPECT_LT(thrown.shown, 0.005);
                EXPECT_LT(thrown.penetration, 0.005);
            }
        }
    }
}

// What the gate asks the world: a collider that comes near only by moving counts only when
// asked to look ahead, and only if it moves far enough in that time.
TEST(Gating, MovingCollidersCountByHowFarTheyMove) {
    const Vec3 lo(-0.05, -0.05, -0.05), hi(0.05, 0.05, 0.05);
    World world(World::Settings{Vec3::Zero()});
    const Collider thrown = testing::dynamic_box("thrown", Vec3(0.3, 0, 0), 0.02, 0.1);
    const ColliderHandle ball = world.add_collider(thrown);
    world.teleport(ball, thrown.pose, Vec3(-20, 0, 0), Vec3::Zero());  // 22 cm a frame
    EXPECT_FALSE(world.any_collider_near(lo, hi));
    EXPECT_TRUE(world.any_collider_near(lo, hi, 1 / 90.0));
    world.teleport(ball, thrown.pose, Vec3(-2, 0, 0), Vec3::Zero());  // 2 cm a frame
    EXPECT_FALSE(world.any_collider_near(lo, hi, 1 / 90.0));

    World paddles(World::Settings{Vec3::Zero()});
    Collider paddle = testing::static_box("paddle", Vec3(0, 0.4, 0), Vec3(0.1, 0.01, 0.1));
    paddle.motion = Motion::Kinematic;
    const ColliderHandle moving = paddles.add_collider(paddle);
    EXPECT_FALSE(paddles.any_collider_near(lo, hi, 1 / 90.0));                    // standing still
    paddles.set_kinematic_target(moving, Pose{Vec3(0, 0, 0), Quat::Identity()});  // 40 cm
    EXPECT_FALSE(paddles.any_collider_near(lo, hi));
    EXPECT_TRUE(paddles.any_collider_near(lo, hi, 1 / 90.0));
}

}  // namespace
}  // namespace physhand
