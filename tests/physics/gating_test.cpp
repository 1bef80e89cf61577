#include <gtest/gtest.h>

#include "simulation.h"
#include "test_scenes.h"

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

}  // namespace
}  // namespace physhand
