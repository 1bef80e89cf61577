#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>

#include "collider.h"
#include "collider_shape.h"
#include "simulation.h"
#include "speed_limit.h"

class btBroadphaseInterface;
class btCollisionDispatcher;
class btCollisionObject;
class btCollisionShape;
class btDefaultCollisionConfiguration;
class btRigidBody;
class btSequentialImpulseConstraintSolver;

namespace physhand {

class HandWorld;

// Who a Bullet object is, kept in its user indices.
enum class BodyRole : int { Collider = 1, Hand = 2 };

// A collision object's role, as the world tags it (its user index).
BodyRole role_of(const btCollisionObject* o);

// Collision groups: hand parts never collide with each other (either hand).
inline constexpr int kHandGroup = 1 << 6;

// Hand contacts from this far away. Bullet scales the reach to each shape (0.2 mm for a
// finger), so a hand part that reaches a surface within the substep is found inside it next
// time; from further away the solver stops it at the surface, and one substep per frame
// presses a palm into a table 0.3 mm instead of 5 mm (measured, press_table). Only hand
// pairs: colliders keep Bullet's reach, with which a thrown cube topples a pyramid.
inline constexpr double kHandContactReach = 0.02;  // m

// The Bullet world and the proxy colliders in it. Hand bodies are owned by PhysicalHand
// and only added to / removed from this world.
class World {
  public:
    struct Settings {
        Vec3 gravity;
        bool sleeping = true;
        double max_body_speed = 20.0;
    };
    explicit World(const Settings& settings);
    ~World();

    ColliderHandle add_collider(const Collider& collider);
    bool remove_collider(ColliderHandle handle);
    bool has_collider(ColliderHandle handle) const { return colliders_.count(handle) != 0; }
    bool is_kinematic(ColliderHandle handle) const;
    bool set_kinematic_target(ColliderHandle handle, const Pose& pose);
    bool teleport(ColliderHandle handle, const Pose& pose, const Vec3& linear_velocity,
                  const Vec3& angular_velocity);
    // Moves a dynamic collider by `offset` and gives it at least `speed` along it, keeping its
    // contacts (teleport forgets them); anything else is left as it is.
    void carry(ColliderHandle handle, const Vec3& offset, double speed);
    std::optional<BodyState> body_state(ColliderHandle handle) const;
    std::size_t collider_count() const { return colliders_.size(); }
    const Vec3& gravity() const { return settings_.gravity; }
    // Every collider's pose and velocities are finite.
    bool colliders_finite() const;

    void add_hand_body(btRigidBody* body);
    void remove_hand_body(btRigidBody* body);

    // True when a step would change anything: awake dynamic bodies, moving kinematic ones
    // or hand bodies in the world.
    bool needs_step() const;
    // One fixed substep of length h; `fraction` (0..1] of the way to kinematic targets.
    // Every body's speeds are limited before it moves; returns what the limit found.
    SpeedCheck step(double h, double fraction);
    // Kinematic targets become the current poses; the next step starts from there.
    void finish_kinematic_motion();

    // How deep a shape placed at `pose` (not in the world) lies in the collider it goes
    // deepest into, m; 0 in none, each awake dynamic collider moved on `ahead_s` at its
    // velocities. By the contact algorithms (physics/pair_depth); changes nothing.
    double depth_in_colliders(btCollisionShape& shape, const Pose& pose,
                              double ahead_s = 0.0) const;

    // Any collider whose bounds meet the box [lo, hi], or would within `lookahead_s` moving
    // as it moves now (a dynamic one at its speed, a kinematic one toward its target).
    bool any_collider_near(const Vec3& lo, const Vec3& hi, double lookahead_s = 0.0) const;
    // Any collider a hand can move or be moved with (dynamic or kinematic) whose bounds meet
    // the box [lo, hi] now.
    bool any_movable_collider_near(const Vec3& lo, const Vec3& hi) const;

    struct ContactPoint {
        const btCollisionObject* hand_part;
        ColliderHandle collider;
        double distance;  // < 0: penetrating
        double impulse;
        Motion collider_motion;    // the hand can move a dynamic one only
        Vec3 point;                // on the collider's surface, world frame
        Vec3 normal;               // from the collider toward the hand part
        Vec3 impulse_on_collider;  // normal and friction, N·s
        Vec3 collider_centre;      // its centre of mass
        // How fast the pair approached along the normal at its contact points before the
        // last substep's solver, m/s (0 when separating).
        double approach_speed;
        // The collider's velocity at `point` (hand contacts; zero for collider pairs).
        Vec3 collider_velocity = Vec3::Zero();
    };
    // Whether ContactPoint::approach_speed is measured (otherwise 0).
    void set_measure_approach(bool measure);
    // How many moves a hand part is given to leave what it went into (depenetrate_hands).
    void set_hand_depenetration_moves(int moves);
    // Hand-versus-collider contact points, re-measured at the current poses.
    void for_each_hand_contact(const std::function<void(const ContactPoint&)>& visit) const;
    // Contact points between two colliders: `hand_part` null, `collider` the first, `other`
    // the second (the normal from the first toward it, the impulse the first's).
    void for_each_collider_contact(
        const std::function<void(const ContactPoint&, ColliderHandle other)>& visit) const;

    void mark_touched(ColliderHandle handle, HandSide side);
    void clear_touched();

  private:
    struct Entry;
    bool collider_near(const Vec3& lo, const Vec3& hi, double lookahead_s, bool movable_only) const;
    Entry* find(ColliderHandle handle);
    const Entry* find(ColliderHandle handle) const;

    Settings settings_;
    std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btBroadphaseInterface> broadphase_;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
    std::unique_ptr<HandWorld> world_;
    std::map<ColliderHandle, std::unique_ptr<Entry>> colliders_;  // ordered: deterministic
    ColliderHandle next_handle_ = 1;
    // The furthest any kinematic collider moves toward its target this frame, m.
    double kinematic_travel_ = 0.0;
    int hand_bodies_ = 0;
};

}  // namespace physhand
