#pragma once

#include "hand_skeleton.h"
#include "scene.h"

namespace physhand {

// What survives a trip through OpenXR's 32-bit floats (XrPosef, XrVector3f, float sizes).
// The physics-only runner rounds its inputs this way so that it simulates bit for bit what
// the layer simulates from the same scene: contact-rich scenes are chaotic, and a 1e-7 m
// difference in a ghost pose ends up centimetres apart.
Vec3 round_to_float(const Vec3& v);
Pose round_to_float(const Pose& pose);
HandPose round_to_float(const HandPose& hand);
Collider round_to_float(const Collider& collider);

}  // namespace physhand
