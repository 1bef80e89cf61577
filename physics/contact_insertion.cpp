#include "contact_insertion.h"

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

}  // namespace physhand
