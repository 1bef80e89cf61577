#include "hand_depenetration.h"

#include <btBulletDynamicsCommon.h>

#include <map>
#include <utility>
#include <vector>

#include "pair_depth.h"
#include "world.h"

namespace physhand {

namespace {

// A kept point may claim this much more depth than its pair has before it is dropped.
constexpr double kClaimSlack = 0.0005;

bool has_role(const btCollisionObject& o, BodyRole role) {
    return static_cast<BodyRole>(o.getUserIndex()) == role;
}

struct Touch {
    const btCollisionObject* other;
    btPersistentManifold* manifold;
};

struct PartTouches {
    std::vector<Touch> movable;
    std::vector<Touch> fixed;
};

// Drops the points of `manifold` lying deeper than `depth` (plus the slack) as the bodies are
// now placed.
void drop_deeper_claims(btPersistentManifold& manifold, double depth) {
    const btTransform& a = manifold.getBody0()->getWorldTransform();
    const btTransform& b = manifold.getBody1()->getWorldTransform();
    for (int p = manifold.getNumContacts() - 1; p >= 0; --p) {
        const btManifoldPoint& point = manifold.getContactPoint(p);
        const double distance =
            (a * point.m_localPointA - b * point.m_localPointB).dot(point.m_normalWorldOnB);
        if (-distance > depth + kClaimSlack) manifold.removeContactPoint(p);
    }
}

void move_part(btRigidBody& part, const btVector3& by) {
    btTransform t = part.getWorldTransform();
    t.setOrigin(t.getOrigin() + by);
    part.setWorldTransform(t);
    part.setInterpolationWorldTransform(t);
}

// Whether the two objects' bounding boxes, where they are now, meet: they can overlap.
bool may_overlap(const btCollisionObject& a, const btCollisionObject& b) {
    btVector3 a_lo, a_hi, b_lo, b_hi;
    a.getCollisionShape()->getAabb(a.getWorldTransform(), a_lo, a_hi);
    b.getCollisionShape()->getAabb(b.getWorldTransform(), b_lo, b_hi);
    return TestAabbAgainstAabb2(a_lo, a_hi, b_lo, b_hi);
}

// How deep `part` lies in `other` now.
double depth_now(btCollisionWorld& world, const btRigidBody& part, const btCollisionObject& other) {
    return may_overlap(part, other) ? pair_depth(world, part, other).depth : 0.0;
}

struct MoveOut {
    bool moved = false;
    double depth = 0.0;  // left, m
};

// Moves `part` out of `other` to kHandDepthAllowed.
MoveOut move_out(btCollisionWorld& world, btRigidBody& part, const btCollisionObject& other) {
    if (!may_overlap(part, other)) return {};
    const PairDepth found = pair_depth(world, part, other);
    const double excess = found.depth - kHandDepthAllowed;
    if (excess <= 0.0) return {false, found.depth};
    move_part(part, found.out * static_cast<btScalar>(excess));
    return {true, kHandDepthAllowed};
}

}  // namespace

void depenetrate_hands(btCollisionWorld& world) {
    btDispatcher& dispatcher = *world.getDispatcher();
    // Ordered by the parts' place in the manifold list, so a run repeats exactly.
    std::vector<btRigidBody*> order;
    std::map<btRigidBody*, PartTouches> touches;
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
        btPersistentManifold* m = dispatcher.getManifoldByIndexInternal(i);
        const btCollisionObject* a = m->getBody0();
        const btCollisionObject* b = m->getBody1();
        if (has_role(*b, BodyRole::Hand)) std::swap(a, b);
        if (!has_role(*a, BodyRole::Hand) || !has_role(*b, BodyRole::Collider)) continue;
        auto* part = const_cast<btRigidBody*>(btRigidBody::upcast(a));
        if (!part || !part->hasContactResponse()) continue;
        auto [it, fresh] = touches.try_emplace(part);
        if (fresh) order.push_back(part);
        (b->isStaticOrKinematicObject() ? it->second.fixed : it->second.movable).push_back({b, m});
    }
    for (btRigidBody* part : order) {
        const PartTouches& t = touches[part];
        if (t.movable.empty()) continue;
        bool moved = false;
        std::vector<double> depths;
        for (const Touch& touch : t.movable) {
            const MoveOut m = move_out(world, *part, *touch.other);
            moved |= m.moved;
            depths.push_back(m.depth);
        }
        if (moved) {
            for (const Touch& touch : t.fixed) {
                if (move_out(world, *part, *touch.other).moved)
                    drop_deeper_claims(*touch.manifold, kHandDepthAllowed);
            }
        }
        for (std::size_t i = 0; i < t.movable.size(); ++i) {
            // Each move may have changed the depths found before it.
            const double depth = moved ? depth_now(world, *part, *t.movable[i].other) : depths[i];
            drop_deeper_claims(*t.movable[i].manifold, depth);
        }
    }
}

}  // namespace physhand
