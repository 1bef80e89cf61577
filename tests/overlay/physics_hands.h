#pragma once

// Realistic hands for the overlay from the physics hand model, converted the way the
// layer converts its hands: the tests' integration case and the benchmark draw these.

#include <array>

#include "hand_skeleton.h"
#include "overlay_renderer.h"

namespace physhand::overlay::testing {

Joints to_overlay(const HandPose& pose);

// The XR_EXT_hand_tracking parent table of physics/, -1 at the wrist.
std::array<int, kJointCount> skeleton_parents();

// Two half-curled hands, wrists 30 cm in front of an eye at the origin looking down -Z, palms
// down; on each, the index and middle tips touch something, so their ghosts are pressed
// 1.5 cm further down than the physical joints.
Frame demo_frame(std::span<const View> views);

}  // namespace physhand::overlay::testing
