#include "capsule_end_contacts.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>

#include <optional>
#include <utility>

#include "world.h"

namespace physhand {

namespace {

bool is_hand_capsule(const btCollisionObject& o) {
    return static_cast<BodyRole>(o.getUserIndex()) == BodyRole::Hand &&
           o.getCollisionShape()->getShapeType() == CAPSULE_SHAPE_PROXYTYPE;
}

// A contact as Bullet states one: the point on the collider, the normal from the collider
// toward the hand, and the distance between the surfaces (negative: penetrating).
struct Contact {
    btVector3 normal;
    btVector3 on_collider;
    btScalar distance;
};

Contact plane_contact(const btVector3& centre, btScalar radius, const btCollisionObject& plane) {
    const auto& shape = static_cast<const btStaticPlaneShape&>(*plane.getCollisionShape());
    const btTransform& t = plane.getWorldTransform();
    const btVector3 normal = t.getBasis() * shape.getPlaneNormal();
    const btScalar height =
        normal.dot(centre) - normal.dot(t.getOrigin()) - shape.getPlaneConstant();
    return {normal, centre - normal * height, height - radius};
}

Contact box_contact(const btVector3& centre, btScalar radius, const btCollisionObject& box) {
    const btVector3 half =
        static_cast<const btBoxShape&>(*box.getCollisionShape()).getHalfExtentsWithMargin();
    const btTransform& t = box.getWorldTransform();
    const btVector3 local = t.invXform(centre);
    btVector3 nearest = local;
    nearest.setMax(-half);
    nearest.setMin(half);
    const btVector3 out = local - nearest;
    const btScalar outside = out.length();
    if (outside > SIMD_EPSILON) {
        return {t.getBasis() * (out / outside), t * nearest, outside - radius};
    }
    // Inside: out through the nearest face.
    int axis = 0;
    for (int i = 1; i < 3; ++i) {
        if (half[i] - btFabs(local[i]) < half[axis] - btFabs(local[axis])) axis = i;
    }
    btVector3 normal(0, 0, 0);
    normal[axis] = local[axis] < 0 ? -1 : 1;
    nearest[axis] = normal[axis] * half[axis];
    return {t.getBasis() * normal, t * nearest, -(half[axis] - btFabs(local[axis])) - radius};
}

std::optional<Contact> convex_contact(const btVector3& centre, btScalar radius,
                                      const btCollisionObject& other, btScalar reach) {
    btSphereShape sphere(radius);
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver penetration;
    const auto* convex = static_cast<const btConvexShape*>(other.getCollisionShape());
    btGjkPairDetector gjk(convex, &sphere, &simplex, &penetration);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = other.getWorldTransform();
    input.m_transformB = btTransform(btMatrix3x3::getIdentity(), centre);
    const btScalar far = radius + convex->getMargin() + reach;
    input.m_maximumDistanceSquared = far * far;
    btPointCollector found;
    gjk.getClosestPoints(input, found, nullptr);
    if (!found.m_hasResult) return std::nullopt;
    // The collector's B is the sphere: turn the contact around to the collider's side.
    const btVector3 on_collider =
        found.m_pointInWorld + found.m_normalOnBInWorld * found.m_distance;
    return Contact{-found.m_normalOnBInWorld, on_collider, found.m_distance};
}

// An end's point takes the place of the manifold's nearest point, as Bullet's own insertion
// does, unless that point is deeper and elsewhere on the capsule: the distance to a convex
// collider along the capsule is least at an end unless the capsule crosses an edge or a
// curved surface, whose contact it then keeps beside the ends'.
void merge_end_contact(const btManifoldPoint& end, bool hand_first, btScalar radius,
                       btPersistentManifold& manifold) {
    constexpr btScalar kDeeper = 1e-5f;  // m: more than float rounding
    const auto on_hand = [hand_first](const btManifoldPoint& p) {
        return hand_first ? p.m_localPointA : p.m_localPointB;
    };
    const int nearest = manifold.getCacheEntry(end);
    if (nearest < 0) {
        manifold.addManifoldPoint(end);
        return;
    }
    const btManifoldPoint& there = manifold.getContactPoint(nearest);
    const bool keep = there.getDistance() < end.getDistance() - kDeeper &&
                      (on_hand(there) - on_hand(end)).length2() > radius * radius;
    if (keep) {
        manifold.addManifoldPoint(end);
    } else {
        manifold.replaceContactPoint(end, nearest);
    }
}

}  // namespace

void add_capsule_end_contacts(btCollisionDispatcher& dispatcher) {
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
        btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(i);
        const btCollisionObject* hand = manifold->getBody0();
        const btCollisionObject* other = manifold->getBody1();
        const bool hand_first = is_hand_capsule(*hand);
        if (!hand_first) std::swap(hand, other);
        if (!is_hand_capsule(*hand)) continue;
        // Nothing of the capsule within reach: neither end is.
        if (manifold->getNumContacts() == 0) continue;
        const btCollisionShape* other_shape = other->getCollisionShape();
        const int other_type = other_shape->getShapeType();
        if (other_type != STATIC_PLANE_PROXYTYPE && !other_shape->isConvex()) continue;

        const auto& capsule = static_cast<const btCapsuleShape&>(*hand->getCollisionShape());
        const btTransform& t = hand->getWorldTransform();
        const btCollisionObjectWrapper hand_wrap(nullptr, &capsule, hand, t, -1, -1);
        const btCollisionObjectWrapper other_wrap(nullptr, other_shape, other,
                                                  other->getWorldTransform(), -1, -1);
        const btScalar reach = manifold->getContactBreakingThreshold();
        const btScalar radius = capsule.getRadius();
        btVector3 axis(0, 0, 0);
        axis[capsule.getUpAxis()] = capsule.getHalfHeight();
        for (const btVector3& end : {t * axis, t * -axis}) {
            const std::optional<Contact> c =
                other_type == STATIC_PLANE_PROXYTYPE ? plane_contact(end, radius, *other)
                : other_type == BOX_SHAPE_PROXYTYPE  ? box_contact(end, radius, *other)
                                                     : convex_contact(end, radius, *other, reach);
            if (!c) continue;
            // Bullet builds the point (friction, restitution, local points) in a manifold of
            // its own, in the real one's order; merge_end_contact says why not in place.
            btPersistentManifold built(manifold->getBody0(), manifold->getBody1(), 0, reach,
                                       manifold->getContactProcessingThreshold());
            btManifoldResult result(hand_first ? &hand_wrap : &other_wrap,
                                    hand_first ? &other_wrap : &hand_wrap);
            result.setPersistentManifold(&built);
            if (hand_first) {
                result.addContactPoint(c->normal, c->on_collider, c->distance);
            } else {
                const btVector3 on_hand = c->on_collider + c->normal * c->distance;
                result.addContactPoint(-c->normal, on_hand, c->distance);
            }
            if (built.getNumContacts() == 1) {
                merge_end_contact(built.getContactPoint(0), hand_first, radius, *manifold);
            }
        }
    }
}

}  // namespace physhand
