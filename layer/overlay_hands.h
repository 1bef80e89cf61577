#pragma once

// The physics' hands as the overlay draws them: joints and the bodies that collide, moved
// into the space the eyes are in.

#include <array>

#include "overlay_renderer.h"
#include "pose.h"
#include "simulation.h"

namespace physhand::layer {

// `frame`: the simulation's frame in the eyes' space.
overlay::Joints to_overlay(const HandPose& hand, const Pose& frame);
std::array<overlay::Solid, overlay::kMaxSolids> to_overlay(const HandSolids& solids,
                                                           const Pose& frame);

}  // namespace physhand::layer
