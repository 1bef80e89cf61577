#include "pair_depth.h"

#include <btBulletCollisionCommon.h>

namespace physhand {

PairDepth pair_depth(btCollisionWorld& world, const btCollisionObject& a,
                     const btCollisionObject& b) {
    PairDepth deepest;
    const btCollisionObjectWrapper first(nullptr, a.getCollisionShape(), &a, a.getWorldTransform(),
                                         -1, -1);
    const btCollisionObjectWrapper second(nullptr, b.getCollisionShape(), &b, b.getWorldTransform(),
                                          -1, -1);
    btDispatcher& dispatcher = *world.getDispatcher();
    btCollisionAlgorithm* algorithm =
        dispatcher.findAlgorithm(&first, &second, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    if (!algorithm) return deepest;
    btManifoldResult result(&first, &second);
    algorithm->processCollision(&first, &second, world.getDispatchInfo(), &result);
    btManifoldArray manifolds;
    algorithm->getAllContactManifolds(manifolds);
    for (int i = 0; i < manifolds.size(); ++i) {
        const btPersistentManifold& m = *manifolds[i];
        // The algorithm may keep the pair in either order; its normal points toward body 0.
        const bool a_first = m.getBody0() == &a;
        for (int p = 0; p < m.getNumContacts(); ++p) {
            const btManifoldPoint& point = m.getContactPoint(p);
            if (-point.getDistance() <= deepest.depth) continue;
            deepest.depth = -point.getDistance();
            deepest.out = a_first ? point.m_normalWorldOnB : -point.m_normalWorldOnB;
            deepest.on_a = a_first ? point.getPositionWorldOnA() : point.getPositionWorldOnB();
            deepest.on_b = a_first ? point.getPositionWorldOnB() : point.getPositionWorldOnA();
        }
    }
    algorithm->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algorithm);
    return deepest;
}

}  // namespace physhand
