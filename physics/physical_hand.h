#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "bone_joints.h"
#include "drive.h"
#include "hand_skeleton.h"
#include "simulation.h"

class btCollisionObject;
class btCollisionShape;
class btRigidBody;

namespace physhand {

class World;

// The range a human hand's joint bends in, between the bone anchored at `anchor` and the body
// before it (the palm for a finger's first bone), wider than a tracked hand bends it, so that
// only what the hand touches bends a bone that far: a finger's knuckle, middle and end joints
// and the thumb's knuckle and end joint. The thumb's base turns freely (none). The knuckles'
// abduction spans a spread finger's splay against the palm's frame, which is the middle
// finger's. Without ranges, the displacement task's wall folded a fingertip fully back.
std::optional<JointRange> joint_range(Joint anchor);

// The simulated hand: rigid bodies laid out by the drive's body model, each following a
// target frame derived from one ghost joint (its anchor). Joints the body carries move
// rigidly with it, keeping their current ghost offsets from the anchor.
class PhysicalHand {
  public:
    // Body sizes come from `shape_source` (the first valid ghost sample).
    PhysicalHand(HandSide side, const DriveSettings& drive, const HandPose& shape_source);
    ~PhysicalHand();
    PhysicalHand(const PhysicalHand&) = delete;
    PhysicalHand& operator=(const PhysicalHand&) = delete;

    void attach(World& world);
    void detach(World& world);
    bool attached() const { return world_ != nullptr; }

    // Places every body exactly where `target` puts it, moving as it has since
    // `previous_target`, `frame_dt` before.
    void seat(const HandPose& target, const HandPose& previous_target, double frame_dt);
    // Applies drive forces for one substep of length h toward `goal` (the target at the end of
    // the substep), `previous_target`/`target` giving the target's velocity over the frame.
    void drive(const HandPose& goal, const HandPose& previous_target, const HandPose& target,
               double frame_dt, double h);
    // What bodies touched in the last substep (`normal`: from the collider toward the body;
    // `gap`: 0, or how far a movable collider (or a static one, for bones) lay from a
    // body it did not touch, under kLonePressGive; `holds`: on a movable collider, another hand
    // part touches it from the opposite side or it rests on this body): a body that rests on
    // what it cannot move (a bone: or nears a static collider) turns more softly, one
    // that rests on static colliders alone presses no deeper than kRestingPressDepth into them,
    // and one that presses or nears movable colliders without holding them gives up
    // kLonePressGive of its reach (near as well as touching, so that it does not press in again
    // each time it comes clear).
    void clear_touches();
    // How fast `body`'s target moves along `normal` relative to the hand's palm target, m/s, in
    // the frame last driven: over 0 along a contact normal (toward the body), that part of the
    // ghost is opening away from what it touches, as fingers do letting go.
    double opening_speed(int body, const Vec3& normal) const;
    // A collider that `body` touched (gap 0) or neared in the last substep: its normal toward
    // the body, whether the body holds it (Simulation::note_touches), its velocity there.
    void note_touch(int body, Motion motion, const Vec3& normal, double gap, bool holds,
                    const Vec3& velocity);
    // With bone capsules (DriveSettings::joined_bones), puts every bone back on the body
    // before it after a substep of length h.
    void close_joint_gaps(double h);
    // How far the last close_joint_gaps moved `body`'s centre, and the body's velocity.
    Vec3 closing_move(int body) const;
    Vec3 body_velocity(int body) const;
    // How fast `body`'s target moved over the frame last driven.
    Vec3 target_velocity(int body) const;
    // With joined bones, rebuilds each bone capsule whose far end lies more than 3 mm from
    // where `target` has the next joint (seen from the bone's first joint), keeping its
    // start, and places each joint on the body before it where `target` has it: a hand built
    // from a first sample that tracking noise distorted kept capsules that no longer reached
    // the joints they were joined at (the jitter scene's, 8 mm off).
    void fit_bones(const HandPose& target);
    // While re-seating, bodies pass through colliders until they are clear of them.
    void set_contact_response(bool enabled);
    bool contact_response() const { return contact_response_; }
    // Whether any body lies inside a collider where it is now.
    bool overlaps_colliders(const World& world) const;

    // Physical joints for the current body poses, using `target` for carried offsets. Each
    // joint's radius is what its body collides with there (a finger's capsule, half the palm
    // box's thickness), not the runtime's: a joint sphere drawn as returned never reaches
    // further into what the hand rests on than the hand does. Joints the palm box carries lie
    // on its mid-plane.
    void read(const HandPose& target, PhysicalHandState& out) const;
    // Each body as it collides, placed by the joint it follows in `hand` (as read() gives
    // it, or moved on from that) and touching where the joints it carries are `in_contact`.
    HandSolids solids(const HandPose& hand, const std::array<bool, kJointCount>& in_contact) const;
    // Which body a collision object is, or -1.
    int body_index(const btCollisionObject* object) const;
    std::size_t body_count() const { return bodies_.size(); }
    // The joints a body carries (contact flags are per joint).
    const std::vector<Joint>& carried_joints(int body) const;
    // The fastest any point of a body moves (its centre's speed plus its spin times its
    // bounding radius), m/s.
    double max_point_speed() const;
    // World bounds of all bodies.
    void bounds(Vec3& lo, Vec3& hi) const;
    const DriveSettings& drive_settings() const { return drive_; }
    // Gains, limits and law may change; the body model may not (build a new hand for that).
    void set_drive(const DriveSettings& drive) { drive_ = drive; }

  private:
    struct Body;
    Pose target_of(const Body& body, const HandPose& target) const;
    // Where `pose` has `joint`, in the frame `pose` gives `body`.
    Vec3 joint_in(const Body& body, Joint joint, const HandPose& pose) const;
    // Moves each joint of joined bones toward where `goal` has it on the body before it: at
    // most kJointRefitSpeed while a body touches or nears a collider, at once otherwise.
    void refit_joints(const HandPose& goal, double h);
    // Where and how fast the drive pulls a body at `position` whose target is `goal`, moving
    // at `goal_velocity`: for a body resting on static colliders alone, no further into them
    // than kRestingPressDepth; for one pressing movable colliders without holding them,
    // kLonePressGive less far into them, no further than it is when it is letting go of what it
    // held, and, where its pad side presses them, no faster into them than they move.
    LinearState contact_aim(const Body& body, const Vec3& position, const Pose& goal,
                            const Vec3& goal_velocity) const;
    Pose body_pose(const Body& body, const HandPose& target) const;
    // Joint `j` as `body` places it, keeping its offset in `target` from the body's anchor.
    Pose joint_on(const Body& body, Joint j, const HandPose& target) const;

    HandSide side_;
    DriveSettings drive_;
    std::vector<std::unique_ptr<Body>> bodies_;
    std::vector<BoneJoint> joints_;  // bone capsules: parents before their children
    std::vector<std::pair<std::size_t, std::size_t>> joint_bodies_;  // each joint's parent, child
    std::array<int, kJointCount> body_of_joint_{};
    std::array<double, kJointCount> collision_radius_{};  // of the joint's body, at the joint
    World* world_ = nullptr;
    bool contact_response_ = true;
};

}  // namespace physhand
