#include "contact_insertion.h"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

namespace physhand {

void insert_contact_point(btPersistentManifold& manifold, const btManifoldPoint& point) {
    const int nearest = manifold.getCacheEntry(point);
    if (nearest < 0) {
        manifold.addManifoldPoint(point);
        return;
    }
    // Bullet keeps the old point only when the new one asks for an anchor.
    btManifoldPoint fresh = point;
    if (point.getDistance() < manifold.getContactPoint(nearest).getDistance() - kAnchorSlack)
        fresh.m_contactPointFlags &= ~BT_CONTACT_FLAG_FRICTION_ANCHOR;
    manifold.replaceContactPoint(fresh, nearest);
}

std::optional<btManifoldPoint> build_contact_point(btManifoldResult& result,
                                                   btPersistentManifold& manifold,
                                                   const btVector3& normal_on_b,
                                                   const btVector3& point_on_b, btScalar distance) {
    btPersistentManifold built(manifold.getBody0(), manifold.getBody1(), 0,
                               manifold.getContactBreakingThreshold(),
                               manifold.getContactProcessingThreshold());
    result.setPersistentManifold(&built);
    result.addContactPoint(normal_on_b, point_on_b, distance);
    result.setPersistentManifold(&manifold);
    if (built.getNumContacts() != 1) return std::nullopt;
    return built.getContactPoint(0);
}

}  // namespace physhand
