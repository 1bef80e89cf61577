#include "bone_joints.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "bullet_convert.h"

namespace physhand {

namespace {

// The most sweeps over the hand's joints per substep (they stop once every joint is closed):
// kSweeps, or kSqueezedSweeps while a bone squeezes, held where it is for the first
// kHeldSweeps; after them the bones before it may not have closed every gap alone, and the
// rest close what is left as any other joint, each body by its share. lift_hold squeezed to
// curls 0.3-1.0 over 4 shifts, held and the widest joint: 8 of 32 at 10 sweeps without
// squeezing bones held, 0.69 mm; held for all of 10 sweeps, 28 but 12 mm (its joints left
// open); held for 10, then closing by shares: 11 at 30 sweeps, 15 at 50 and at 30 with 50
// while a bone squeezes, all 0.30 mm (the give). Every sample scene's joints then lie within
// their give (0.74 mm at 10 sweeps). Fingers hooked round a 2 cm bar, their ghosts pulled
// 10 cm back through it: at 10 sweeps they came through it, joints open; at 30 they come
// through it too (bones 39 mm in), joints closed, and contact points Bullet keeps from the
// bar's far side then hold the hand 6.2 cm off its ghost (docs/design.md). Robustness, jointed/1,
// 3200 plays: 3029 at 10 sweeps without held bones; with them, 3039 at 50, 3032 at 30 and 50.
constexpr int kSweeps = 30;
constexpr int kSqueezedSweeps = 50;
constexpr int kHeldSweeps = 10;
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

// Turns `pose` rigidly by `turn` about `pivot`.
void turn_about(Pose& pose, const Vec3& pivot, const Quat& turn) {
    pose.position = pivot + turn * (pose.position - pivot);
    pose.orientation = (turn * pose.orientation).normalized();
}

// Moves `pose` rigidly so that its `point` lands on `to`: turned about `pivot` toward it
// first, where there is one, then slid the rest of the way.
void move_point(Pose& pose, const std::optional<Vec3>& pivot, const Vec3& point, const Vec3& to) {
    Vec3 moved = point;
    if (pivot) {
        const Vec3 from = point - *pivot;
        const Vec3 toward = to - *pivot;
        if (from.norm() > kClosed && toward.norm() > kClosed) {
            const Quat turn = Quat::FromTwoVectors(from, toward);
            turn_about(pose, *pivot, turn);
            moved = *pivot + turn * from;
        }
    }
    pose.position += to - moved;
}

// The poses of the bodies a closing reads and moves, read from Bullet once and written back
// once: converted at every read and move, they cost jointed/1 3.5 us of press_table's 52.6 us
// step (median) and 1.6 of lift_hold's 33.5.
class BodyPoses {
  public:
    struct Entry {
        btRigidBody* body;
        Pose was;
        Pose now;
        int moves = 0;  // how often the closing has moved it
    };
    // Every body that `joints` join.
    explicit BodyPoses(const std::vector<BoneJoint>& joints) {
        entries_.reserve(joints.size() + 1);
        for (const BoneJoint& j : joints) {
            add(j.parent);
            add(j.child);
        }
    }
    // `body` must be one that the joints join.
    Entry& operator[](btRigidBody* body) {
        return *std::find_if(entries_.begin(), entries_.end(),
                             [&](const Entry& e) { return e.body == body; });
    }
    // Writes each moved pose back, its move over h added to the body's velocity unless
    // `squeezes` says the body squeezes what it holds.
    void write(double h, const std::function<bool(const btRigidBody*)>& squeezes) const;

  private:
    void add(btRigidBody* body) {
        for (const Entry& e : entries_) {
            if (e.body == body) return;
        }
        const Pose pose = from_bt(body->getWorldTransform());
        entries_.push_back({body, pose, pose});
    }

    std::vector<Entry> entries_;
};

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

void BodyPoses::write(double h, const std::function<bool(const btRigidBody*)>& squeezes) const {
    for (const Entry& e : entries_) {
        if (e.now.position == e.was.position &&
            e.now.orientation.coeffs() == e.was.orientation.coeffs())
            continue;
        const btTransform t = to_bt(e.now);
        e.body->setWorldTransform(t);
        e.body->setInterpolationWorldTransform(t);
        // A squeezing bone takes no velocity from its move: the move puts it back on its joints
        // against the contact that stopped it, and kept as velocity it drove the bone on into
        // what it held every substep, the joint pulling one way and the contact the other, until
        // the squeezed cube spun out of the grip. lift_hold squeezed to curls 0.3-1.0 over 16
        // shifts, jointed/1: 48 of 128 held, 74 without (37 and 75 at shifts 16-31); its linear
        // or its angular move alone left out, 46 and 53; any holding bone's, 59; any touching
        // one's, 40; a squeezing bone's capped at 0.02 or 0.1 m/s, 71 and 70. Robustness,
        // jointed/1, 3200 plays: 3032 -> 3055.
        if (squeezes(e.body)) continue;
        e.body->setLinearVelocity(
            e.body->getLinearVelocity() +
            to_bt(capped((e.now.position - e.was.position) / h, kMostJoiningSpeed)));
        e.body->setAngularVelocity(
            e.body->getAngularVelocity() +
            to_bt(capped(rotation_between(e.was.orientation, e.now.orientation) / h,
                         kMostJoiningSpeed / kFingerLever)));
    }
}

void close_joint_gaps(const std::vector<BoneJoint>& joints, double h,
                      const std::vector<const btRigidBody*>& squeezing) {
    const auto squeezes = [&](const btRigidBody* body) {
        return std::find(squeezing.begin(), squeezing.end(), body) != squeezing.end();
    };
    BodyPoses poses(joints);
    // Each joint's two bodies, and how often each had moved when the joint was last found
    // closed and within its range: a joint whose bodies have not moved since is not checked
    // again (jointed/1 lift_hold: 3.9 sweeps a substep, most joints long settled).
    struct Visit {
        BodyPoses::Entry* parent;
        BodyPoses::Entry* child;
        int parent_moves = -1;
        int child_moves = -1;
    };
    std::vector<Visit> visits;
    visits.reserve(joints.size());
    for (const BoneJoint& j : joints) visits.push_back({&poses[j.parent], &poses[j.child]});
    const int sweeps = squeezing.empty() ? kSweeps : kSqueezedSweeps;
    for (int sweep = 0; sweep < sweeps; ++sweep) {
        bool closed = false;
        for (std::size_t i = 0; i < joints.size(); ++i) {
            const BoneJoint& j = joints[i];
            Visit& v = visits[i];
            if (v.parent->moves == v.parent_moves && v.child->moves == v.child_moves) continue;
            Pose& parent = v.parent->now;
            Pose& child = v.child->now;
            bool moved = false;
            const Vec3 end = parent * j.end_in_parent;
            const Vec3 start = child * j.start_in_child;
            const Vec3 apart = end - start;
            const double distance = apart.norm();
            const bool child_held = sweep < kHeldSweeps && squeezes(j.child);
            const bool parent_held = sweep < kHeldSweeps && squeezes(j.parent);
            if (distance >= kGive + kClosed) {
                const double child_share =
                    child_held != parent_held
                        ? (child_held ? 0.0 : 1.0)
                        : j.child->getInvMass() / (j.child->getInvMass() + j.parent->getInvMass());
                const Vec3 gap = apart * ((distance - kGive) / distance);
                const std::optional<Vec3> parent_pivot =
                    j.parent_start ? std::optional<Vec3>(parent * *j.parent_start) : std::nullopt;
                move_point(child, child * j.far_in_child, start, start + child_share * gap);
                move_point(parent, parent_pivot, end, end - (1.0 - child_share) * gap);
                ++v.parent->moves;
                ++v.child->moves;
                moved = true;
            }
            if (j.range) {
                const Quat parent_frame = parent.orientation * j.parent_frame;
                const Quat child_frame = child.orientation * j.child_frame;
                const std::optional<Quat> allowed =
                    j.range->bring_within(parent_frame.inverse() * child_frame);
                if (allowed) {
                    const Quat turn = parent_frame * *allowed * child_frame.inverse();
                    if (child_held && !parent_held) {
                        turn_about(parent, parent * j.end_in_parent, turn.inverse());
                        ++v.parent->moves;
                    } else {
                        turn_about(child, parent * j.end_in_parent, turn);
                        ++v.child->moves;
                    }
                    moved = true;
                }
            }
            if (moved) {
                closed = true;
            } else {
                v.parent_moves = v.parent->moves;
                v.child_moves = v.child->moves;
            }
        }
        // A sweep that closed nothing leaves the next one nothing to close either: a hand
        // whose joints all lie within their give (any hand touching nothing) costs one sweep.
        if (!closed) break;
    }
    poses.write(h, squeezes);
}

}  // namespace physhand
