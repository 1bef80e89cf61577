#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "collider.h"
#include "contact_events.h"
#include "drive.h"
#include "hand_skeleton.h"
#include "speed_limit.h"

namespace physhand {

struct SimulationSettings {
    DriveSettings drive = default_drive();
    double frame_rate_hz = 90.0;   // substep length is 1 / (frame_rate_hz * drive.substeps)
    double max_body_speed = 20.0;  // m/s, for hand parts and dynamic colliders alike
    bool gating = true;            // skip a hand with no collider within reach
    bool sleeping = true;          // dynamic colliders at rest stop being simulated
    double gate_reach = 0.05;      // m between hand and collider bounds that wakes a hand
    // A lost hand carries on this long before it lets go. Trackers lose a hand for a few
    // hundred milliseconds; at 0.5 s, a 500 ms loss while the hand held something dropped it:
    // of losses starting every 0.5 s through the five sample tasks, 44 of 86 succeeded at
    // 500 ms and 42 of 84 at 700 ms (83 and 80 now; 74 of 83 at 900 ms).
    double dropout_grace_s = 1.0;
    double reseat_distance = 0.15;  // m of wrist error beyond which the hand is re-seated
    double max_step_s = 0.1;        // time beyond this per call is dropped, not simulated
};

struct BodyState {
    Pose pose;
    Vec3 linear_velocity = Vec3::Zero();
    Vec3 angular_velocity = Vec3::Zero();
    std::array<bool, 2> touched_by{};  // by HandSide, during the last step
    bool asleep = false;
};

// What the physical hand is after a step, in the simulation's frame.
struct PhysicalHandState {
    HandPose joints;  // active when the hand is tracked or holding within its grace period
    std::array<Vec3, kJointCount> linear_velocity{};
    std::array<Vec3, kJointCount> angular_velocity{};
    std::array<bool, kJointCount> in_contact{};     // joint's body touched a collider
    std::array<double, kJointCount> drive_force{};  // |spring force| on the joint's body, N
    bool simulated = false;  // false: gated or untracked, joints are the ghost's exactly
    // The largest distance between the ends of two bones that meet at a joint (each bone's
    // body placing the joint), m: how far the hand has come apart.
    double max_joint_gap = 0.0;
};

// One body of the physical hand as it collides, for drawing it as it is.
struct HandSolid {
    enum class Kind { Sphere, Capsule, Box };
    Kind kind = Kind::Sphere;
    Pose pose;  // the body's centre; a capsule's axis is its local z
    // Sphere: radius in x. Capsule: radius in x, half the distance between its end centres
    // in z. Box: half extents.
    Vec3 size = Vec3::Zero();
    bool in_contact = false;  // touched a collider
};

struct HandSolids {
    std::array<HandSolid, kJointCount> parts{};  // a body per joint at most
    std::size_t count = 0;
};

// What the hands did to a collider: the impulse they gave it, and its moment about the
// collider's centre of mass, world frame.
struct HandImpulse {
    Vec3 linear = Vec3::Zero();   // N·s
    Vec3 angular = Vec3::Zero();  // N·m·s
};

// Counters of pathological input, for tests and logs.
struct GuardCounters {
    std::uint64_t rejected_samples = 0;  // NaN/Inf, zero quaternion, absurd jump
    std::uint64_t reseats = 0;
    std::uint64_t dropouts = 0;        // a tracked hand's samples stopped
    std::uint64_t reacquisitions = 0;  // a lost, simulated hand's ghost came back within grace
    std::uint64_t speed_clamps = 0;    // body-substeps the speed limit slowed down
};

class World;
class PhysicalHand;

// The Bullet world, the proxy colliders and the two physical hands. Not thread-safe:
// callers serialise access. Deterministic for the same sequence of calls.
class Simulation {
  public:
    Simulation(const SimulationSettings& settings, const Vec3& gravity);
    ~Simulation();
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;

    const SimulationSettings& settings() const { return settings_; }
    // Takes effect from the next step; changing the body model rebuilds the hands.
    void set_drive(const DriveSettings& drive);

    // Throws std::invalid_argument naming what is wrong (zero size, bad mass, ...).
    ColliderHandle add_collider(const Collider& collider);
    bool remove_collider(ColliderHandle handle);
    bool has_collider(ColliderHandle handle) const;
    // Kinematic colliders: where it should be at the end of the next physics frame.
    bool set_kinematic_target(ColliderHandle handle, const Pose& pose);
    // Where it should be at `time_s` (the clock of step_sampling): each physics frame up to
    // then moves it to its place on the straight way there from where it is now, so it moves
    // evenly whichever display rate sets its targets. A time not after the last physics frame
    // is reached at the next.
    bool set_kinematic_target(ColliderHandle handle, const Pose& pose, double time_s);
    // Any collider: placed now (at the time shown), with the given velocities (dynamic only),
    // woken up.
    bool teleport(ColliderHandle handle, const Pose& pose, const Vec3& linear_velocity,
                  const Vec3& angular_velocity);
    // As shown at the latest time stepped to, as the hands are: a dynamic body moved on from
    // the last physics frame at its velocities. Shown where that frame left it, a projectile
    // in the throw lagged the hand that held it, 14 mm into its fingers at a 72 Hz display.
    std::optional<BodyState> body_state(ColliderHandle handle) const;
    std::size_t collider_count() const;

    // Where the tracked hands were at a time, by HandSide (inactive: not tracked).
    using GhostSource = std::function<std::array<HandPose, 2>(double time_s)>;

    // Advances the physics, in frames of 1/settings().frame_rate_hz, to the last frame at or
    // before `time_s`, each frame driving the hands toward the ghosts where they were at its
    // time (`ghosts_at`; frames are timed in whole nanoseconds as physics/frame_clock.h times
    // 90 Hz displays), then shows the hands at `time_s`. A time on the frames' grid (within a
    // microsecond) shows that frame's state. Any other time (another display rate, jitter)
    // shows the last frame's state moved on as its ghost moved since (sampled at `time_s`),
    // or, for joints in contact or a noisy ghost, at the frame's own velocities. So the
    // physics steps the same frames on the same ghosts whatever the display rate, and every
    // display time gets a pose of its own. An earlier or equal time changes nothing. Over
    // settings().max_step_s since the last frame, only that much is simulated. The first call
    // starts the clock and simulates one frame, the last at or before its time.
    void step_sampling(double time_s, const GhostSource& ghosts_at);
    // The same for ghosts sampled at `time_s` alone: a frame between two calls takes them
    // where they were between the two samples.
    void step_to(double time_s, const std::array<HandPose, 2>& ghosts);
    // The last physics frame's time.
    double time() const { return time_s_; }

    // The hand as shown at the latest time stepped to.
    const PhysicalHandState& hand(HandSide side) const;
    // Its bodies as they collide, placed as hand(side) shows its joints (none when it is not
    // active). Computed on request: only a caller that draws the hand needs them. Changes no
    // physics.
    HandSolids hand_solids(HandSide side);
    // How deep the hand as shown (hand_solids) lies in the collider it goes deepest into, that
    // collider as shown too (body_state), m: what a user sees sink into things. The contact points
    // (last_max_penetration) are taken before the substep moves the bodies and keep one point of a
    // few per pair, so they can miss a part pushed deep (a squeezing thumb 20 mm into a cube while
    // they said 3 mm). Bullet's closest-point queries, on request (a scene run asks each frame);
    // changes no physics.
    double shown_depth(HandSide side);
    // Every pose, velocity and drive force of both hands and of every collider is finite
    // (the nonfinite_count of docs/metrics.md counts frames where this is false).
    bool state_is_finite() const;
    // Hand-collider contacts of the last physics frame.
    const std::vector<ContactInfo>& contacts() const { return contacts_; }
    // The impulse both hands gave a collider (normal and friction) since it was last taken,
    // and forgets it: each frame's share is taken once, whoever asks how often. Zero for one
    // they did not touch or that does not exist, and before the first call (nothing is
    // summed until someone asks). Static and kinematic colliders too: an app
    // that moves an object itself applies it in its own engine.
    HandImpulse take_hand_impulse(ColliderHandle handle);
    // Begin / persist / end of hand-collider contacts, frame by frame, once enabled.
    ContactEventLog& contact_events() { return contact_events_; }
    // Deepest hand-collider penetration at the end of any substep of the last step, m.
    double last_max_penetration() const { return last_max_penetration_; }
    const GuardCounters& guard_counters() const { return guards_; }
    int last_substeps() const { return last_substeps_; }
    // Fastest linear speed any simulated body (hand part or awake dynamic collider) moved with
    // in a substep of the last step: never over settings().max_body_speed, which Bullet's
    // step applies between its solver and its integration of positions.
    double last_max_body_speed() const { return last_speeds_.fastest; }
    // The fastest the drive and the contacts asked for, before that limit (infinity if not
    // finite): over the limit, the limit acted (speed_clamps counts it).
    double last_max_requested_speed() const { return last_speeds_.requested; }

  private:
    struct HandSlot;
    void step_substeps(int substeps);
    // The box holding `ghost` and, while it is simulated, the slot's physical hand.
    void bounds_with_hand(const HandSlot& slot, const HandPose& ghost, Vec3& lo, Vec3& hi) const;
    // Whether the simulated hand touches or nears a collider it can move (or be moved with),
    // or one lies within the box holding the hand and `ghost`.
    bool movable_in_way(const HandSlot& slot, const HandPose& ghost) const;
    // Takes the step's ghost sample (`step_dt` after the last) and decides whether the hand
    // is simulated in it.
    void update_hand_gate(HandSlot& slot, const HandPose& ghost, double step_dt);
    // Into how many pieces a substep of length h is cut so that no hand part near a collider
    // moves further in one than its contacts reach ahead.
    // `target_speed`: the fastest joint of each hand's target in this step, m/s.
    int pieces_for_fast_parts(double h, const std::array<double, 2>& target_speed) const;
    using ContactIndex = std::map<std::tuple<int, int, ColliderHandle>, std::size_t>;
    using ColliderIndex = std::map<std::pair<ColliderHandle, ColliderHandle>, std::size_t>;
    // After each world step: contact flags, penetration, touched colliders, contacts_ (and
    // collider_contacts_ when contact events want them).
    void collect_contacts(ContactIndex& contact_index, ColliderIndex& collider_index);
    void collect_collider_contacts(ColliderIndex& collider_index);
    // Tells each hand what its bodies touched (collect_contacts' touches_), and whether they
    // hold what they touch: another hand part touches it from the opposite side, or it rests
    // on them.
    void note_touches();
    // Joined bones: moves each dynamic collider that comes into a hand body faster than the
    // body's target moves that way, by over kCarriedApproachSpeed, as far as the joints'
    // closing moved that body into it.
    void carry_what_the_joints_pushed();
    void publish_hand(HandSlot& slot);
    // The last physics frame at or before `time_s`, and whether `time_s` is within a
    // microsecond of it. Physics frames fall on the display clock of physics/frame_clock.h,
    // in whole nanoseconds, so that a frame's ghosts are sampled at the very time a display
    // at that rate would ask for.
    std::int64_t frame_at_or_before(double time_s, bool& on_grid) const;
    // Moves every kinematic collider with a timed target to its place at `frame_time_s`.
    void move_kinematic_legs(double frame_time_s);
    // What is shown `ahead_s` after the last physics frame, when the runtime's sample of the
    // ghost then is `sample`.
    void show_hand(HandSlot& slot, double ahead_s, const HandPose& sample) const;

    SimulationSettings settings_;
    std::unique_ptr<World> world_;
    std::array<std::unique_ptr<HandSlot>, 2> hands_;
    std::vector<ContactInfo> contacts_;
    std::vector<ContactInfo> collider_contacts_;  // only for contact events that want them
    // A hand body touching a collider in the last substep.
    struct HandTouch {
        PhysicalHand* hand;
        int body;
        Motion motion;
        Vec3 normal;  // from the collider toward the body
        ColliderHandle collider;
        double gap;              // 0: touching; else only near (within kLonePressGive)
        double impulse;          // normal, N·s, in the last substep (0 when only near)
        Vec3 collider_velocity;  // at the contact point
    };
    std::vector<HandTouch> touches_;
    // Every hand-collider contact point of the last substep, touching or within the manifolds'
    // reach (kHandContactReach), for show_hand: a part shown between frames goes no further
    // toward a collider than its gap.
    struct HandGap {
        const PhysicalHand* hand;
        int body;
        Vec3 normal;  // from the collider toward the body
        double gap;   // m, 0 when touching
        Vec3 collider_velocity;
    };
    std::vector<HandGap> gaps_;
    ContactEventLog contact_events_;
    std::map<ColliderHandle, HandImpulse> hand_impulses_;  // not taken yet
    bool hand_impulses_wanted_ = false;
    // A kinematic collider on its way to a timed target, from where it was at from_t.
    struct KinematicLeg {
        Pose from, to;
        double from_t = 0.0, to_t = 0.0;
    };
    std::map<ColliderHandle, KinematicLeg> kinematic_legs_;
    double time_s_ = 0.0;
    std::int64_t tick_ = 0;                 // the last physics frame's end, in substeps
    double shown_time_ = 0.0;               // the latest time asked for
    double shown_ahead_s_ = 0.0;            // how far it lies past the last physics frame
    std::array<HandPose, 2> last_samples_;  // the ghosts given with it (step_to)
    bool have_samples_ = false;
    bool started_ = false;
    double last_max_penetration_ = 0.0;
    SpeedCheck last_speeds_;
    int last_substeps_ = 0;
    GuardCounters guards_;
};

}  // namespace physhand
