#pragma once

#include "../physics/test_scenes.h"
#include "simulation.h"

namespace physhand::testing {

inline constexpr double kStressCubeHalf = 0.03;

// A table with a cube the hands rest on, so every pathology happens in contact, and a floor
// (a cube knocked off the table would otherwise fall toward the speed limit).
struct StressBench {
    Simulation sim;
    ColliderHandle cube;
    explicit StressBench(const SimulationSettings& settings) : sim(settings, Vec3(0, -9.81, 0)) {
        sim.add_collider(floor_plane());
        sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
        cube = sim.add_collider(dynamic_box("cube", Vec3(0.1, 0.78, -0.4), kStressCubeHalf, 0.1));
    }
};

}  // namespace physhand::testing
