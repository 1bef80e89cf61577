#pragma once

#include "scene.h"

// The paper's visual feedback: an object a hand touches turns translucent, so the user sees
// the fingers inside the grip; and, as its discussion proposes, it starts to fade as a hand
// comes within the hover distance, so contact is announced before it happens.
namespace physhand::sample {

// Alpha of a touched object.
inline constexpr float kTouchedAlpha = 0.35f;

// Distance from `point` (in the scene frame) to the surface of a collider with `shape` at
// `pose`; 0 inside. Meshes and convex hulls are measured to their bounding sphere.
double surface_distance(const Shape& shape, const Pose& pose, const Vec3& point);

// Opaque (1) beyond `hover_m`, falling linearly to kTouchedAlpha at a gap of 0 or less, and
// kTouchedAlpha while touched. `gap_m`: the nearest hand joint's distance to the surface less
// its radius (negative where it overlaps). A `hover_m` of 0 turns hovering off: only a touch
// fades an object.
float object_alpha(bool touched, double gap_m, double hover_m);

}  // namespace physhand::sample
