#pragma once

#include "../physics/test_scenes.h"
#include "simulation.h"

namespace physhand::testing {

inline HandPose hand_at(const Vec3& wrist, double curl) {
    HandArticulation a;
    a.curl.fill(curl);
    return pose_hand(HandSide::Right, Pose{wrist, Quat::Identity()}, a);
}

inline bool finite(const PhysicalHandState& s) {
    for (std::size_t j = 0; j < kJointCount; ++j) {
        if (!is_finite(s.joints.joints[j]) || !is_finite(s.linear_velocity[j]) ||
            !is_finite(s.angular_velocity[j]) || !std::isfinite(s.drive_force[j])) {
            return false;
        }
    }
    return true;
}

// A table with a cube the hand rests on, so every pathology happens in contact.
struct StressBench {
    Simulation sim;
    ColliderHandle cube;
    explicit StressBench(const SimulationSettings& settings) : sim(settings, Vec3(0, -9.81, 0)) {
        sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
        cube = sim.add_collider(dynamic_box("cube", Vec3(0.1, 0.78, -0.4), 0.03, 0.1));
    }
};

}  // namespace physhand::testing
