#include "simulation.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "bullet_convert.h"
#include "collider_shape.h"
#include "frame_clock.h"
#include "ghost_filter.h"
#include "noise_filter.h"
#include "physical_hand.h"
#include "skeleton_fit.h"
#include "tracking_gap.h"
#include "world.h"

namespace physhand {

namespace {

// A contact point within this distance counts as touching (surfaces meet, margins aside).
constexpr double kTouchDistance = 0.0005;
// Two hand parts grip what they both touch where their contact normals are more than 107
// degrees apart and the other pushes at least kOpposedShare as hard; an object bears on a
// part whose normal (toward the part) points within 60 degrees of straight down.
constexpr double kOpposed = -0.3;
constexpr double kBearsWeight = -0.5;
// A part whose opposite has all but let go (the fingers opening to throw) is letting go too,
// and no longer squeezes what it held (PhysicalHand's contact_aim). With the opposite counted
// however lightly it touched, the thumb squeezed on for the frame after the fingers opened
// and kicked the thrown cube sideways at 0.38 m/s (0.18 with this), past the pyramid it was
// thrown at. Robustness, bones/1 over 3200 plays: 2842 -> 2952 (throw 464 -> 523,
// displacement 475 -> 527, the mass family 116 -> 138 of 160, size 115 -> 128); shares of
// 0.35 and 0.4 gave 2960 and 2952; at 4 shifts, 0.25, 0.45 and 0.5 gave 722, 728 and 730 of
// 800 against 713; letting go without the share, 711. What it costs: in the throw 1.7 times
// as fast (4 g at the wrist) the fingers ahead of the cube fall under the share 30 ms before
// they open, and the thumb behind it, letting go, loses it early (it leaves 4-6 % faster
// than the hand).
constexpr double kOpposedShare = 1.0 / 3.0;
// An opposite part whose ghost opens away from the object (faster than kOpeningSpeed along
// its contact normal, relative to the hand) counts while it pushes at least kOpeningShare as
// hard. Under 2 mm of tracking noise the index ahead of a thrown cube let go over three frames
// instead of one, staying above kOpposedShare until the last, while the thumb behind it went on
// pushing along its slanted contact: the cube left at 0.35 m/s sideways (0.18 without noise)
// and clipped the pyramid's edge. With this, 0.26 m/s. Robustness, bones/1 over 3200 plays:
// 2952 -> 3035 (throw 523 -> 610; displacement 527 -> 523, within its spread). At 800 plays:
// shares of 0.7, 0.8 and 1.0 gave 751, 752 and 752 (1/3: 730); an opening speed of 0.02 and
// 0.1 m/s, 754 and 753. A higher share for every opposite part, opening or not, cost the
// pushes that hold a cube against one stronger finger: at 0.6, displacement 128 -> 100 of 160
// and stack 159 -> 152.
constexpr double kOpeningShare = 0.8;
constexpr double kOpeningSpeed = 0.05;  // m/s
// How fast a lost hand may have moved on while it was lost (a brisk reach): back that far
// from where it was predicted, it is eased onto its ghost like a nearer one, not re-seated
// there. A flick lost for 233 ms came back 15.1 cm on, was re-seated past the ball in its
// way and never touched it.
constexpr double kLostHandSpeed = 1.0;  // m/s
// A gated hand wakes when a collider comes within gate_reach, and sleeps again only when
// none is within this multiple of it, so it does not flicker at the boundary.
constexpr double kGateHysteresis = 1.5;
// A dynamic collider that comes into a joined hand body faster than its target moves that way
// by more than this (m/s, along the contact normal, after the substep's solve) is carried as
// far as the joints' closing then moves that body into it, and comes on no faster than the
// body gives way. The solve leaves a ball thrown into the palm moving on with the palm; the
// closing then draws the palm back to its fingers, into the ball, and only the next substeps
// push them apart: a 3 cm ball and 2 and 4 cm cubes thrown at the open jointed hand at 10 and
// 15 m/s (palm, index) went 5.4-28.9 mm into it as shown, 0.2-2.9 mm carried. A grip's slower
// contacts are left to the solver; carrying every touched collider, lift_hold squeezed to
// curls 0.3-1.0 over 4 shifts held 9 of 32 (23), above 0.1 or 0.3 m/s 12 and 21, above 1, 2
// or 3 m/s 23 (thrown: 2.9, 7.4, 7.4 mm). Measured against the collider's own speed rather than
// against the target's, a thrown projectile, which the hand swings, was carried out of the
// grip: robustness, jointed/1, 240 plays, 222 -> 214 (the throw 9 fewer); as it is, 222.
constexpr double kCarriedApproachSpeed = 1.0;
// Below this quaternion norm a joint orientation is garbage, not merely unnormalised.
constexpr double kMinQuaternionNorm = 1e-3;
// The furthest a hand part near a collider may move in one world step. Contacts are found
// kHandContactReach ahead and last from one step to the next; parts that moved up to twice
// that passed into nothing (throw: fingertips 3.7 m/s, 4.2 cm a step, 0.47 mm deep), but
// a throw 1.5 times as fast passed opening fingers 38 mm into the projectile it released
// (Bullet's sweep stops nothing a body already touches). A substep is cut into pieces that
// keep every part under this, where a fast part is near a collider (at most 8 pieces).
constexpr double kSafeTravel = 2 * kHandContactReach;
constexpr int kMaxSubstepPieces = 8;

// One contact point into the frame's record of its pair.
void add_contact_point(ContactInfo& info, const World::ContactPoint& c, bool first) {
    if (first || -c.distance > info.penetration) {
        info.point = c.point;
        info.normal = c.normal;
    }
    info.impulse += c.impulse;
    info.impulse_on_collider += c.impulse_on_collider;
    info.penetration = std::max(info.penetration, -c.distance);
    info.approach_speed = std::max(info.approach_speed, c.approach_speed);
}

// Checks a runtime sample and normalises quaternions that need it (a unit one is left
// bit for bit as the runtime gave it); false if unusable.
bool sanitise(HandPose& ghost) {
    for (std::size_t j = 0; j < kJointCount; ++j) {
        Pose& p = ghost.joints[j];
        const double n = p.orientation.norm();
        if (!is_finite(p) || !std::isfinite(n) || n < kMinQuaternionNorm ||
            !std::isfinite(ghost.radii[j]) || ghost.radii[j] < 0.0) {
            return false;
        }
        if (std::abs(n - 1.0) > 1e-9) p.orientation.coeffs() /= n;
    }
    return true;
}

HandPose interpolate_hand(const HandPose& a, const HandPose& b, double s) {
    HandPose out = b;
    for (std::size_t j = 0; j < kJointCount; ++j)
        out.joints[j] = interpolate(a.joints[j], b.joints[j], s);
    return out;
}

void ghost_bounds(const HandPose& ghost, Vec3& lo, Vec3& hi) {
    lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const Vec3 r = Vec3::Constant(ghost.radii[j]);
        lo = lo.cwiseMin(ghost.joints[j].position - r);
        hi = hi.cwiseMax(ghost.joints[j].position + r);
    }
}

}  // namespace

struct Simulation::HandSlot {
    HandSide side;
    std::unique_ptr<PhysicalHand> body;  // built from the first valid ghost
    // For drawing a hand not simulated yet (hand_solids): the bodies it would have, kept
    // apart so that drawing never changes the physics.
    std::unique_ptr<PhysicalHand> drawn_model;
    HandPose ghost;            // latest valid ghost
    HandPose previous_ghost;   // ghost at the previous step
    HandPose target;           // what the drive follows: the ghost, smoothed
    HandPose previous_target;  // target at the previous step
    SkeletonFit skeleton;
    NoiseFilter noise;
    GhostFilter filter;
    TrackingGap gap;
    HandPose target_at_loss;  // the target when tracking was last lost, and its velocity
    Vec3 velocity_at_loss = Vec3::Zero();
    bool tracked = false;  // this step's sample was valid
    bool have_ghost = false;
    bool simulated = false;
    double last_tracked_time = -std::numeric_limits<double>::infinity();
    PhysicalHandState state;  // at the last physics frame
    PhysicalHandState shown;  // at the latest time asked for
};

Simulation::Simulation(const SimulationSettings& settings, const Vec3& gravity)
    : settings_(settings),
      world_(std::make_unique<World>(
          World::Settings{gravity, settings.sleeping, settings.max_body_speed})) {
    if (settings.drive.substeps < 1 || !(settings.frame_rate_hz > 0.0)) {
        throw std::invalid_argument("simulation: substeps and frame rate must be positive");
    }
    for (HandSide side : kHandSides) {
        hands_[static_cast<int>(side)] = std::make_unique<HandSlot>();
        hands_[static_cast<int>(side)]->side = side;
    }
    world_->set_hand_depenetration_moves(settings.drive.depenetration_moves);
}

Simulation::~Simulation() {
    for (auto& slot : hands_) {
        if (slot->body) slot->body->detach(*world_);
    }
}

void Simulation::set_drive(const DriveSettings& drive) {
    if (drive.substeps < 1) throw std::invalid_argument("drive: substeps must be >= 1");
    const double old_h = 1.0 / (settings_.frame_rate_hz * settings_.drive.substeps);
    settings_.drive = drive;
    world_->set_hand_depenetration_moves(drive.depenetration_moves);
    tick_ = static_cast<std::int64_t>(std::floor(
        static_cast<double>(tick_) * old_h * settings_.frame_rate_hz * drive.substeps + 0.5));
    for (auto& slot : hands_) {
        slot->drawn_model.reset();
        if (!slot->body) continue;
        if (slot->body->drive_settings().body_model == drive.body_model) {
            slot->body->set_drive(drive);
            continue;
        }
        // A new body layout starts where the physical hand is, not at the ghost: a hand
        // pressing into a desk would otherwise be rebuilt inside it.
        const bool was_simulated = slot->simulated;
        slot->body->detach(*world_);
        slot->body = std::make_unique<PhysicalHand>(slot->side, drive, slot->ghost);
        if (!was_simulated) continue;
        const HandPose& here = slot->state.joints;
        slot->body->seat(here, here, 1.0 / settings_.frame_rate_hz);
        slot->body->attach(*world_);
    }
}

ColliderHandle Simulation::add_collider(const Collider& collider) {
    return world_->add_collider(collider);
}
bool Simulation::remove_collider(ColliderHandle handle) {
    kinematic_legs_.erase(handle);
    hand_impulses_.erase(handle);
    return world_->remove_collider(handle);
}
HandImpulse Simulation::take_hand_impulse(ColliderHandle handle) {
    hand_impulses_wanted_ = true;
    const auto it = hand_impulses_.find(handle);
    if (it == hand_impulses_.end()) return {};
    const HandImpulse given = it->second;
    hand_impulses_.erase(it);
    return given;
}

bool Simulation::has_collider(ColliderHandle handle) const {
    return world_->has_collider(handle);
}
bool Simulation::set_kinematic_target(ColliderHandle handle, const Pose& pose) {
    if (!is_finite(pose) || !world_->set_kinematic_target(handle, pose)) return false;
    kinematic_legs_.erase(handle);
    return true;
}
bool Simulation::set_kinematic_target(ColliderHandle handle, const Pose& pose, double time_s) {
    if (!is_finite(pose) || !std::isfinite(time_s) || !world_->is_kinematic(handle)) return false;
    if (!started_ || time_s <= time_s_ + kSameTimeS) return set_kinematic_target(handle, pose);
    kinematic_legs_[handle] = {world_->body_state(handle)->pose, pose, time_s_, time_s};
    return true;
}
void Simulation::move_kinematic_legs(double frame_time_s) {
    for (auto it = kinematic_legs_.begin(); it != kinematic_legs_.end();) {
        const KinematicLeg& leg = it->second;
        const bool arrives = frame_time_s >= leg.to_t - kSameTimeS;
        const double s = arrives ? 1.0 : (frame_time_s - leg.from_t) / (leg.to_t - leg.from_t);
        world_->set_kinematic_target(it->first, interpolate(leg.from, leg.to, s));
        it = arrives ? kinematic_legs_.erase(it) : std::next(it);
    }
}
bool Simulation::teleport(ColliderHandle handle, const Pose& pose, const Vec3& linear_velocity,
                          const Vec3& angular_velocity) {
    if (!is_finite(pose) || !is_finite(linear_velocity) || !is_finite(angular_velocity))
        return false;
    kinematic_legs_.erase(handle);
    if (!world_->teleport(handle, pose, linear_velocity, angular_velocity)) return false;
    // Placed at the time shown, which lies shown_ahead_s_ past the world's: a dynamic body goes
    // where its velocities (as the world limited them) bring it to `pose` by then.
    const BodyState placed = *world_->body_state(handle);
    if (shown_ahead_s_ > 0.0 && (placed.linear_velocity.squaredNorm() > 0.0 ||
                                 placed.angular_velocity.squaredNorm() > 0.0)) {
        world_->teleport(
            handle,
            moved_on(pose, placed.linear_velocity, placed.angular_velocity, -shown_ahead_s_),
            placed.linear_velocity, placed.angular_velocity);
    }
    return true;
}
std::optional<BodyState> Simulation::body_state(ColliderHandle handle) const {
    std::optional<BodyState> s = world_->body_state(handle);
    if (s && !s->asleep)
        s->pose = moved_on(s->pose, s->linear_velocity, s->angular_velocity, shown_ahead_s_);
    return s;
}
std::size_t Simulation::collider_count() const {
    return world_->collider_count();
}

const PhysicalHandState& Simulation::hand(HandSide side) const {
    return hands_[static_cast<int>(side)]->shown;
}

HandSolids Simulation::hand_solids(HandSide side) {
    HandSlot& slot = *hands_[static_cast<int>(side)];
    if (!slot.shown.joints.active) return {};
    if (slot.body) {
        slot.drawn_model.reset();
        return slot.body->solids(slot.shown.joints, slot.shown.in_contact);
    }
    // A hand never simulated yet (gated since it appeared) has no bodies: those it would get.
    if (!slot.drawn_model) {
        slot.drawn_model = std::make_unique<PhysicalHand>(side, settings_.drive, slot.ghost);
    }
    return slot.drawn_model->solids(slot.shown.joints, slot.shown.in_contact);
}

double Simulation::shown_depth(HandSide side) {
    const HandSolids solids = hand_solids(side);
    double deepest = 0.0;
    for (std::size_t i = 0; i < solids.count; ++i) {
        const HandSolid& solid = solids.parts[i];
        std::unique_ptr<btConvexInternalShape> shape;
        switch (solid.kind) {
            case HandSolid::Kind::Sphere:
                shape = std::make_unique<btSphereShape>(static_cast<btScalar>(solid.size.x()));
                break;
            case HandSolid::Kind::Capsule:
                shape =
                    std::make_unique<btCapsuleShapeZ>(static_cast<btScalar>(solid.size.x()),
                                                      static_cast<btScalar>(2 * solid.size.z()));
                break;
            case HandSolid::Kind::Box:
                shape = std::make_unique<btBoxShape>(to_bt(solid.size));
                shape->setMargin(0.001f);  // as the palm's; the half extents stay the same
                break;
        }
        deepest = std::max(deepest, world_->depth_in_colliders(*shape, solid.pose, shown_ahead_s_));
    }
    return deepest;
}

bool Simulation::state_is_finite() const {
    for (const auto& slot : hands_) {
        const PhysicalHandState& s = slot->state;
        for (std::size_t j = 0; j < kJointCount; ++j) {
            if (!is_finite(s.joints.joints[j]) || !is_finite(s.linear_velocity[j]) ||
                !is_finite(s.angular_velocity[j]) || !std::isfinite(s.drive_force[j])) {
                return false;
            }
        }
    }
    return world_->colliders_finite();
}

void Simulation::bounds_with_hand(const HandSlot& slot, const HandPose& ghost, Vec3& lo,
                                  Vec3& hi) const {
    ghost_bounds(ghost, lo, hi);
    if (!slot.simulated) return;
    Vec3 plo, phi;
    slot.body->bounds(plo, phi);
    lo = lo.cwiseMin(plo);
    hi = hi.cwiseMax(phi);
}

bool Simulation::movable_in_way(const HandSlot& slot, const HandPose& ghost) const {
    if (!slot.simulated) return false;
    const bool touching = std::any_of(touches_.begin(), touches_.end(), [&](const HandTouch& t) {
        return t.hand == slot.body.get() && t.motion != Motion::Static;
    });
    if (touching) return true;
    Vec3 lo, hi;
    bounds_with_hand(slot, ghost, lo, hi);
    return world_->any_movable_collider_near(lo, hi);
}

void Simulation::update_hand_gate(HandSlot& slot, const HandPose& input, double step_dt) {
    HandPose sample = input;
    const bool valid = sample.active && sanitise(sample);
    if (sample.active && !valid) ++guards_.rejected_samples;
    const bool touching = std::any_of(slot.state.in_contact.begin(), slot.state.in_contact.end(),
                                      [](bool c) { return c; });

    const double frame_dt = 1.0 / settings_.frame_rate_hz;
    if (valid) {
        // A hand coming back from a loss is compared with where it was predicted to be.
        const bool was_lost = slot.have_ghost && !slot.tracked && slot.simulated;
        const double since_tracked = time_s_ - slot.last_tracked_time;
        // Before anything reads the sample: the hand is built from it, the gate and the
        // jump checks compare it, and a gated hand is it.
        if (settings_.drive.smoothing.fit_skeleton) {
            const double dt = slot.have_ghost ? since_tracked : 0.0;
            sample = slot.skeleton.apply(sample, dt);
        }
        const HandPose& last = was_lost ? slot.target : slot.ghost;
        // A jump no hand can make: start over from the new place rather than fling the
        // physical hand (and whatever it holds) across the room.
        const double jump =
            slot.have_ghost ? (sample[Joint::Wrist].position - last[Joint::Wrist].position).norm()
                            : 0.0;
        const double jump_allowed =
            std::max(settings_.reseat_distance, was_lost ? kLostHandSpeed * since_tracked : 0.0);
        // Held back from where it is driven (its target: an eased return holds that short of
        // the ghost, which measured here re-seated a hand easing back 14 cm on the next frame).
        const bool lost_hand =
            slot.simulated &&
            (slot.state.joints[Joint::Wrist].position - slot.target[Joint::Wrist].position).norm() >
                settings_.reseat_distance;
        const bool reseat =
            jump > jump_allowed || lost_hand || since_tracked > settings_.dropout_grace_s;
        const bool continues = slot.have_ghost && !reseat;
        slot.previous_ghost = continues ? slot.ghost : sample;
        slot.ghost = sample;
        slot.previous_target = continues ? slot.target : sample;
        if (!continues) {
            slot.noise.reset(sample);
            slot.filter.reset(sample);
            slot.gap.reset();
            slot.target = sample;
        } else {
            // Only a simulated hand is smoothed (a gated one is the ghost itself), and not
            // while it holds or presses something: how hard it grips is how far the ghost
            // reaches into the object, which smoothing would delay.
            // Samples are one step apart, or a whole loss apart after one.
            const double sample_dt = was_lost ? since_tracked : step_dt;
            HandPose followed =
                slot.noise.apply(sample, sample_dt, settings_.drive.smoothing.noise_acceleration);
            if (slot.simulated && !touching) {
                followed = slot.filter.apply(followed, sample_dt, settings_.drive.smoothing);
            } else {
                slot.filter.follow(followed, sample_dt, settings_.drive.smoothing);
            }
            if (was_lost) ++guards_.reacquisitions;
            // A hand holding or pressing something movable is eased onto its returning ghost,
            // so what it holds comes along, and so is one with anything movable in its way
            // there, which going straight to a ghost 13 cm off at 4 m/s flung (a ball flicked
            // while the hand was lost, flying 8 m). A hand among static colliders alone goes
            // straight to it, and is re-seated there if they stop it: eased, a hand that the
            // pathological-tracking stress left under the table crept along beneath it toward
            // a ghost 0.8 m off above it, and came back after 1.08 s (jointed, seed 898).
            if (was_lost && movable_in_way(slot, followed))
                slot.gap.reacquire(slot.target, followed);
            slot.target = slot.gap.correct(followed, step_dt);
        }
        slot.have_ghost = true;
        slot.tracked = true;
        slot.last_tracked_time = time_s_;
        if (reseat && slot.simulated) {
            ++guards_.reseats;
            slot.body->seat(slot.target, slot.previous_target, frame_dt);
            slot.body->set_contact_response(false);
        }
    } else {
        if (slot.tracked) {
            ++guards_.dropouts;
            slot.target_at_loss = slot.target;
            slot.velocity_at_loss = slot.filter.hand_velocity();
        }
        slot.tracked = false;
        slot.previous_ghost = slot.ghost;
        slot.previous_target = slot.target;
        const bool in_grace = time_s_ - slot.last_tracked_time <= settings_.dropout_grace_s;
        if (!(slot.simulated && in_grace)) {
            if (slot.body) slot.body->detach(*world_);
            slot.simulated = false;
            return;
        }
        // Within the grace period the hand goes on as it was moving, grip unchanged.
        slot.target = TrackingGap::predict(slot.target_at_loss, slot.velocity_at_loss,
                                           time_s_ - slot.last_tracked_time);
    }

    Vec3 lo, hi;
    bounds_with_hand(slot, slot.ghost, lo, hi);
    const double reach = settings_.gate_reach * (slot.simulated ? kGateHysteresis : 1.0);
    // A collider that would come within reach during the frame wakes the hand now: a ball
    // thrown at 15 m/s crosses 17 cm in a frame and passed through a hand still asleep.
    const bool wanted =
        !settings_.gating || touching || !slot.tracked ||
        world_->any_collider_near(lo - Vec3::Constant(reach), hi + Vec3::Constant(reach), frame_dt);
    if (wanted && !slot.simulated) {
        if (!slot.body) {
            slot.body = std::make_unique<PhysicalHand>(slot.side, settings_.drive, slot.ghost);
        }
        slot.body->seat(slot.previous_target, slot.previous_target, frame_dt);
        slot.body->attach(*world_);
        // Woken inside something (tracking began there): pass through until clear. Woken
        // outside, meet at once what woke it: it may arrive within this frame.
        slot.body->set_contact_response(!slot.body->overlaps_colliders(*world_));
        slot.simulated = true;
    } else if (!wanted && slot.simulated) {
        slot.body->detach(*world_);
        slot.simulated = false;
    }
}

void Simulation::step_to(double time_s, const std::array<HandPose, 2>& ghosts) {
    const double before = shown_time_;
    const bool first = !have_samples_;
    step_sampling(time_s, [&](double frame_time) {
        if (first || frame_time >= time_s - kSameTimeS) return ghosts;
        std::array<HandPose, 2> between = ghosts;
        const double s = std::clamp((frame_time - before) / (time_s - before), 0.0, 1.0);
        for (std::size_t side = 0; side < 2; ++side) {
            if (ghosts[side].active && last_samples_[side].active)
                between[side] = interpolate_hand(last_samples_[side], ghosts[side], s);
        }
        return between;
    });
    if (shown_time_ == time_s) {
        last_samples_ = ghosts;
        have_samples_ = true;
    }
}

std::int64_t Simulation::frame_at_or_before(double time_s, bool& on_grid) const {
    const std::int64_t period_ns = frame_period_ns(settings_.frame_rate_hz);
    const double frames = time_s * 1e9 / static_cast<double>(period_ns);
    const auto nearest = static_cast<std::int64_t>(std::llround(frames));
    on_grid = std::abs(time_s - clock_seconds(nearest * period_ns)) < kSameTimeS;
    return on_grid ? nearest : static_cast<std::int64_t>(std::floor(frames));
}

void Simulation::step_sampling(double time_s, const GhostSource& ghosts_at) {
    if (!std::isfinite(time_s) || (started_ && time_s <= shown_time_)) return;
    const int substeps = settings_.drive.substeps;
    const double frame_rate = settings_.frame_rate_hz;
    const double rate = frame_rate * substeps;
    const std::int64_t period_ns = frame_period_ns(frame_rate);
    const auto frame_time = [&](std::int64_t frame) { return clock_seconds(frame * period_ns); };
    bool on_grid = false;
    const std::int64_t last_frame = frame_at_or_before(time_s, on_grid);
    if (!started_) {
        tick_ = (last_frame - 1) * substeps;  // the first call simulates one frame
        started_ = true;
    }
    auto frame = tick_ / substeps;
    const auto max_frames = std::max<std::int64_t>(
        1, static_cast<std::int64_t>(settings_.max_step_s * frame_rate + 1e-9));
    if (last_frame - frame > max_frames) frame = last_frame - max_frames;  // the rest is dropped
    for (++frame; frame <= last_frame; ++frame) {
        tick_ = (frame - 1) * substeps;
        time_s_ = static_cast<double>(tick_) / rate;
        move_kinematic_legs(frame_time(frame));
        const std::array<HandPose, 2> ghosts = ghosts_at(frame_time(frame));
        for (HandSide side : kHandSides) {
            update_hand_gate(*hands_[static_cast<int>(side)], ghosts[static_cast<int>(side)],
                             1.0 / frame_rate);
        }
        step_substeps(substeps);
        tick_ = frame * substeps;
        time_s_ = static_cast<double>(tick_) / rate;
        contact_events_.record(contacts_, collider_contacts_, time_s_);
        for (auto& slot : hands_) publish_hand(*slot);
    }
    shown_time_ = time_s;
    shown_ahead_s_ = on_grid ? 0.0 : time_s - frame_time(last_frame);
    if (on_grid) {
        for (auto& slot : hands_) slot->shown = slot->state;
        return;
    }
    const std::array<HandPose, 2> now = ghosts_at(time_s);
    for (auto& slot : hands_) {
        show_hand(*slot, shown_ahead_s_, now[static_cast<int>(slot->side)]);
    }
}

void Simulation::show_hand(HandSlot& slot, double ahead_s, const HandPose& sample) const {
    slot.shown = slot.state;
    if (!(ahead_s > 0.0) || !slot.state.joints.active) return;
    // Clean tracking tells how a joint moved since the frame: a free joint moves as its
    // ghost did, a gated hand is its ghost. A joint in contact or near, or a noisy ghost, carries
    // on at the frame's velocities instead, so nothing is shown pressed into what stopped it and
    // the noise the filter took out does not come back; so does every joint when the sample
    // is unusable or has jumped further than a hand moves (the next frame judges it).
    HandPose ghost_now = sample;
    const bool ghost_moves =
        ghost_now.active && sanitise(ghost_now) && slot.tracked && slot.noise.passes_clean() &&
        (ghost_now[Joint::Wrist].position - slot.ghost[Joint::Wrist].position).norm() <=
            settings_.reseat_distance;
    // A joint touching a collider or within kLonePressGive of one (touches_) carries on at the
    // frame's velocity, not as its ghost moved; and no joint goes further toward a collider than
    // the gap between them at the frame (gaps_). At a 144 Hz display, the fingers that flick the
    // sphere task's ball were shown 5.3 mm into it (now 0.02), a finger drawn up the displacement
    // task's wall 9.5 mm into that (now 5.5; 5.25 on the frames themselves, wedged in the hole's
    // edge), and the throw's fingers 16 mm into the projectile with it shown where its frame left
    // it (now 1.5).
    std::array<bool, kJointCount> touches{};
    for (const HandTouch& t : touches_) {
        if (t.hand != slot.body.get()) continue;
        for (Joint j : slot.body->carried_joints(t.body)) touches[index_of(j)] = true;
    }
    std::array<Vec3, kJointCount> start{};
    for (std::size_t j = 0; j < kJointCount; ++j) {
        Pose& joint = slot.shown.joints.joints[j];
        start[j] = joint.position;
        if (ghost_moves && !touches[j]) {
            const Pose& then = slot.ghost.joints[j];
            const Pose& now = ghost_now.joints[j];
            joint.position += now.position - then.position;
            joint.orientation =
                (now.orientation * then.orientation.conjugate() * joint.orientation).normalized();
            continue;
        }
        joint =
            moved_on(joint, slot.state.linear_velocity[j], slot.state.angular_velocity[j], ahead_s);
    }
    for (const HandGap& g : gaps_) {
        if (g.hand != slot.body.get()) continue;
        for (Joint j : slot.body->carried_joints(g.body)) {
            Vec3& position = slot.shown.joints.joints[index_of(j)].position;
            const double closing =
                (position - start[index_of(j)] - ahead_s * g.collider_velocity).dot(g.normal);
            if (closing < -g.gap) position -= (closing + g.gap) * g.normal;
        }
    }
}

void Simulation::step_substeps(int substeps) {
    last_substeps_ = 0;
    last_max_penetration_ = 0.0;
    last_speeds_ = {};
    contacts_.clear();
    collider_contacts_.clear();
    world_->clear_touched();
    for (auto& slot : hands_) slot->state.in_contact = {};
    const bool any_hand =
        std::any_of(hands_.begin(), hands_.end(), [](const auto& s) { return s->simulated; });
    if (!any_hand && !world_->needs_step()) {
        world_->finish_kinematic_motion();
        return;
    }

    world_->set_measure_approach(contact_events_.enabled());
    const double h = 1.0 / (settings_.frame_rate_hz * settings_.drive.substeps);
    const double step_dt = h * substeps;
    // How fast each hand's target moves in this step: the drive can reach it within a substep.
    std::array<double, 2> target_speed{};
    for (std::size_t side = 0; side < hands_.size(); ++side) {
        const HandSlot& slot = *hands_[side];
        if (!slot.simulated) continue;
        for (std::size_t j = 0; j < kJointCount; ++j) {
            const double moved =
                (slot.target.joints[j].position - slot.previous_target.joints[j].position).norm();
            target_speed[side] = std::max(target_speed[side], moved / step_dt);
        }
    }
    for (auto& slot : hands_) {
        if (slot->simulated) slot->body->fit_bones(slot->target);
    }
    ContactIndex contact_index;
    ColliderIndex collider_index;
    for (int i = 0; i < substeps; ++i) {
        const int pieces = pieces_for_fast_parts(h, target_speed);
        for (int p = 0; p < pieces; ++p) {
            const double fraction = (i + (p + 1.0) / pieces) / substeps;
            for (auto& slot : hands_) {
                if (!slot->simulated) continue;
                const HandPose target =
                    interpolate_hand(slot->previous_target, slot->target, fraction);
                slot->body->drive(target, slot->previous_target, slot->target, step_dt, h / pieces);
            }
            const SpeedCheck speeds = world_->step(h / pieces, fraction);
            guards_.speed_clamps += static_cast<std::uint64_t>(speeds.clamped);
            last_speeds_.add(speeds);
            ++last_substeps_;
            collect_contacts(contact_index, collider_index);
            for (auto& slot : hands_) {
                if (slot->simulated) slot->body->close_joint_gaps(h / pieces);
            }
            carry_what_the_joints_pushed();
        }
    }
    world_->finish_kinematic_motion();
}

int Simulation::pieces_for_fast_parts(double h, const std::array<double, 2>& target_speed) const {
    int pieces = 1;
    for (std::size_t side = 0; side < hands_.size(); ++side) {
        const HandSlot* slot = hands_[side].get();
        if (!slot->simulated || !slot->body->contact_response()) continue;
        const double travel = std::max(slot->body->max_point_speed(), target_speed[side]) * h;
        if (travel <= kSafeTravel) continue;
        Vec3 lo, hi;
        slot->body->bounds(lo, hi);
        const Vec3 reach = Vec3::Constant(travel);
        if (!world_->any_collider_near(lo - reach, hi + reach)) continue;
        pieces = std::max(pieces, static_cast<int>(std::ceil(travel / kSafeTravel)));
    }
    return std::min(pieces, kMaxSubstepPieces);
}

void Simulation::carry_what_the_joints_pushed() {
    // Per collider: the longest push into it, and the speed of the body that pushed.
    std::map<ColliderHandle, std::pair<Vec3, double>> pushes;
    for (const HandTouch& t : touches_) {
        if (t.motion != Motion::Dynamic || t.gap > 0.0 ||
            !t.hand->drive_settings().joined_bones() ||
            (t.collider_velocity - t.hand->target_velocity(t.body)).dot(t.normal) <
                kCarriedApproachSpeed)
            continue;
        const double into = -t.hand->closing_move(t.body).dot(t.normal);
        if (into <= 0.0) continue;
        auto& [push, speed] = pushes.try_emplace(t.collider, Vec3::Zero(), 0.0).first->second;
        if (into <= push.norm()) continue;
        push = -into * t.normal;
        speed = -t.hand->body_velocity(t.body).dot(t.normal);
    }
    for (const auto& [collider, push] : pushes) world_->carry(collider, push.first, push.second);
}

void Simulation::collect_contacts(ContactIndex& contact_index, ColliderIndex& collider_index) {
    std::array<bool, 2> penetrating{};
    for (auto& slot : hands_) {
        if (slot->body) slot->body->clear_touches();
    }
    touches_.clear();
    gaps_.clear();
    world_->for_each_hand_contact([&](const World::ContactPoint& c) {
        const int tag = c.hand_part->getUserIndex2();
        const int side = tag >> 8;
        HandSlot& slot = *hands_[static_cast<std::size_t>(side)];
        const int body = slot.body ? slot.body->body_index(c.hand_part) : -1;
        if (body < 0) return;
        if (c.distance < 0) penetrating[static_cast<std::size_t>(side)] = true;
        if (!slot.body->contact_response()) return;
        const bool near = c.distance > kTouchDistance && c.impulse <= 0.0;
        gaps_.push_back(
            {slot.body.get(), body, c.normal, near ? c.distance : 0.0, c.collider_velocity});
        if (near) {
            // Near a static collider, only a bone rests on it (PhysicalHand::note_touch); a joint
            // sphere lands on it.
            if (c.distance < kLonePressGive && (c.collider_motion != Motion::Static ||
                                                slot.body->drive_settings().joined_bones())) {
                touches_.push_back({slot.body.get(), body, c.collider_motion, c.normal, c.collider,
                                    c.distance, 0.0, c.collider_velocity});
            }
            return;
        }
        last_max_penetration_ = std::max(last_max_penetration_, -c.distance);
        touches_.push_back({slot.body.get(), body, c.collider_motion, c.normal, c.collider, 0.0,
                            c.impulse, c.collider_velocity});
        for (Joint j : slot.body->carried_joints(body)) slot.state.in_contact[index_of(j)] = true;
        world_->mark_touched(c.collider, slot.side);
        const auto key = std::make_tuple(side, body, c.collider);
        auto [it, inserted] = contact_index.try_emplace(key, contacts_.size());
        if (inserted) {
            contacts_.push_back({slot.side, slot.body->carried_joints(body).front(), c.collider});
        }
        add_contact_point(contacts_[it->second], c, inserted);
        if (hand_impulses_wanted_) {
            HandImpulse& given = hand_impulses_[c.collider];
            given.linear += c.impulse_on_collider;
            given.angular += (c.point - c.collider_centre).cross(c.impulse_on_collider);
        }
    });
    note_touches();
    if (contact_events_.between_colliders()) collect_collider_contacts(collider_index);
    // The contact points alone miss a bone deep inside a collider (a jointed hand teleported
    // into the table met it again with its palm on the top and its fingers beneath), so the
    // hand's shapes are tested too before it collides again.
    for (auto& slot : hands_) {
        if (slot->simulated && !slot->body->contact_response() &&
            !penetrating[static_cast<int>(slot->side)] &&
            !slot->body->overlaps_colliders(*world_)) {
            slot->body->set_contact_response(true);
        }
    }
}

void Simulation::note_touches() {
    const double g = world_->gravity().norm();
    const Vec3 up = g > 0.0 ? Vec3(-world_->gravity() / g) : Vec3::Zero();
    for (const HandTouch& t : touches_) {
        bool holds = false;
        if (t.motion != Motion::Static) {
            holds = t.normal.dot(up) < kBearsWeight;
            for (const HandTouch& o : touches_) {
                if (holds) break;
                if (o.collider != t.collider || o.normal.dot(t.normal) >= kOpposed) continue;
                const double share = o.hand->opening_speed(o.body, o.normal) > kOpeningSpeed
                                         ? kOpeningShare
                                         : kOpposedShare;
                holds = o.impulse >= share * t.impulse;
            }
        }
        t.hand->note_touch(t.body, t.motion, t.normal, t.gap, holds, t.collider_velocity);
    }
}

void Simulation::collect_collider_contacts(ColliderIndex& collider_index) {
    world_->for_each_collider_contact([&](const World::ContactPoint& c, ColliderHandle other) {
        if (c.distance > kTouchDistance && c.impulse <= 0.0) return;
        auto [it, inserted] =
            collider_index.try_emplace({c.collider, other}, collider_contacts_.size());
        if (inserted) {
            ContactInfo info{HandSide::Left, Joint::Palm, c.collider};
            info.other = other;
            collider_contacts_.push_back(info);
        }
        add_contact_point(collider_contacts_[it->second], c, inserted);
    });
}

void Simulation::publish_hand(HandSlot& slot) {
    PhysicalHandState& s = slot.state;
    if (!slot.have_ghost || (!slot.tracked && !slot.simulated)) {
        s.joints.active = false;
        s.simulated = false;
        s.in_contact = {};
        s.drive_force = {};
        s.max_joint_gap = 0.0;
        return;
    }
    s.simulated = slot.simulated;
    if (slot.simulated) {
        slot.body->read(slot.target, s);
        s.joints.active = true;
        return;
    }
    // Gated: the ghost itself, exactly.
    const double dt = 1.0 / settings_.frame_rate_hz;
    s.joints = slot.ghost;
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const Pose& a = slot.previous_ghost.joints[j];
        const Pose& b = slot.ghost.joints[j];
        s.linear_velocity[j] = (b.position - a.position) / dt;
        s.angular_velocity[j] = rotation_between(a.orientation, b.orientation) / dt;
    }
    s.in_contact = {};
    s.drive_force = {};
    s.max_joint_gap = 0.0;
}

}  // namespace physhand
