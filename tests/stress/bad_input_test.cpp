#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "stress_bench.h"

namespace physhand {
namespace {

using testing::dynamic_box;
using testing::static_box;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using Bench = testing::StressBench;
using testing::finite;
using testing::hand_at;

TEST(BadInput, NonFiniteAndDegenerateSamplesAreRejected) {
    Bench b{SimulationSettings{}};
    const Vec3 wrist(0.13, 0.86, -0.33);
    int f = 1;
    for (; f <= 30; ++f) b.sim.step_to(f / 90.0, {HandPose{}, hand_at(wrist, 0.3)});
    for (int kind = 0; kind < 4; ++kind, ++f) {
        HandPose bad = hand_at(wrist, 0.3);
        Pose& j = bad.joints[index_of(Joint::IndexTip)];
        if (kind == 0) j.position.x() = kNaN;
        if (kind == 1) j.position.y() = kInf;
        if (kind == 2) j.orientation.coeffs().setZero();
        if (kind == 3) bad.radii[3] = kNaN;
        b.sim.step_to(f / 90.0, {HandPose{}, bad});
        EXPECT_TRUE(finite(b.sim.hand(HandSide::Right))) << kind;
        EXPECT_TRUE(b.sim.hand(HandSide::Right).joints.active) << kind;  // held through it
    }
    EXPECT_EQ(b.sim.guard_counters().rejected_samples, 4u);
    // A non-unit quaternion is only normalised, not rejected.
    HandPose scaled = hand_at(wrist, 0.3);
    for (Pose& p : scaled.joints) p.orientation.coeffs() *= 3.0;
    b.sim.step_to(++f / 90.0, {HandPose{}, scaled});
    EXPECT_EQ(b.sim.guard_counters().rejected_samples, 4u);
    EXPECT_NEAR(b.sim.hand(HandSide::Right).joints[Joint::Wrist].orientation.norm(), 1.0, 1e-9);
}

TEST(BadInput, TeleportsReseatTheHandWithoutLaunchingAnything) {
    SimulationSettings settings;
    Bench b{settings};
    const Vec3 home(0.1, 0.80, -0.30);
    int f = 1;
    for (; f <= 30; ++f) b.sim.step_to(f / 90.0, {HandPose{}, hand_at(home, 0.5)});
    double fastest = 0.0;
    for (int jump = 0; jump < 6; ++jump) {
        const Vec3 away = home + Vec3(jump % 2 ? 10.0 : -3.0, 0, 0);
        for (int i = 0; i < 5; ++i, ++f) {
            b.sim.step_to(f / 90.0, {HandPose{}, hand_at(away, 0.5)});
            fastest = std::max(fastest, b.sim.body_state(b.cube)->linear_velocity.norm());
        }
        for (int i = 0; i < 5; ++i, ++f) {  // back, into the cube
            b.sim.step_to(f / 90.0, {HandPose{}, hand_at(home - Vec3(0, 0.03, 0), 0.5)});
            fastest = std::max(fastest, b.sim.body_state(b.cube)->linear_velocity.norm());
            ASSERT_TRUE(finite(b.sim.hand(HandSide::Right)));
        }
    }
    EXPECT_GE(b.sim.guard_counters().reseats, 6u);
    EXPECT_LT(fastest, 1.0);  // re-seated inside the cube, the hand passes out of it gently
}

TEST(BadInput, ExtremeParametersStayFiniteAndBounded) {
    for (double stiffness : {1e4, 1e6}) {
        for (const DriveSettings& base : builtin_drives()) {
            SimulationSettings settings;
            settings.drive = base;
            settings.drive.stiffness = stiffness;
            settings.drive.substeps = 1;
            Simulation sim(settings, Vec3(0, -9.81, 0));
            sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
            sim.add_collider(dynamic_box("grain", Vec3(0.1, 0.7525, -0.35), 0.0025, 0.001));
            sim.add_collider(dynamic_box("anvil", Vec3(-0.1, 0.80, -0.35), 0.05, 1000.0));
            sim.add_collider(static_box("slab", Vec3(0, -25.0, 0), Vec3(25, 25, 25)));
            for (int f = 1; f <= 120; ++f) {
                sim.step_to(f / 90.0,
                            {HandPose{}, hand_at(Vec3(0.05 * std::sin(f * 0.3), 0.78, -0.3), 0.6)});
                ASSERT_TRUE(finite(sim.hand(HandSide::Right))) << base.name << " k=" << stiffness;
                ASSERT_LE(sim.max_body_speed(), settings.max_body_speed + 1e-3);
            }
        }
    }
}

}  // namespace
}  // namespace physhand
