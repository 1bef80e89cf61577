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

std::optional<Quat> turn_within(const JointRange& range, const Quat& turn) {
    const Quat q = turn.w() < 0.0 ? Quat(-turn.coeffs()) : turn;
    const Vec3 tip = q * Vec3(0, 0, -1);
    const double flexion = std::atan2(-tip.y(), -tip.z());
    const double abduction = std::asin(std::clamp(tip.x(), -1.0, 1.0));
    // Swing and twist: the twist about the bone's own z is q's part along z.
    const double twist = 2.0 * std::atan2(q.z(), q.w());
    const double f = std::clamp(flexion, range.least_flexion, range.most_flexion);
    const double a = std::clamp(abduction, -range.abduction, range.abduction);
    const double t = std::clamp(twist, -range.twist, range.twist);
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
            const Pose parent = from_bt(j.parent->getWorldTransform());
            const Pose child = from_bt(j.child->getWorldTransform());
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
            }
            if (!j.range) continue;
            const Quat parent_frame =
                from_bt(j.parent->getWorldTransform()).orientation * j.parent_frame;
            const Quat child_frame =
                from_bt(j.child->getWorldTransform()).orientation * j.child_frame;
            const std::optional<Quat> allowed =
                turn_within(*j.range, parent_frame.inverse() * child_frame);
            if (!allowed) continue;
            note(*j.child);
            turn_about(*j.child, from_bt(j.parent->getWorldTransform()) * j.end_in_parent,
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
