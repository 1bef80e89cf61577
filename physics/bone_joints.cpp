#include "bone_joints.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "bullet_convert.h"

namespace physhand {

namespace {

// Sweeps over the hand's joints per substep. Robustness, bones/1 joined with no give, 640
// plays of displacement and throw: 10 sweeps 574, 20 sweeps 545 (the throw's release aimed
// differently); every sample scene's joints then within 0.3 mm of each other after 10.
constexpr int kSweeps = 10;
// Gaps below this are not worth a move (m).
constexpr double kClosed = 1e-7;
// How far a joint gives before it is closed (m): only what lies beyond it is closed.
// Robustness, 3200 plays, against 3061 unjoined: 2967 with none, 3020 at 0.3 mm, 3016 at
// 0.5, 2971 at 0.8 (closing every 0.1 mm a noisy ghost's bones change in length, the
// joints shook the grips the throw and the stack need).
constexpr double kGive = 0.0003;

// The most speed a joint's closing gives a body: a hand rebuilt far from a ghost that
// distorted its first sample closes centimetres at once, and at the move's own speed
// (60 m/s, stress seed 802) it asked for three times the speed limit.
constexpr double kMostJoiningSpeed = 1.0;  // m/s; turning: that at a finger's length
constexpr double kFingerLever = 0.05;      // m

Vec3 capped(const Vec3& v, double most) {
    const double n = v.norm();
    return n > most ? Vec3(v * (most / n)) : v;
}

// Moves `body` rigidly so that its `point` lands on `to`: turned about `pivot` toward it
// first, where there is one, then slid the rest of the way.
void move_point(btRigidBody& body, const std::optional<Vec3>& pivot, const Vec3& point,
                const Vec3& to) {
    Pose pose = from_bt(body.getWorldTransform());
    Vec3 moved = point;
    if (pivot) {
        const Vec3 from = point - *pivot;
        const Vec3 toward = to - *pivot;
        if (from.norm() > kClosed && toward.norm() > kClosed) {
            const Quat turn = Quat::FromTwoVectors(from, toward);
            pose.position = *pivot + turn * (pose.position - *pivot);
            pose.orientation = (turn * pose.orientation).normalized();
            moved = *pivot + turn * from;
        }
    }
    pose.position += to - moved;
    body.setWorldTransform(to_bt(pose));
}

// Turns `body` rigidly by `turn` about `pivot`.
void turn_about(btRigidBody& body, const Vec3& pivot, const Quat& turn) {
    Pose pose = from_bt(body.getWorldTransform());
    pose.position = pivot + turn * (pose.position - pivot);
    pose.orientation = (turn * pose.orientation).normalized();
    body.setWorldTransform(to_bt(pose));
}

// How far past its range a joint turns before it is turned back (radians).
constexpr double kRangeGive = 1e-3;

}  // namespace

JointRange::JointRange(double least_flexion, double most_flexion, double abduction, double twist)
    : least_flexion_(least_flexion),
      most_flexion_(most_flexion),
      abduction_(abduction),
      twist_(twist),
      least_cos_(std::cos(least_flexion)),
      least_sin_(std::sin(least_flexion)),
      most_cos_(std::cos(most_flexion)),
      most_sin_(std::sin(most_flexion)),
      abduction_sin_(std::sin(abduction)),
      half_twist_tan_(std::tan(twist / 2.0)) {}

std::optional<Quat> JointRange::bring_within(const Quat& turn) const {
    const Quat q = turn.w() < 0.0 ? Quat(-turn.coeffs()) : turn;
    const Vec3 tip = q * Vec3(0, 0, -1);
    // The tip's direction in the plane it flexes in, (-z, -y), lies between the least and the
    // most flexion's; its x is the sine of its abduction; q's part along z (q.w >= 0) is its
    // twist's half-angle tangent times q.w.
    const double u = -tip.z();
    const double v = -tip.y();
    if (least_cos_ * v - least_sin_ * u >= 0.0 && u * most_sin_ - v * most_cos_ >= 0.0 &&
        std::abs(tip.x()) <= abduction_sin_ && std::abs(q.z()) <= half_twist_tan_ * q.w())
        return std::nullopt;
    const double flexion = std::atan2(v, u);
    const double abduction = std::asin(std::clamp(tip.x(), -1.0, 1.0));
    const double twist = 2.0 * std::atan2(q.z(), q.w());
    const double f = std::clamp(flexion, least_flexion_, most_flexion_);
    const double a = std::clamp(abduction, -abduction_, abduction_);
    const double t = std::clamp(twist, -twist_, twist_);
    if (std::abs(f - flexion) + std::abs(a - abduction) + std::abs(t - twist) < kRangeGive)
        return std::nullopt;
    const Vec3 allowed(std::sin(a), -std::sin(f) * std::cos(a), -std::cos(f) * std::cos(a));
    return Quat::FromTwoVectors(Vec3(0, 0, -1), allowed) *
           Quat(Eigen::AngleAxisd(t, Vec3::UnitZ()));
}

void close_joint_gaps(const std::vector<BoneJoint>& joints, double h) {
    // Each moved body, as it was before its first move.
    std::vector<std::pair<btRigidBody*, Pose>> moved;
    const auto note = [&](btRigidBody& body) {
        if (std::none_of(moved.begin(), moved.end(),
                         [&](const auto& m) { return m.first == &body; }))
            moved.emplace_back(&body, from_bt(body.getWorldTransform()));
    };
    const auto move = [&](btRigidBody& body, const std::optional<Vec3>& pivot, const Vec3& point,
                          const Vec3& to) {
        note(body);
        move_point(body, pivot, point, to);
    };
    for (int sweep = 0; sweep < kSweeps; ++sweep) {
        bool closed = false;
        for (const BoneJoint& j : joints) {
            Pose parent = from_bt(j.parent->getWorldTransform());
            Pose child = from_bt(j.child->getWorldTransform());
            const Vec3 end = parent * j.end_in_parent;
            const Vec3 start = child * j.start_in_child;
            const Vec3 apart = end - start;
            const double distance = apart.norm();
            if (distance >= kGive + kClosed) {
                const double child_share =
                    j.child->getInvMass() / (j.child->getInvMass() + j.parent->getInvMass());
                const Vec3 gap = apart * ((distance - kGive) / distance);
                move(*j.child, child * j.far_in_child, start, start + child_share * gap);
                const std::optional<Vec3> parent_pivot =
                    j.parent_start ? std::optional<Vec3>(parent * *j.parent_start) : std::nullopt;
                move(*j.parent, parent_pivot, end, end - (1.0 - child_share) * gap);
                closed = true;
                parent = from_bt(j.parent->getWorldTransform());
                child = from_bt(j.child->getWorldTransform());
            }
            if (!j.range) continue;
            const Quat parent_frame = parent.orientation * j.parent_frame;
            const Quat child_frame = child.orientation * j.child_frame;
            const std::optional<Quat> allowed =
                j.range->bring_within(parent_frame.inverse() * child_frame);
            if (!allowed) continue;
            note(*j.child);
            turn_about(*j.child, parent * j.end_in_parent,
                       parent_frame * *allowed * child_frame.inverse());
            closed = true;
        }
        // A sweep that closed nothing leaves the next one nothing to close either: a hand
        // whose joints all lie within their give (any hand touching nothing) costs one sweep.
        if (!closed) break;
    }
    for (const auto& [body, was] : moved) {
        body->setInterpolationWorldTransform(body->getWorldTransform());
        const Pose now = from_bt(body->getWorldTransform());
        body->setLinearVelocity(
            body->getLinearVelocity() +
            to_bt(capped((now.position - was.position) / h, kMostJoiningSpeed)));
        body->setAngularVelocity(
            body->getAngularVelocity() +
            to_bt(capped(rotation_between(was.orientation, now.orientation) / h,
                         kMostJoiningSpeed / kFingerLever)));
    }
}

}  // namespace physhand
