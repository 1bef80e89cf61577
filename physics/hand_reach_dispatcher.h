#pragma once

#include <btBulletCollisionCommon.h>

#include "world.h"

namespace physhand {

// Bullet's dispatcher, with every manifold of a hand part reaching kHandContactReach ahead.
class HandReachDispatcher : public btCollisionDispatcher {
  public:
    using btCollisionDispatcher::btCollisionDispatcher;
    btPersistentManifold* getNewManifold(const btCollisionObject* a,
                                         const btCollisionObject* b) override {
        btPersistentManifold* m = btCollisionDispatcher::getNewManifold(a, b);
        if (is_hand(*a) || is_hand(*b))
            m->setContactBreakingThreshold(static_cast<btScalar>(kHandContactReach));
        return m;
    }

  private:
    static bool is_hand(const btCollisionObject& o) {
        return static_cast<BodyRole>(o.getUserIndex()) == BodyRole::Hand;
    }
};

}  // namespace physhand
