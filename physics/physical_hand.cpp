#include "physical_hand.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "bullet_convert.h"
#include "collider_shape.h"
#include "speed_limit.h"
#include "world.h"

namespace physhand {

namespace {

// Bone masses as in Ultraleap's physical hands (0.1 kg a bone, palm three times that):
// light enough to follow, heavy enough that contacts with 0.1 kg objects stay solvable.
constexpr double kBoneMass = 0.1;
constexpr double kPalmMass = 0.3;
// Bullet's rolling resistance on the hand (a lever of 1 mm times the other's friction), as a
// finger pad's, succeeded in 2596 of 3200 robustness plays against 2537 (bones/1, 16 shifts),
// but a held cube then circled 35 um in the still grip (lift_hold's slip, 0.015 um without)
// and an app's own object, which gets only the hands' contact impulses, ended 12 mm from
// the layer's own (app_push, 10 allowed); spinning resistance let the cube slip 0.4-2.2 mm.
constexpr double kHandFriction = 1.0;
// How far a bone's ghost must reach into what it holds, past the palm's lag behind its own
// ghost, for the bone to count as squeezing it (close_joint_gaps then holds it where it is).
// lift_hold squeezed to curls 0.3-1.0 over 4 shifts: 15 of 32 held (8 before), contact points
// at most 3.3 mm deep (8.0). The palm's lag is taken off so that a hand swinging what it holds
// (a throw's wind-up), which trails its whole ghost alike, squeezes nothing: measured from the
// ghost alone, the thumb behind a thrown cube counted as squeezing for 17 substeps, and throws
// under 3 mm of noise missed (robustness, jointed/1, 3200 plays, 10 sweeps: 2999 against 3017).
constexpr double kSqueezeReach = 0.01;
constexpr double kMinRadius = 0.004;
// Every hand body turns like a 10 cm ball of its mass. A finger capsule's own inertia about
// its axis is so small that the contact solver would rather roll it than move what the
// fingers hold, and the grip is lost (measured: lift_hold drops the cube; Ultraleap sets
// bone orientation directly for the same reason). The orientation drive scales its torque
// by this inertia, so it tracks as stiffly as before.
constexpr double kRotationalInertiaRadius = 0.1;
// How fast a joined bone's joint moves along the body before it to where the ghost has it
// (m/s): a hand built from a first sample that tracking noise distorted by centimetres placed
// joints where no later ghost had them, and never came within 5 mm of its ghost again
// (stress seeds 8, 12, 20; recovered in 0.06-0.28 s at 0.1 m/s; seed 1419 of 1459 at 0.6
// alone). Robustness, 3200 plays: 3044 at 0.3, 3048 at 0.6 (noise family 599, 604). Only
// while the hand touches or nears something, where a joint that jumps moves what it holds: a
// hand touching nothing refits at once, or the jitter scene's, built from its first noisy
// sample, had a bone 3 mm from where its ghost put its joint in the third frame. Faster
// always (1.2 m/s, or at once), stress seeds 1-600 failed one run (23: a hand whose ghost had
// been teleported into the table still caught in it a second after clean tracking came back);
// as landed, none of those (4 of seeds 1-12000, against 5 at 0.6 m/s always, until a hand
// re-seated in the table collided again only once clear of it, Simulation::collect_contacts;
// none since).
constexpr double kJointRefitSpeed = 0.6;
// How far a joined bone capsule's far end may lie from where its ghost has it (in the frame
// of the bone's first joint) before the capsule is rebuilt to the ghost's bone, m. At 1 mm a
// hand under pathological tracking had its bones rebuilt nearly every frame and never came
// back within 5 mm of its ghost (stress seed 1147; 796 rebuilds).
constexpr double kBoneFitGive = 0.003;

Joint next_joint(Joint j) {
    return static_cast<Joint>(index_of(j) + 1);
}

// The bone from joint `anchor` to the next, in the anchor's frame, as `source` places them.
Vec3 bone_in_anchor(const HandPose& source, Joint anchor) {
    return source[anchor].inverse() * source[next_joint(anchor)].position;
}

// A bone capsule's frame in its anchor joint's frame (centred on the bone `local`, its axis
// along it) and its length.
struct BoneSpan {
    Pose offset;
    double length;
};
BoneSpan bone_span(const Vec3& local) {
    const double length = std::max(local.norm(), 1e-3);
    return {Pose{local / 2, Quat::FromTwoVectors(Vec3(0, 0, -1), local / length)}, length};
}

// The sphere swept along a fast hand part's path: inside the part, so that what it sweeps
// into touches the part too.
btScalar swept_sphere_radius(const btCollisionShape& shape) {
    return static_cast<btScalar>(min_half_extent(shape) * 0.8);
}

Vec3 angular_velocity_between(const Quat& from, const Quat& to, double dt) {
    return rotation_between(from, to) / dt;
}

// The contacts' common direction (the mean of their normals), or nothing where contacts on
// opposite sides (a finger wedged in a gap) give no one direction.
std::optional<Vec3> common_direction(const Vec3& normal_sum) {
    const double agreement = normal_sum.norm();
    if (agreement < 0.5) return std::nullopt;
    return Vec3(normal_sum / agreement);
}

}  // namespace

struct PhysicalHand::Body {
    Joint anchor;
    Pose offset;  // body frame in the anchor joint's frame
    // A bone body's joint with the body before it: where that body ends there, in its frame,
    // as built (joined bones: then as the ghost has it, fit_bones).
    std::optional<Vec3> end_in_parent;
    std::vector<Joint> carried;
    double mass;
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btRigidBody> rigid;
    double last_force = 0.0;
    // In the last substep: touched a static or kinematic collider, or a dynamic one; came near
    // a static one (note_touch).
    bool touching_fixed = false;
    bool touching_movable = false;
    bool near_static = false;
    // The sums of the static and of the movable colliders' contact normals (toward the body)
    // in the last substep.
    Vec3 static_normal = Vec3::Zero();
    Vec3 movable_normal = Vec3::Zero();
    // It held a movable collider it touched (note_touch's `holds`).
    bool holding = false;
    // It held what it touched before this substep, and has stayed within kLonePressGive of
    // it since: no longer holding, it is letting go.
    bool held_before = false;
    // Its target's velocity relative to the palm's target over the frame last driven, turned
    // as the palm is now (world axes).
    Vec3 velocity_in_hand = Vec3::Zero();
    // How far the nearest movable collider it touched or neared lay from it (0: touching;
    // kLonePressGive: none near).
    double movable_gap = kLonePressGive;
    // The mean velocity of the movable colliders at the points where it touched or neared them,
    // and how many points that is.
    Vec3 movable_velocity = Vec3::Zero();
    int movable_touches = 0;
    // A bone: it holds what it touches and its ghost lies over kSqueezeReach inside it,
    // beyond how far the palm trails its own.
    bool squeezing = false;
    // Joined bones: its pose before the last substep, and how fast it moved over it, the joint
    // closing's moves included: what read() reports. Its own velocity misreports a bone that
    // the closing and a contact move back and forth: fingers caught at a bar, still, reported
    // up to 2.5 m/s (the closing moved them into it every substep, adding the move as
    // velocity, and the contact pushed them back out).
    Pose substep_start;
    Vec3 moved_linear = Vec3::Zero();
    Vec3 moved_angular = Vec3::Zero();
    // How far the last joint closing moved its centre.
    Vec3 closing_move = Vec3::Zero();
    // How fast its target moves, over the frame last driven.
    Vec3 target_velocity = Vec3::Zero();
};

std::optional<JointRange> joint_range(Joint anchor) {
    const auto degrees = [](double least, double most, double abduction, double twist) {
        constexpr double kDegree = std::numbers::pi / 180.0;
        return JointRange(least * kDegree, most * kDegree, abduction * kDegree, twist * kDegree);
    };
    if (anchor == Joint::ThumbMetacarpal) return std::nullopt;
    if (anchor == Joint::ThumbProximal) return degrees(-20, 70, 20, 20);
    if (anchor == Joint::ThumbDistal) return degrees(-25, 90, 15, 15);
    switch ((index_of(anchor) - index_of(Joint::IndexProximal)) % 5) {
        case 0:
            return degrees(-30, 100, 45, 30);
        // A finger's middle joint bends back 30 degrees, as a lax one can. Held to 10, the
        // fingers pressed on in the displacement task lost it (robustness, jointed/1, 320 plays
        // of throw and displacement, only the middle joints held: 270 against 289 unheld; 282
        // at 20 degrees, 288 at 30; every joint held, 288).
        case 1:
            return degrees(-30, 120, 15, 15);
        default:
            return degrees(-25, 95, 15, 15);
    }
}

PhysicalHand::PhysicalHand(HandSide side, const DriveSettings& drive, const HandPose& source)
    : side_(side), drive_(drive) {
    auto add = [&](Joint anchor, const Pose& offset, std::vector<Joint> carried,
                   std::unique_ptr<btCollisionShape> shape, double mass) {
        auto b = std::make_unique<Body>();
        b->anchor = anchor;
        b->offset = offset;
        b->carried = std::move(carried);
        b->mass = mass;
        b->shape = std::move(shape);
        for (Joint j : b->carried) body_of_joint_[index_of(j)] = static_cast<int>(bodies_.size());
        bodies_.push_back(std::move(b));
    };

    if (drive.body_model == BodyModel::JointSpheres) {
        for (std::size_t j = 0; j < kJointCount; ++j) {
            const Joint joint = static_cast<Joint>(j);
            const bool core = joint == Joint::Palm || joint == Joint::Wrist;
            collision_radius_[j] = std::max(source.radii[j], kMinRadius);
            add(joint, Pose{}, {joint},
                std::make_unique<btSphereShape>(static_cast<btScalar>(collision_radius_[j])),
                core ? kPalmMass / 2 : kBoneMass);
        }
    } else {
        // Palm box spanning wrist to knuckles and index to little finger, in the palm frame.
        const Pose palm_inv = source[Joint::Palm].inverse();
        Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
        double knuckle_radius = 0.0;
        for (Joint j : {Joint::Wrist, Joint::IndexMetacarpal, Joint::MiddleMetacarpal,
                        Joint::RingMetacarpal, Joint::LittleMetacarpal, Joint::IndexProximal,
                        Joint::MiddleProximal, Joint::RingProximal, Joint::LittleProximal}) {
            const Vec3 p = palm_inv * source[j].position;
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
            knuckle_radius = std::max(knuckle_radius, source.radii[index_of(j)]);
        }
        const double thickness = std::max(source.radii[index_of(Joint::Palm)] * 0.6, kMinRadius);
        const Vec3 half((hi.x() - lo.x()) / 2 + knuckle_radius * 0.8, thickness,
                        std::max((hi.z() - lo.z()) / 2, kMinRadius));
        auto box = std::make_unique<btBoxShape>(to_bt(half));
        box->setMargin(0.001f);
        const std::vector<Joint> on_palm = {Joint::Palm,
                                            Joint::Wrist,
                                            Joint::IndexMetacarpal,
                                            Joint::MiddleMetacarpal,
                                            Joint::RingMetacarpal,
                                            Joint::LittleMetacarpal};
        for (Joint j : on_palm) collision_radius_[index_of(j)] = thickness;
        add(Joint::Palm,
            Pose{Vec3((lo.x() + hi.x()) / 2, 0, (lo.z() + hi.z()) / 2), Quat::Identity()}, on_palm,
            std::move(box), kPalmMass);

        // A capsule per bone, from its anchor joint to the next; the last carries the tip.
        for (Joint first : kFingerFirstBone) {
            for (int bone = 0; bone < 3; ++bone) {
                const Joint a = static_cast<Joint>(index_of(first) + bone);
                const Joint b = next_joint(a);
                const BoneSpan span = bone_span(bone_in_anchor(source, a));
                const double radius = std::max(
                    std::min(source.radii[index_of(a)], source.radii[index_of(b)]), kMinRadius);
                std::vector<Joint> carried = {a};
                if (bone == 2) carried.push_back(b);
                for (Joint j : carried) collision_radius_[index_of(j)] = radius;
                add(a, span.offset, carried,
                    std::make_unique<btCapsuleShapeZ>(static_cast<btScalar>(radius),
                                                      static_cast<btScalar>(span.length)),
                    kBoneMass);
            }
        }
    }

    const int index_base = static_cast<int>(side) << 8;
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        Body& b = *bodies_[i];
        const btVector3 inertia =
            btVector3(1, 1, 1) * static_cast<btScalar>(0.4 * b.mass * kRotationalInertiaRadius *
                                                       kRotationalInertiaRadius);
        btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(b.mass), nullptr,
                                                      b.shape.get(), inertia);
        info.m_startWorldTransform = to_bt(target_of(b, source));
        info.m_friction = static_cast<btScalar>(kHandFriction);
        b.rigid = std::make_unique<btRigidBody>(info);
        btRigidBody& r = *b.rigid;
        r.setFlags(r.getFlags() | BT_DISABLE_WORLD_GRAVITY);  // the drive holds the hand up
        r.setGravity(btVector3(0, 0, 0));
        r.setActivationState(DISABLE_DEACTIVATION);
        if (drive.body_model == BodyModel::JointSpheres) r.setAngularFactor(0.0f);
        // Contacts found kHandContactReach ahead stop a hand part that moves less than that
        // in a substep; sweeping every faster finger as well cost a fifth of a free-moving
        // hand's step at one substep (callgrind, free_motion) and found nothing more.
        r.setCcdMotionThreshold(static_cast<btScalar>(kHandContactReach));
        r.setCcdSweptSphereRadius(swept_sphere_radius(*b.shape));
        r.setUserIndex(static_cast<int>(BodyRole::Hand));
        r.setUserIndex2(index_base | static_cast<int>(i));
        const std::optional<Joint> before = joint_parent(b.anchor);
        if (drive.body_model != BodyModel::BoneCapsules || !before) continue;
        const Body& parent = *bodies_[static_cast<std::size_t>(body_of_joint_[index_of(*before)])];
        if (&parent == &b) continue;
        b.end_in_parent = joint_in(parent, b.anchor, source);
        // A capsule's centre lies halfway along its bone.
        const Vec3 start = b.offset.inverse().position;
        joints_.push_back({parent.rigid.get(), b.rigid.get(), *b.end_in_parent, start, -start,
                           parent.end_in_parent
                               ? std::optional<Vec3>(parent.offset.inverse().position)
                               : std::nullopt,
                           joint_range(b.anchor), parent.offset.orientation.inverse(),
                           b.offset.orientation.inverse()});
        joint_bodies_.emplace_back(static_cast<std::size_t>(body_of_joint_[index_of(*before)]), i);
    }
}

PhysicalHand::~PhysicalHand() {
    if (world_) detach(*world_);
}

void PhysicalHand::attach(World& world) {
    if (world_) return;
    for (auto& b : bodies_) world.add_hand_body(b->rigid.get());
    world_ = &world;
}

void PhysicalHand::detach(World& world) {
    if (!world_) return;
    for (auto& b : bodies_) world.remove_hand_body(b->rigid.get());
    world_ = nullptr;
}

Pose PhysicalHand::target_of(const Body& body, const HandPose& target) const {
    return target[body.anchor] * body.offset;
}

Vec3 PhysicalHand::joint_in(const Body& body, Joint joint, const HandPose& pose) const {
    return target_of(body, pose).inverse() * pose[joint].position;
}

void PhysicalHand::seat(const HandPose& target, const HandPose& previous_target, double frame_dt) {
    for (auto& b : bodies_) {
        const Pose now = target_of(*b, target);
        const Pose before = target_of(*b, previous_target);
        btRigidBody& r = *b->rigid;
        const btTransform t = to_bt(now);
        r.setWorldTransform(t);
        r.setInterpolationWorldTransform(t);
        r.setLinearVelocity(to_bt((now.position - before.position) / frame_dt));
        r.setAngularVelocity(
            drive_.body_model == BodyModel::JointSpheres
                ? btVector3(0, 0, 0)
                : to_bt(angular_velocity_between(before.orientation, now.orientation, frame_dt)));
        r.clearForces();
        b->substep_start = now;
        b->moved_linear = from_bt(r.getLinearVelocity());
        b->moved_angular = from_bt(r.getAngularVelocity());
        b->last_force = 0.0;
        b->touching_fixed = b->touching_movable = b->near_static = false;
    }
}

void PhysicalHand::drive(const HandPose& goal_pose, const HandPose& previous_target,
                         const HandPose& target, double frame_dt, double h) {
    if (drive_.joined_bones()) refit_joints(goal_pose, h);
    const Pose palm_before = previous_target[Joint::Palm].inverse();
    const Pose palm_now = target[Joint::Palm].inverse();
    const Quat palm_turn = target[Joint::Palm].orientation;
    const Body& palm = *bodies_[static_cast<std::size_t>(body_of_joint_[index_of(Joint::Palm)])];
    const Vec3 palm_lag =
        from_bt(palm.rigid->getCenterOfMassPosition()) - target_of(palm, goal_pose).position;
    for (auto& b : bodies_) {
        btRigidBody& r = *b->rigid;
        if (drive_.joined_bones()) b->substep_start = from_bt(r.getWorldTransform());
        const Pose goal = target_of(*b, goal_pose);
        const Pose before = target_of(*b, previous_target);
        const Pose now = target_of(*b, target);
        b->velocity_in_hand =
            palm_turn * (palm_now * now.position - palm_before * before.position) / frame_dt;
        const LinearState body{from_bt(r.getCenterOfMassPosition()),
                               from_bt(r.getLinearVelocity())};
        b->target_velocity = (now.position - before.position) / frame_dt;
        const LinearState aim = contact_aim(*b, body.position, goal, b->target_velocity);
        b->squeezing = false;
        if (drive_.joined_bones() && b->holding && b->touching_movable) {
            const std::optional<Vec3> n = common_direction(b->movable_normal);
            b->squeezing = n && (body.position - goal.position - palm_lag).dot(*n) > kSqueezeReach;
        }
        const Vec3 force = drive_force(drive_, b->mass, body, aim, h);
        r.applyCentralForce(to_bt(force));
        b->last_force = force.norm();
        if (drive_.drive_orientation) {
            const btMatrix3x3 basis = r.getWorldTransform().getBasis();
            const btVector3 inv = r.getInvInertiaDiagLocal();
            Eigen::Matrix3d rot;
            for (int i = 0; i < 3; ++i) {
                for (int k = 0; k < 3; ++k) rot(i, k) = basis[i][k];
            }
            const Vec3 diag(inv.x() > 0 ? 1.0 / inv.x() : 0.0, inv.y() > 0 ? 1.0 / inv.y() : 0.0,
                            inv.z() > 0 ? 1.0 / inv.z() : 0.0);
            const Eigen::Matrix3d inertia = rot * diag.asDiagonal() * rot.transpose();
            const Vec3 torque = drive_torque(
                drive_, b->mass, inertia, from_bt(r.getOrientation()),
                from_bt(r.getAngularVelocity()), goal.orientation,
                angular_velocity_between(before.orientation, now.orientation, frame_dt), h,
                (b->touching_fixed || b->near_static) && !b->touching_movable);
            r.applyTorque(to_bt(torque));
        }
    }
}

LinearState PhysicalHand::contact_aim(const Body& b, const Vec3& position, const Pose& goal,
                                      const Vec3& goal_velocity) const {
    const LinearState ghost{goal.position, goal_velocity};
    // Algorithm 1 follows the ghost as it is.
    if (drive_.law == DriveLaw::Explicit) return ghost;
    // A kinematic collider may be an app's own object that the hand grips (docs/extension.md's
    // coupling recipe): movable, as a dynamic one.
    if (b.movable_gap < kLonePressGive) {
        if (b.holding) return ghost;
        const std::optional<Vec3> n = common_direction(b.movable_normal);
        if (!n) return ghost;
        // How deep the goal lies in what the body touches or nears.
        const double into = (position - goal.position).dot(*n) - b.movable_gap;
        if (into <= 0.0) return ghost;
        // A part letting go gives up all its reach: the squeeze it held with, let loose once
        // nothing opposite held against it, kicked a thrown cube off its course.
        const Vec3 aim =
            goal.position + (b.held_before ? into : std::min(into, kLonePressGive)) * *n;
        // Nor does a pad (the side of a finger or the palm that faces the object) press on into
        // it faster than it moves: drawn back past the cube it had just put in its hole, a
        // fingertip beyond the cube kept driving into it at the hand's 0.3 m/s and pulled it
        // out. Robustness, bones/1, 3200 plays: 3035 -> 3059 (displacement 523 -> 540, throw
        // 610 -> 616); lift_hold squeezed to curls 0.3-1.0 over 12 shifts held 86 -> 96 of 96.
        // Every side giving that speed up: 3041 (the size family under 80 %); a pad giving up
        // all its speed into the object, not what the object moves at: 3063, but a flat hand
        // pushing an app's own cube then lagged it, which the app's engine follows 14 mm off.
        const Vec3 back = goal.orientation * b.offset.orientation.inverse() * Vec3::UnitY();
        const double closing = (goal_velocity - b.movable_velocity).dot(*n);
        if (closing < 0.0 && n->dot(back) > 0.0) return {aim, goal_velocity - closing * *n};
        return {aim, goal_velocity};
    }
    const std::optional<Vec3> n = common_direction(b.static_normal);
    if (!n) return ghost;
    const double into = (position - goal.position).dot(*n);
    return into > kRestingPressDepth
               ? LinearState{goal.position + (into - kRestingPressDepth) * *n, goal_velocity}
               : ghost;
}

double PhysicalHand::opening_speed(int body, const Vec3& normal) const {
    return bodies_[static_cast<std::size_t>(body)]->velocity_in_hand.dot(normal);
}

void PhysicalHand::clear_touches() {
    for (auto& b : bodies_) {
        b->held_before = b->holding || (b->held_before && b->movable_gap < kLonePressGive);
        b->touching_fixed = b->touching_movable = b->near_static = false;
        b->static_normal = b->movable_normal = Vec3::Zero();
        b->holding = false;
        b->movable_gap = kLonePressGive;
        b->movable_velocity = Vec3::Zero();
        b->movable_touches = 0;
    }
}

void PhysicalHand::note_touch(int body, Motion motion, const Vec3& normal, double gap, bool holds,
                              const Vec3& velocity) {
    Body& b = *bodies_[static_cast<std::size_t>(body)];
    // Near a static collider (bones only, Simulation::collect_contacts), a body rests on
    // it as one touching it does (drive aim and turning gains): held a hair above a table by
    // their joints, bones that rested only on the substeps they touched it switched between
    // pressing on and resting every substep (jointed, press_table: joints 0.15 mm RMS frame to
    // frame, pitched 0.18; 0.005 with this).
    if (gap > 0.0 && motion == Motion::Static) b.near_static = true;
    if (gap == 0.0) (motion == Motion::Dynamic ? b.touching_movable : b.touching_fixed) = true;
    (motion == Motion::Static ? b.static_normal : b.movable_normal) += normal;
    if (motion == Motion::Static) return;
    b.movable_velocity =
        (b.movable_velocity * b.movable_touches + velocity) / (b.movable_touches + 1);
    ++b.movable_touches;
    b.movable_gap = std::min(b.movable_gap, gap);
    if (holds) b.holding = true;
}

void PhysicalHand::refit_joints(const HandPose& goal, double h) {
    const bool touching = std::any_of(bodies_.begin(), bodies_.end(), [](const auto& b) {
        return b->touching_fixed || b->touching_movable || b->near_static ||
               b->movable_gap < kLonePressGive;
    });
    for (std::size_t i = 0; i < joints_.size(); ++i) {
        const Body& parent = *bodies_[joint_bodies_[i].first];
        const Body& child = *bodies_[joint_bodies_[i].second];
        const Vec3 wanted = joint_in(parent, child.anchor, goal);
        Vec3 step = wanted - joints_[i].end_in_parent;
        const double most = kJointRefitSpeed * h;
        if (touching && step.norm() > most) step *= most / step.norm();
        joints_[i].end_in_parent += step;
    }
}

void PhysicalHand::fit_bones(const HandPose& target) {
    if (!drive_.joined_bones()) return;
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        Body& b = *bodies_[i];
        if (b.shape->getShapeType() != CAPSULE_SHAPE_PROXYTYPE) continue;
        const Vec3 local = bone_in_anchor(target, b.anchor);
        // The capsule's centre lies halfway to its far end.
        if ((local - 2.0 * b.offset.position).norm() <= kBoneFitGive) continue;
        const BoneSpan span = bone_span(local);
        // The bone keeps its start where it is; its far end moves to where the ghost has it.
        btRigidBody& r = *b.rigid;
        const Pose was = from_bt(r.getWorldTransform());
        const Pose now = was * b.offset.inverse() * span.offset;
        auto shape = std::make_unique<btCapsuleShapeZ>(
            static_cast<const btCapsuleShape&>(*b.shape).getRadius(),
            static_cast<btScalar>(span.length));
        // Out of the world and back, so that no contact keeps the old shape's points.
        if (world_) world_->remove_hand_body(&r);
        r.setCollisionShape(shape.get());
        r.setWorldTransform(to_bt(now));
        r.setInterpolationWorldTransform(to_bt(now));
        r.setCcdSweptSphereRadius(swept_sphere_radius(*shape));
        if (world_) world_->add_hand_body(&r);
        b.shape = std::move(shape);
        b.offset = span.offset;
        for (std::size_t k = 0; k < joints_.size(); ++k) {
            BoneJoint& joint = joints_[k];
            if (joint_bodies_[k].second == i) {
                joint.start_in_child = span.offset.inverse().position;
                joint.far_in_child = -joint.start_in_child;
                joint.child_frame = span.offset.orientation.inverse();
            } else if (joint_bodies_[k].first == i) {
                joint.end_in_parent = now.inverse() * (was * joint.end_in_parent);
                joint.parent_start = span.offset.inverse().position;
                joint.parent_frame = span.offset.orientation.inverse();
            }
        }
    }
    for (const auto& [parent, child] : joint_bodies_) {
        Body& c = *bodies_[child];
        c.end_in_parent = joint_in(*bodies_[parent], c.anchor, target);
    }
}

Vec3 PhysicalHand::closing_move(int body) const {
    return bodies_[static_cast<std::size_t>(body)]->closing_move;
}

Vec3 PhysicalHand::target_velocity(int body) const {
    return bodies_[static_cast<std::size_t>(body)]->target_velocity;
}

Vec3 PhysicalHand::body_velocity(int body) const {
    return from_bt(bodies_[static_cast<std::size_t>(body)]->rigid->getLinearVelocity());
}

void PhysicalHand::close_joint_gaps(double h) {
    if (!drive_.joined_bones()) return;
    std::vector<const btRigidBody*> squeezing;
    std::vector<Vec3> centres;
    centres.reserve(bodies_.size());
    for (const auto& b : bodies_) {
        if (b->squeezing) squeezing.push_back(b->rigid.get());
        centres.push_back(from_bt(b->rigid->getCenterOfMassPosition()));
    }
    physhand::close_joint_gaps(joints_, h, squeezing);
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
        Body* b = bodies_[i].get();
        b->closing_move = from_bt(b->rigid->getCenterOfMassPosition()) - centres[i];
        const Pose now = from_bt(b->rigid->getWorldTransform());
        b->moved_linear = (now.position - b->substep_start.position) / h;
        b->moved_angular = rotation_between(b->substep_start.orientation, now.orientation) / h;
    }
}

void PhysicalHand::set_contact_response(bool enabled) {
    if (contact_response_ == enabled) return;
    contact_response_ = enabled;
    for (auto& b : bodies_) {
        const int flags = b->rigid->getCollisionFlags();
        b->rigid->setCollisionFlags(enabled ? flags & ~btCollisionObject::CF_NO_CONTACT_RESPONSE
                                            : flags | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    }
}

bool PhysicalHand::overlaps_colliders(const World& world) const {
    return std::any_of(bodies_.begin(), bodies_.end(), [&](const auto& b) {
        return world.depth_in_colliders(*b->shape, from_bt(b->rigid->getWorldTransform())) > 0.0;
    });
}

Pose PhysicalHand::body_pose(const Body& b, const HandPose& target) const {
    Pose pose = from_bt(b.rigid->getWorldTransform());
    // A sphere's orientation means nothing: it carries its joint turned as the target is.
    if (drive_.body_model == BodyModel::JointSpheres)
        pose.orientation = target_of(b, target).orientation;
    return pose;
}

Pose PhysicalHand::joint_on(const Body& b, Joint j, const HandPose& target) const {
    const Pose anchor_to_joint = target[b.anchor].inverse() * target[j];
    Pose joint = body_pose(b, target) * b.offset.inverse() * anchor_to_joint;
    joint.orientation.normalize();
    return joint;
}

void PhysicalHand::read(const HandPose& target, PhysicalHandState& out) const {
    out.joints.active = target.active;
    out.joints.radii = collision_radius_;
    out.max_joint_gap = 0.0;
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const Joint joint_id = static_cast<Joint>(j);
        const Body& b = *bodies_[static_cast<std::size_t>(body_of_joint_[j])];
        const btRigidBody& r = *b.rigid;
        Pose joint = joint_on(b, joint_id, target);
        if (b.shape->getShapeType() == BOX_SHAPE_PROXYTYPE) {
            const Pose body = body_pose(b, target);
            Vec3 local = body.inverse() * joint.position;
            local.y() = 0.0;
            joint.position = body * local;
        }
        out.joints.joints[j] = joint;
        const bool joined = drive_.joined_bones();
        const Vec3 w = joined ? b.moved_angular : from_bt(r.getAngularVelocity());
        out.angular_velocity[j] = w;
        out.linear_velocity[j] = (joined ? b.moved_linear : from_bt(r.getLinearVelocity())) +
                                 w.cross(joint.position - from_bt(r.getCenterOfMassPosition()));
        out.drive_force[j] = b.last_force;
        const std::optional<Joint> parent = joint_parent(joint_id);
        if (!parent) continue;
        const int parent_body = body_of_joint_[index_of(*parent)];
        if (parent_body == body_of_joint_[j]) continue;
        const Body& p = *bodies_[static_cast<std::size_t>(parent_body)];
        // A bone body's end as built, which no ghost's bone length moves, against where this
        // bone starts; a sphere: the joint as the sphere before it places it.
        const Vec3 end = b.end_in_parent
                             ? Vec3(from_bt(p.rigid->getWorldTransform()) * *b.end_in_parent)
                             : joint_on(p, joint_id, target).position;
        const Vec3 start = b.end_in_parent
                               ? Vec3(from_bt(r.getWorldTransform()) * b.offset.inverse().position)
                               : joint.position;
        out.max_joint_gap = std::max(out.max_joint_gap, (end - start).norm());
    }
}

HandSolids PhysicalHand::solids(const HandPose& hand,
                                const std::array<bool, kJointCount>& in_contact) const {
    HandSolids out;
    for (const auto& b : bodies_) {
        HandSolid& solid = out.parts[out.count++];
        solid.pose = hand[b->anchor] * b->offset;
        solid.in_contact = in_contact[index_of(b->carried.front())];
        const btCollisionShape& shape = *b->shape;
        switch (shape.getShapeType()) {
            case BOX_SHAPE_PROXYTYPE:
                solid.kind = HandSolid::Kind::Box;
                solid.size =
                    from_bt(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin());
                break;
            case CAPSULE_SHAPE_PROXYTYPE: {
                const auto& capsule = static_cast<const btCapsuleShape&>(shape);
                solid.kind = HandSolid::Kind::Capsule;
                solid.size = Vec3(capsule.getRadius(), 0.0, capsule.getHalfHeight());
                break;
            }
            default:
                solid.kind = HandSolid::Kind::Sphere;
                solid.size = Vec3(static_cast<const btSphereShape&>(shape).getRadius(), 0.0, 0.0);
        }
    }
    return out;
}

int PhysicalHand::body_index(const btCollisionObject* object) const {
    const int tag = object->getUserIndex2();
    if ((tag >> 8) != static_cast<int>(side_)) return -1;
    const int i = tag & 0xff;
    return i < static_cast<int>(bodies_.size()) &&
                   bodies_[static_cast<std::size_t>(i)]->rigid.get() == object
               ? i
               : -1;
}

const std::vector<Joint>& PhysicalHand::carried_joints(int body) const {
    return bodies_[static_cast<std::size_t>(body)]->carried;
}

double PhysicalHand::max_point_speed() const {
    double fastest = 0.0;
    for (const auto& b : bodies_) fastest = std::max(fastest, physhand::max_point_speed(*b->rigid));
    return fastest;
}

void PhysicalHand::bounds(Vec3& lo, Vec3& hi) const {
    lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (const auto& b : bodies_) {
        btVector3 a, c;
        b->rigid->getCollisionShape()->getAabb(b->rigid->getWorldTransform(), a, c);
        lo = lo.cwiseMin(from_bt(a));
        hi = hi.cwiseMax(from_bt(c));
    }
}

}  // namespace physhand
