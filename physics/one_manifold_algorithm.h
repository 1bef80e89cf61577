#pragma once

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <btBulletCollisionCommon.h>

namespace physhand {

// A collision algorithm of this project's for one pair: it keeps the pair's points in one
// manifold of its own, (`body0`, `body1`), made only if the dispatcher would collide them,
// and, as Bullet's own convex pairs, has no continuous collision detection.
class OneManifoldAlgorithm : public btActivatingCollisionAlgorithm {
  public:
    OneManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                         const btCollisionObjectWrapper* first,
                         const btCollisionObjectWrapper* second, const btCollisionObject* body0,
                         const btCollisionObject* body1)
        : btActivatingCollisionAlgorithm(info, first, second) {
        if (m_dispatcher->needsCollision(body0, body1))
            manifold_ = m_dispatcher->getNewManifold(body0, body1);
    }
    ~OneManifoldAlgorithm() override {
        if (manifold_) m_dispatcher->releaseManifold(manifold_);
    }
    OneManifoldAlgorithm(const OneManifoldAlgorithm&) = delete;
    OneManifoldAlgorithm& operator=(const OneManifoldAlgorithm&) = delete;

    btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                   btManifoldResult*) override {
        return 1;
    }

    void getAllContactManifolds(btManifoldArray& manifolds) override {
        if (manifold_) manifolds.push_back(manifold_);
    }

  protected:
    btPersistentManifold* manifold_ = nullptr;
};

}  // namespace physhand
