#pragma once

#include <optional>
#include <vector>

#include "pose.h"

class btRigidBody;

namespace physhand {

// How far a joint bends, in radians, between the joint frames of the two bones it joins (as
// OpenXR's: -Z along the bone toward the tip, +Y on the back of the hand). Flexion turns the
// child's -Z toward -Y, the palm (negative: hyperextension); abduction turns it toward +X or
// -X; twist turns it about its own length. Flexion spans under half a turn, abduction and
// twist under a quarter either way.
class JointRange {
  public:
    JointRange(double least_flexion, double most_flexion, double abduction, double twist);
    double least_flexion() const { return least_flexion_; }
    double most_flexion() const { return most_flexion_; }
    double abduction() const { return abduction_; }
    double twist() const { return twist_; }
    // `turn` (the child's joint frame in its parent's) brought within the range; none if it
    // lies within it already.
    std::optional<Quat> bring_within(const Quat& turn) const;

  private:
    double least_flexion_, most_flexion_, abduction_, twist_;
    // The limits as directions and ratios, which tell a turn within the range (nearly every
    // turn, every substep) without trigonometry.
    double least_cos_, least_sin_, most_cos_, most_sin_, abduction_sin_, half_twist_tan_;
};

// Where a bone meets the body before it (the palm, or the bone before it in its finger).
struct BoneJoint {
    btRigidBody* parent = nullptr;
    btRigidBody* child = nullptr;
    Vec3 end_in_parent = Vec3::Zero();   // where the parent ends, in its frame
    Vec3 start_in_child = Vec3::Zero();  // where the child starts, in its frame
    Vec3 far_in_child = Vec3::Zero();    // the child's other end, about which it turns
    // A bone parent turns about its own start to meet its child; the palm (none) moves whole.
    std::optional<Vec3> parent_start;
    // How far the child turns against its parent (none: it turns freely, as a thumb's base
    // nearly does), and the joint frames each body carries, in its own frame.
    std::optional<JointRange> range;
    Quat parent_frame = Quat::Identity();
    Quat child_frame = Quat::Identity();
};

// Puts each child's start back within 0.3 mm (the joint's give) of its parent's end, after
// a substep of length h: each of the two moves its share of the gap in inverse proportion
// to its mass (a finger caught on an edge holds the hand back as much as the hand pulls
// it), a bone by turning about its other end (the finger bends) and then sliding what
// turning cannot close. `joints` lists parents before their children; the sweep is
// repeated, since moving a parent opens its own joint again. Velocities change by the move
// over h (at most 1 m/s), as a constraint's impulse would change them: moved without, the
// bodies would keep pressing where they were pulled from. A child bent past its joint's range
// is turned back to its edge about the joint, alone: turning the parent the other way by its
// share as well, the sweeps did not settle on a finger the wall bent in the displacement scene
// (joints 2.3 mm apart; 0.76 mm alone).
// A bone in `squeezing` (one the contacts stop short of its ghost, deep in what it holds) stays
// where the contacts put it for the first sweeps: its parent takes the whole gap, and is the
// one turned when the bone lies past its range; what the bones before it cannot close then,
// the later sweeps close by every body's share. Moved by its share from the first, each
// squeezing bone passed its ghost's curl on into the held object through the bones before it,
// and a thumb that squeezed less bent aside. Nor does a squeezing bone take its move as
// velocity: that drove it on into what it held every substep.
void close_joint_gaps(const std::vector<BoneJoint>& joints, double h,
                      const std::vector<const btRigidBody*>& squeezing = {});

}  // namespace physhand
