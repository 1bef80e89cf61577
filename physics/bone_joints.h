#pragma once

#include <optional>
#include <vector>

#include "pose.h"

class btRigidBody;

namespace physhand {

// Where a bone meets the body before it (the palm, or the bone before it in its finger).
struct BoneJoint {
    btRigidBody* parent = nullptr;
    btRigidBody* child = nullptr;
    Vec3 end_in_parent = Vec3::Zero();   // where the parent ends, in its frame
    Vec3 start_in_child = Vec3::Zero();  // where the child starts, in its frame
    Vec3 far_in_child = Vec3::Zero();    // the child's other end, about which it turns
    // A bone parent turns about its own start to meet its child; the palm (none) moves whole.
    std::optional<Vec3> parent_start;
};

// Puts each child's start back within 0.3 mm (the joint's give) of its parent's end, after
// a substep of length h: each of the two moves its share of the gap in inverse proportion
// to its mass (a finger caught on an edge holds the hand back as much as the hand pulls
// it), a bone by turning about its other end (the finger bends) and then sliding what
// turning cannot close. `joints` lists parents before their children; the sweep is
// repeated, since moving a parent opens its own joint again. Velocities change by the move
// over h (at most 1 m/s), as a constraint's impulse would change them: moved without, the
// bodies would keep pressing where they were pulled from.
void close_joint_gaps(const std::vector<BoneJoint>& joints, double h);

}  // namespace physhand
