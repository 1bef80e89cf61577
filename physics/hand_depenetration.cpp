#include "hand_depenetration.h"

#include <btBulletDynamicsCommon.h>

#include <map>
#include <utility>
#include <vector>

#include "pair_depth.h"
#include "world.h"

namespace physhand {

namespace {

// A kept point may claim this much more depth than its pair has before it is settled.
constexpr double kClaimSlack = 0.0005;

struct Touch {
    const btCollisionObject* other;
    btPersistentManifold* manifold;
};

struct PartTouches {
    std::vector<Touch> movable;
    std::vector<Touch> fixed;
};

// Puts every point of `manifold` (part, other) that claims more depth than `now` has (plus
// the slack), as the bodies are now placed, at the pair's deepest point: a kept anchor read
// along its old normal would push the part back in or tell of depth that is not there. Each
// keeps its impulses, so what the solver did in this substep is still read as a contact
// (dropping them lost it: a thumb pushed into a cube and moved out each substep counted as
// touching nothing, and its drive pushed on as if free). Apart, they are dropped.
void settle_claims(btPersistentManifold& manifold, const btCollisionObject& part,
                   const PairDepth& now) {
    const btTransform& a = manifold.getBody0()->getWorldTransform();
    const btTransform& b = manifold.getBody1()->getWorldTransform();
    const bool part_first = manifold.getBody0() == &part;
    for (int p = manifold.getNumContacts() - 1; p >= 0; --p) {
        btManifoldPoint& point = manifold.getContactPoint(p);
        const double distance =
            (a * point.m_localPointA - b * point.m_localPointB).dot(point.m_normalWorldOnB);
        if (-distance <= now.depth + kClaimSlack) continue;
        if (now.depth <= 0.0) {  // apart: no point of theirs to put it at
            manifold.removeContactPoint(p);
            continue;
        }
        const btVector3& on_first = part_first ? now.on_a : now.on_b;
        const btVector3& on_second = part_first ? now.on_b : now.on_a;
        point.m_localPointA = a.invXform(on_first);
        point.m_localPointB = b.invXform(on_second);
        point.m_positionWorldOnA = on_first;
        point.m_positionWorldOnB = on_second;
        point.m_normalWorldOnB = part_first ? now.out : -now.out;
        point.m_distance1 = static_cast<btScalar>(-now.depth);
        point.m_contactPointFlags &= ~BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
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
PairDepth depth_now(btCollisionWorld& world, const btRigidBody& part,
                    const btCollisionObject& other) {
    return may_overlap(part, other) ? pair_depth(world, part, other) : PairDepth{};
}

struct MoveOut {
    bool moved = false;
    PairDepth before;  // the pair as found before the move
};

// Moves `part` out of `other` to kHandDepthAllowed, in at most `moves` moves.
MoveOut move_out(btCollisionWorld& world, btRigidBody& part, const btCollisionObject& other,
                 int moves) {
    const PairDepth found = depth_now(world, part, other);
    PairDepth now = found;
    bool moved = false;
    for (int move = 0; move < moves; ++move) {
        const double excess = now.depth - kHandDepthAllowed;
        if (excess <= 0.0) break;
        move_part(part, now.out * static_cast<btScalar>(excess));
        moved = true;
        if (move + 1 < moves) now = depth_now(world, part, other);
    }
    return {moved, found};
}

}  // namespace

void depenetrate_hands(btCollisionWorld& world, int moves) {
    btDispatcher& dispatcher = *world.getDispatcher();
    // Ordered by the parts' place in the manifold list, so a run repeats exactly.
    std::vector<btRigidBody*> order;
    std::map<btRigidBody*, PartTouches> touches;
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
        btPersistentManifold* m = dispatcher.getManifoldByIndexInternal(i);
        const btCollisionObject* a = m->getBody0();
        const btCollisionObject* b = m->getBody1();
        if (role_of(b) == BodyRole::Hand) std::swap(a, b);
        if (role_of(a) != BodyRole::Hand || role_of(b) != BodyRole::Collider) continue;
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
        std::vector<PairDepth> found;
        for (const Touch& touch : t.movable) {
            const MoveOut m = move_out(world, *part, *touch.other, moves);
            moved |= m.moved;
            found.push_back(m.before);
        }
        if (moved) {
            for (const Touch& touch : t.fixed) {
                if (move_out(world, *part, *touch.other, moves).moved)
                    settle_claims(*touch.manifold, *part, depth_now(world, *part, *touch.other));
            }
        }
        for (std::size_t i = 0; i < t.movable.size(); ++i) {
            // What was found holds while the part has not moved.
            const Touch& touch = t.movable[i];
            settle_claims(*touch.manifold, *part,
                          moved ? depth_now(world, *part, *touch.other) : found[i]);
        }
    }
}

}  // namespace physhand
