#include "world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "bullet_convert.h"
#include "capsule_collision.h"
#include "face_contacts.h"
#include "hand_depenetration.h"
#include "hand_point_contacts.h"
#include "hand_reach_dispatcher.h"
#include "pair_depth.h"
#include "speed_limit.h"

namespace physhand {

namespace {

// Below these speeds for 2 s (Bullet's deactivation time) a dynamic body may sleep.
constexpr btScalar kSleepLinear = 0.05f;
constexpr btScalar kSleepAngular = 0.1f;
// Round shapes need a little rolling resistance to ever come to rest. Bullet's is a lever
// arm (m), times the friction of what the body rolls on. Rods and capsules lying on a face
// would roll away on the solver's rounding alone, so theirs is a fixed 1 mm, as is every
// round shape's resistance to spinning.
constexpr btScalar kRollingFriction = 0.001f;
// A ball's rolling resistance grows with its size, as a real one's does: its radius times
// this (on the sample tables, friction 0.6: 0.003, a hard ball on a hard table). The rods'
// 1 mm made a 5 cm ball roll as on carpet (0.024): a flicked ball slowed from 0.72 to
// 0.65 m/s crossing 35 cm of table (sphere scene) and dropped short of the basket.
constexpr double kBallRollingResistance = 0.005;

// Kinematic bodies are flagged static as well (massless to the solver).
Motion motion_of(const btCollisionObject& o) {
    if (o.isKinematicObject()) return Motion::Kinematic;
    return o.isStaticObject() ? Motion::Static : Motion::Dynamic;
}

// What the last solve gave a contact's first body: the solver pushes it along the normal
// and the two friction directions.
Vec3 impulse_on_first(const btManifoldPoint& pt) {
    return from_bt(pt.m_normalWorldOnB * pt.getAppliedImpulse() +
                   pt.m_lateralFrictionDir1 * pt.m_appliedImpulseLateral1 +
                   pt.m_lateralFrictionDir2 * pt.m_appliedImpulseLateral2);
}

}  // namespace

// Bullet's world with three additions for hands: contacts at the ends of each finger capsule
// and the corners of the palm box; the speed limit where it bounds motion: after the
// constraint solver and before positions are integrated, so no body ever moves faster than
// the limit; and hand parts moved out of what they went into once positions are integrated
// (hand_depenetration.h).
class HandWorld : public btDiscreteDynamicsWorld {
  public:
    HandWorld(btCollisionDispatcher* dispatcher, btBroadphaseInterface* broadphase,
              btConstraintSolver* solver, btCollisionConfiguration* configuration, double max_speed)
        : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration),
          dispatcher_(*dispatcher),
          max_speed_(max_speed) {}
    // What the limit found in the last substep.
    const SpeedCheck& last_check() const { return last_check_; }
    // The fastest any awake dynamic collider moves (max_point_speed) since the last substep.
    double fastest_collider() const { return fastest_collider_; }
    void note_collider_speed(double speed) {
        fastest_collider_ = std::max(fastest_collider_, speed);
    }
    // Only contact events need approach speeds.
    void set_measure_approach(bool measure) { measure_approach_ = measure; }
    void set_depenetration_moves(int moves) { depenetration_moves_ = moves; }
    // How fast a pair approached before the last substep's solver (0 when not measured).
    double approach_speed(const btPersistentManifold* m) const {
        const auto it = approach_speed_.find(m);
        return it == approach_speed_.end() ? 0.0 : it->second;
    }

  protected:
    void performDiscreteCollisionDetection() override {
        btDiscreteDynamicsWorld::performDiscreteCollisionDetection();
        add_hand_point_contacts(dispatcher_);
        approach_speed_.clear();
        if (measure_approach_) note_approach_speeds();
    }
    void integrateTransforms(btScalar h) override {
        last_check_ = {};
        fastest_collider_ = 0.0;
        for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) {
            btRigidBody& body = *m_nonStaticRigidBodies[i];
            if (body.isStaticOrKinematicObject() || !body.isActive()) continue;
            last_check_.add(limit_speeds(body, max_speed_));
            if (role_of(&body) == BodyRole::Collider)
                fastest_collider_ = std::max(fastest_collider_, max_point_speed(body));
        }
        btDiscreteDynamicsWorld::integrateTransforms(h);
        depenetrate_hands(*this, depenetration_moves_);
    }

  private:
    // Velocities here are those the last substep ended with: what the hand hit with.
    void note_approach_speeds() {
        for (int i = 0; i < dispatcher_.getNumManifolds(); ++i) {
            const btPersistentManifold* m = dispatcher_.getManifoldByIndexInternal(i);
            const auto* a = btRigidBody::upcast(m->getBody0());
            const auto* b = btRigidBody::upcast(m->getBody1());
            double fastest = 0.0;
            for (int p = 0; p < m->getNumContacts(); ++p) {
                const btManifoldPoint& pt = m->getContactPoint(p);
                btVector3 va(0, 0, 0), vb(0, 0, 0);
                if (a)
                    va = a->getVelocityInLocalPoint(pt.getPositionWorldOnA() -
                                                    a->getCenterOfMassPosition());
                if (b)
                    vb = b->getVelocityInLocalPoint(pt.getPositionWorldOnB() -
                                                    b->getCenterOfMassPosition());
                // The normal points from B to A: A approaching B moves against it.
                fastest =
                    std::max(fastest, static_cast<double>(-(va - vb).dot(pt.m_normalWorldOnB)));
            }
            approach_speed_[m] = fastest;
        }
    }

    btCollisionDispatcher& dispatcher_;
    double max_speed_;
    SpeedCheck last_check_;
    double fastest_collider_ = 0.0;
    std::unordered_map<const btPersistentManifold*, double> approach_speed_;
    int depenetration_moves_ = 1;
    bool measure_approach_ = false;
};

BodyRole role_of(const btCollisionObject* o) {
    return static_cast<BodyRole>(o->getUserIndex());
}

struct World::Entry {
    Collider collider;
    ColliderShape shape;
    std::unique_ptr<btRigidBody> body;
    Pose kinematic_from;
    Pose kinematic_to;
    bool kinematic_moving = false;
    std::array<bool, 2> touched{};
};

World::World(const Settings& settings)
    : settings_(settings),
      configuration_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<HandReachDispatcher>(configuration_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btSequentialImpulseConstraintSolver>()),
      world_(std::make_unique<HandWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                         configuration_.get(), settings.max_body_speed)) {
    register_face_contacts(*dispatcher_);
    register_capsule_collision(*dispatcher_);
    // A dynamic box against a mesh's triangle: its face clipped against the triangle, as a box
    // on a box is, not one GJK point per pair (collider_shape: only dynamic boxes carry the
    // faces this needs, so no other pair changes). Left alone 60 s on a table of 25 cm
    // triangles, boxes of 1-50 cm that moved over 1 mm, at 1/2/4/8 substeps: 9/8/5/7 of 18
    // before (1 cm ones falling through), 2/3/0/0 with this.
    world_->getDispatchInfo().m_enableSatConvex = true;
    world_->setGravity(to_bt(settings.gravity));
    btContactSolverInfo& info = world_->getSolverInfo();
    info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
    // Resolve every penetration by position correction alone, so pushing a hand into an
    // object never turns overlap into launch velocity.
    info.m_splitImpulse = true;
    info.m_splitImpulsePenetrationThreshold = 0.0f;
    // Split impulses move positions only, so undoing nearly all of a penetration in one step
    // adds no energy. Measured at 1 substep: Bullet's 0.8 leaves a palm 0.5 mm deeper in the
    // table and a pinch deeper in its cube; 1.0 wedges the displacement cube at its hole.
    info.m_erp2 = 0.95f;
    // Half of last substep's contact impulses to start from, not Bullet's 0.85: fingers that
    // the ghost pulls into a table as the hand withdraws rock between the contacts at their
    // ends and entered it by 0.02 mm at one substep per frame; at 0.5, 0.006 mm. Measured
    // over press_table, lift_hold and stack with the hand's script offset by up to 0.5 mm
    // (40 runs each): penetration over 0.01 mm in 4 of 40 runs (was 40 of 40), a held cube's
    // slip under 0.01 mm in 35 of 40 (38 at 0.85), stack's tracking unchanged.
    info.m_warmstartingFactor = 0.5f;
    // Bullet's 10 iterations kept. Held still, a cube squeezed between thumb and fingers
    // (lift_hold, final curl 0.5) stays 3.2 mm into the thumb at 10 iterations, the solver
    // unconverged, and 0.02 mm at 100; but grips are made on the 10 (robustness, bones/1, 800
    // plays: 730 succeed at 10, 690 at 30, 716 at 100), and while the fingers close the
    // deepest point stays 4-9 mm at any count.
}

World::~World() {
    for (auto& [handle, entry] : colliders_) world_->removeRigidBody(entry->body.get());
}

World::Entry* World::find(ColliderHandle handle) {
    auto it = colliders_.find(handle);
    return it == colliders_.end() ? nullptr : it->second.get();
}

const World::Entry* World::find(ColliderHandle handle) const {
    auto it = colliders_.find(handle);
    return it == colliders_.end() ? nullptr : it->second.get();
}

ColliderHandle World::add_collider(const Collider& collider) {
    auto entry = std::make_unique<Entry>();
    entry->collider = collider;
    entry->collider.pose.orientation.normalize();
    entry->shape = make_collider_shape(entry->collider);
    btCollisionShape* shape = entry->shape.shape.get();

    const bool dynamic = collider.motion == Motion::Dynamic;
    const btScalar mass = dynamic ? static_cast<btScalar>(collider.mass) : 0.0f;
    btVector3 inertia(0, 0, 0);
    if (dynamic) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform = to_bt(entry->collider.pose);
    info.m_friction = static_cast<btScalar>(collider.friction);
    info.m_restitution = static_cast<btScalar>(collider.restitution);
    entry->body = std::make_unique<btRigidBody>(info);
    btRigidBody* body = entry->body.get();

    const ShapeKind kind = collider.shape.kind;
    if (kind == ShapeKind::Sphere || kind == ShapeKind::Capsule || kind == ShapeKind::Cylinder) {
        body->setRollingFriction(
            kind == ShapeKind::Sphere
                ? static_cast<btScalar>(kBallRollingResistance * collider.shape.radius)
                : kRollingFriction);
        body->setSpinningFriction(kRollingFriction);
    }
    if (collider.motion == Motion::Kinematic) {
        body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
        body->setActivationState(DISABLE_DEACTIVATION);
        entry->kinematic_from = entry->kinematic_to = entry->collider.pose;
    }
    if (dynamic) {
        // Friction anchors keep a contact's first point and pull the two bodies back
        // together there, so what rests or is held does not creep. A rolling ball touches at
        // a new point every step, and the pull back to the old one drove it: a ball set rolling
        // at 0.05 m/s sped up to 0.12 m/s and rolled on for good.
        if (kind != ShapeKind::Sphere) {
            body->setCollisionFlags(body->getCollisionFlags() |
                                    btCollisionObject::CF_HAS_FRICTION_ANCHOR);
        }
        body->setSleepingThresholds(kSleepLinear, kSleepAngular);
        if (!settings_.sleeping) body->setActivationState(DISABLE_DEACTIVATION);
        const double inner = min_half_extent(*shape);
        body->setCcdMotionThreshold(static_cast<btScalar>(inner * 0.5));
        body->setCcdSweptSphereRadius(static_cast<btScalar>(inner * 0.8));
    }
    const ColliderHandle handle = next_handle_++;
    body->setUserIndex(static_cast<int>(BodyRole::Collider));
    body->setUserIndex2(static_cast<int>(handle));
    world_->addRigidBody(body);
    colliders_.emplace(handle, std::move(entry));
    return handle;
}

bool World::remove_collider(ColliderHandle handle) {
    Entry* e = find(handle);
    if (!e) return false;
    world_->removeRigidBody(e->body.get());
    colliders_.erase(handle);
    return true;
}

bool World::is_kinematic(ColliderHandle handle) const {
    const auto it = colliders_.find(handle);
    return it != colliders_.end() && it->second->collider.motion == Motion::Kinematic;
}

bool World::set_kinematic_target(ColliderHandle handle, const Pose& pose) {
    Entry* e = find(handle);
    if (!e || e->collider.motion != Motion::Kinematic) return false;
    e->kinematic_to = pose;
    e->kinematic_moving = true;
    const double turn = rotation_between(e->kinematic_from.orientation, pose.orientation).norm();
    kinematic_travel_ = std::max(kinematic_travel_,
                                 (pose.position - e->kinematic_from.position).norm() +
                                     turn * e->body->getCollisionShape()->getAngularMotionDisc());
    return true;
}

void World::carry(ColliderHandle handle, const Vec3& offset, double speed) {
    Entry* e = find(handle);
    const double distance = offset.norm();
    if (!e || e->collider.motion != Motion::Dynamic || distance <= 0.0) return;
    btRigidBody* body = e->body.get();
    btTransform t = body->getWorldTransform();
    t.setOrigin(t.getOrigin() + to_bt(offset));
    body->setWorldTransform(t);
    body->setInterpolationWorldTransform(t);
    const Vec3 direction = offset / distance;
    const Vec3 velocity = from_bt(body->getLinearVelocity());
    const double along = velocity.dot(direction);
    if (along < speed) body->setLinearVelocity(to_bt(velocity + (speed - along) * direction));
    body->activate(true);
    world_->updateSingleAabb(body);
}

bool World::teleport(ColliderHandle handle, const Pose& pose, const Vec3& linear_velocity,
                     const Vec3& angular_velocity) {
    Entry* e = find(handle);
    if (!e) return false;
    btRigidBody* body = e->body.get();
    const btTransform t = to_bt(pose);
    body->setWorldTransform(t);
    body->setInterpolationWorldTransform(t);
    if (e->collider.motion == Motion::Dynamic) {
        body->setLinearVelocity(to_bt(linear_velocity));
        body->setAngularVelocity(to_bt(angular_velocity));
        // At once: finite but huge velocities (in float) would otherwise turn the first
        // step's state into NaN (found by fuzzing the extension, tests/fuzz).
        limit_speeds(*body, settings_.max_body_speed);
        body->activate(true);
        world_->note_collider_speed(max_point_speed(*body));
    }
    e->kinematic_from = e->kinematic_to = pose;
    e->kinematic_moving = false;
    world_->updateSingleAabb(body);
    // Contacts cached at the old place would push the body back.
    broadphase_->getOverlappingPairCache()->cleanProxyFromPairs(body->getBroadphaseHandle(),
                                                                dispatcher_.get());
    return true;
}

std::optional<BodyState> World::body_state(ColliderHandle handle) const {
    const Entry* e = find(handle);
    if (!e) return std::nullopt;
    const btRigidBody* body = e->body.get();
    BodyState s;
    s.pose = from_bt(body->getWorldTransform());
    if (e->collider.motion == Motion::Dynamic) {
        s.linear_velocity = from_bt(body->getLinearVelocity());
        s.angular_velocity = from_bt(body->getAngularVelocity());
        s.asleep = body->getActivationState() == ISLAND_SLEEPING;
    }
    s.touched_by = e->touched;
    return s;
}

bool World::colliders_finite() const {
    return std::all_of(colliders_.begin(), colliders_.end(), [](const auto& entry) {
        const btRigidBody& b = *entry.second->body;
        const btTransform& t = b.getWorldTransform();
        return is_finite(from_bt(t)) && is_finite(from_bt(b.getLinearVelocity())) &&
               is_finite(from_bt(b.getAngularVelocity()));
    });
}

void World::add_hand_body(btRigidBody* body) {
    world_->addRigidBody(body, kHandGroup, btBroadphaseProxy::AllFilter & ~kHandGroup);
    ++hand_bodies_;
}

void World::remove_hand_body(btRigidBody* body) {
    world_->removeRigidBody(body);
    --hand_bodies_;
}

void World::set_measure_approach(bool measure) {
    world_->set_measure_approach(measure);
}

void World::set_hand_depenetration_moves(int moves) {
    world_->set_depenetration_moves(moves);
}

bool World::needs_step() const {
    if (hand_bodies_ > 0) return true;
    for (const auto& [handle, e] : colliders_) {
        if (e->kinematic_moving) return true;
        if (e->collider.motion == Motion::Dynamic && e->body->isActive()) return true;
    }
    return false;
}

SpeedCheck World::step(double h, double fraction) {
    for (auto& [handle, e] : colliders_) {
        if (!e->kinematic_moving) continue;
        e->body->setWorldTransform(
            to_bt(interpolate(e->kinematic_from, e->kinematic_to, fraction)));
    }
    // maxSubSteps 0: exactly one step of h, forces cleared after it.
    world_->stepSimulation(static_cast<btScalar>(h), 0);

    // Contact distances as of the end of this substep, not of its collision phase.
    for (int i = 0; i < dispatcher_->getNumManifolds(); ++i) {
        btPersistentManifold* m = dispatcher_->getManifoldByIndexInternal(i);
        const btCollisionObject* a = m->getBody0();
        const btCollisionObject* b = m->getBody1();
        if (role_of(a) == BodyRole::Hand || role_of(b) == BodyRole::Hand) {
            m->refreshContactPoints(a->getWorldTransform(), b->getWorldTransform());
        }
    }
    return world_->last_check();
}

void World::finish_kinematic_motion() {
    kinematic_travel_ = 0.0;
    for (auto& [handle, e] : colliders_) {
        if (!e->kinematic_moving) continue;
        e->kinematic_from = e->kinematic_to;
        e->kinematic_moving = false;
        // Zero velocity while it stands still, so resting objects are not dragged.
        e->body->setInterpolationWorldTransform(e->body->getWorldTransform());
    }
}

namespace {

// How far a collider may move in `lookahead_s` as it moves now: a dynamic one at its speed
// (its spin carrying its furthest point), a kinematic one as far as any goes toward its target
// this frame, a static or sleeping one not at all.
double travel_of(const btCollisionObject& o, double lookahead_s, double kinematic_travel) {
    const btRigidBody* body = btRigidBody::upcast(&o);
    if (!body) return 0.0;
    if (body->isKinematicObject()) return kinematic_travel;  // flagged static too: massless
    if (body->isStaticObject() || !body->isActive()) return 0.0;
    return max_point_speed(*body) * lookahead_s;
}

}  // namespace

bool World::any_collider_near(const Vec3& lo, const Vec3& hi, double lookahead_s) const {
    return collider_near(lo, hi, lookahead_s, false);
}

bool World::any_movable_collider_near(const Vec3& lo, const Vec3& hi) const {
    return collider_near(lo, hi, 0.0, true);
}

bool World::collider_near(const Vec3& lo, const Vec3& hi, double lookahead_s,
                          bool movable_only) const {
    struct Near : btBroadphaseAabbCallback {
        Vec3 lo, hi;
        // 0: whatever the broadphase finds near; else each found collider's own travel in that
        // time decides whether it comes near.
        double lookahead_s = 0.0;
        double kinematic_travel = 0.0;
        bool movable_only = false;
        bool found = false;
        bool process(const btBroadphaseProxy* proxy) override {
            const auto* o = static_cast<const btCollisionObject*>(proxy->m_clientObject);
            if (role_of(o) != BodyRole::Collider) return true;
            if (movable_only && motion_of(*o) == Motion::Static) return true;
            const auto* plane = dynamic_cast<const btStaticPlaneShape*>(o->getCollisionShape());
            if (!plane) {
                if (lookahead_s <= 0.0) {
                    found = true;
                    return true;
                }
                const Vec3 travel = Vec3::Constant(travel_of(*o, lookahead_s, kinematic_travel));
                const Vec3 a = from_bt(proxy->m_aabbMin) - travel;
                const Vec3 b = from_bt(proxy->m_aabbMax) + travel;
                found =
                    found || ((a.array() <= hi.array()).all() && (b.array() >= lo.array()).all());
                return true;
            }
            // A plane's bounds are the whole world: test the box's lowest corner instead.
            const btVector3 n = o->getWorldTransform().getBasis() * plane->getPlaneNormal();
            const double offset =
                plane->getPlaneConstant() + n.dot(o->getWorldTransform().getOrigin());
            double lowest = 0.0;
            for (int i = 0; i < 3; ++i) lowest += n[i] * (n[i] > 0 ? lo[i] : hi[i]);
            found = found || lowest - offset <= 0.0;
            return true;
        }
    } near;
    near.lo = lo;
    near.hi = hi;
    near.movable_only = movable_only;
    broadphase_->aabbTest(to_bt(lo), to_bt(hi), near);
    if (near.found || !(lookahead_s > 0.0)) return near.found;
    // Nothing near now: what moves may come near within the lookahead.
    const double widest = std::max(kinematic_travel_, world_->fastest_collider() * lookahead_s);
    if (widest <= 0.0) return false;
    near.lookahead_s = lookahead_s;
    near.kinematic_travel = kinematic_travel_;
    broadphase_->aabbTest(to_bt(lo - Vec3::Constant(widest)), to_bt(hi + Vec3::Constant(widest)),
                          near);
    return near.found;
}

void World::for_each_hand_contact(const std::function<void(const ContactPoint&)>& visit) const {
    for (int i = 0; i < dispatcher_->getNumManifolds(); ++i) {
        const btPersistentManifold* m = dispatcher_->getManifoldByIndexInternal(i);
        const btCollisionObject* a = m->getBody0();
        const btCollisionObject* b = m->getBody1();
        const bool swapped = role_of(a) == BodyRole::Collider;
        if (swapped) std::swap(a, b);
        if (role_of(a) != BodyRole::Hand || role_of(b) != BodyRole::Collider) continue;
        const double approach = world_->approach_speed(m);
        for (int p = 0; p < m->getNumContacts(); ++p) {
            const btManifoldPoint& pt = m->getContactPoint(p);
            // Bullet's normal points from its second body toward its first.
            const Vec3 normal = from_bt(pt.m_normalWorldOnB) * (swapped ? -1.0 : 1.0);
            const Vec3 point =
                from_bt(swapped ? pt.getPositionWorldOnA() : pt.getPositionWorldOnB());
            const Vec3 impulse_on_collider = impulse_on_first(pt) * (swapped ? 1.0 : -1.0);
            const btRigidBody* rb = btRigidBody::upcast(b);
            const Vec3 velocity = rb ? from_bt(rb->getVelocityInLocalPoint(
                                           to_bt(point) - rb->getCenterOfMassPosition()))
                                     : Vec3::Zero();
            visit({a, static_cast<ColliderHandle>(b->getUserIndex2()), pt.getDistance(),
                   pt.getAppliedImpulse(), motion_of(*b), point, normal, impulse_on_collider,
                   from_bt(b->getWorldTransform().getOrigin()), approach, velocity});
        }
    }
}

void World::for_each_collider_contact(
    const std::function<void(const ContactPoint&, ColliderHandle other)>& visit) const {
    for (int i = 0; i < dispatcher_->getNumManifolds(); ++i) {
        const btPersistentManifold* m = dispatcher_->getManifoldByIndexInternal(i);
        const btCollisionObject* a = m->getBody0();
        const btCollisionObject* b = m->getBody1();
        if (role_of(a) != BodyRole::Collider || role_of(b) != BodyRole::Collider) continue;
        const double approach = world_->approach_speed(m);
        for (int p = 0; p < m->getNumContacts(); ++p) {
            const btManifoldPoint& pt = m->getContactPoint(p);
            visit({nullptr, static_cast<ColliderHandle>(a->getUserIndex2()), pt.getDistance(),
                   pt.getAppliedImpulse(), motion_of(*a), from_bt(pt.getPositionWorldOnA()),
                   -from_bt(pt.m_normalWorldOnB), impulse_on_first(pt),
                   from_bt(a->getWorldTransform().getOrigin()), approach},
                  static_cast<ColliderHandle>(b->getUserIndex2()));
        }
    }
}

double World::depth_in_colliders(btCollisionShape& shape, const Pose& pose, double ahead_s) const {
    struct Near : btBroadphaseAabbCallback {
        std::vector<const btCollisionObject*> found;
        bool process(const btBroadphaseProxy* proxy) override {
            const auto* o = static_cast<const btCollisionObject*>(proxy->m_clientObject);
            if (role_of(o) == BodyRole::Collider) found.push_back(o);
            return true;
        }
    } near;
    btCollisionObject probe;
    probe.setCollisionShape(&shape);
    probe.setWorldTransform(to_bt(pose));
    btVector3 lo, hi;
    shape.getAabb(probe.getWorldTransform(), lo, hi);
    // Moved on, a collider may reach the probe from as far as it moves meanwhile.
    const auto moves_on = [&](const btCollisionObject& o) {
        return ahead_s > 0.0 && !o.isStaticOrKinematicObject() &&
               o.getActivationState() != ISLAND_SLEEPING;
    };
    const auto reach = static_cast<btScalar>(std::max(ahead_s, 0.0) * world_->fastest_collider());
    const btVector3 pad(reach, reach, reach);
    world_->getBroadphase()->aabbTest(lo - pad, hi + pad, near);
    double deepest = 0.0;
    for (const btCollisionObject* collider : near.found) {
        if (!moves_on(*collider)) {
            deepest = std::max(deepest, pair_depth(*world_, probe, *collider).depth);
            continue;
        }
        const auto* body = static_cast<const btRigidBody*>(collider);
        btCollisionObject moved;
        moved.setCollisionShape(const_cast<btCollisionShape*>(body->getCollisionShape()));
        moved.setWorldTransform(
            to_bt(moved_on(from_bt(body->getWorldTransform()), from_bt(body->getLinearVelocity()),
                           from_bt(body->getAngularVelocity()), ahead_s)));
        deepest = std::max(deepest, pair_depth(*world_, probe, moved).depth);
    }
    return deepest;
}

void World::mark_touched(ColliderHandle handle, HandSide side) {
    if (Entry* e = find(handle)) e->touched[static_cast<int>(side)] = true;
}

void World::clear_touched() {
    for (auto& [handle, e] : colliders_) e->touched = {};
}

}  // namespace physhand
