#include "contact_insertion.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

namespace physhand {
namespace {

// A point `depth` into the pair at the same place on both bodies, as a friction anchor or not.
btManifoldPoint point_at(btScalar depth, bool anchor) {
    const btVector3 at(0, 0, 0);
    btManifoldPoint p(at, at, btVector3(0, 1, 0), -depth);
    p.m_combinedFriction = 1.0f;
    if (anchor) p.m_contactPointFlags |= BT_CONTACT_FLAG_FRICTION_ANCHOR;
    return p;
}

// A grip's anchored point, its friction holding (lateral impulse within the cone), and a
// fresh point found at the same place.
class AnchorAgainstFreshPoint : public ::testing::Test {
  protected:
    AnchorAgainstFreshPoint() : manifold_(&a_, &b_, 0, 0.02f, 0.0f) {
        btManifoldPoint held = point_at(0.002f, true);
        held.m_appliedImpulse = 1.0f;
        held.m_appliedImpulseLateral1 = 0.3f;
        manifold_.addManifoldPoint(held);
    }
    btScalar depth_after(btScalar fresh_depth) {
        insert_contact_point(manifold_, point_at(fresh_depth, true));
        EXPECT_EQ(manifold_.getNumContacts(), 1);
        return -manifold_.getContactPoint(0).getDistance();
    }
    btCollisionObject a_, b_;
    btPersistentManifold manifold_;
};

TEST_F(AnchorAgainstFreshPoint,
       KeepsTheAnchorAsBulletDoesWhileTheFreshPointIsNoDeeperThanTheSlack) {
    EXPECT_FLOAT_EQ(depth_after(0.002f + kAnchorSlack * 0.9f), 0.002f);
}

TEST_F(AnchorAgainstFreshPoint, GivesWayToAFreshPointDeeperThanTheSlack) {
    EXPECT_FLOAT_EQ(depth_after(0.020f), 0.020f);
    // What the solver warm-starts from stays, as when Bullet replaces a point.
    EXPECT_FLOAT_EQ(manifold_.getContactPoint(0).m_appliedImpulse, 1.0f);
}

TEST_F(AnchorAgainstFreshPoint, AFreshPointFarFromEveryOtherIsAdded) {
    btManifoldPoint far = point_at(0.001f, true);
    far.m_localPointA = far.m_localPointB = btVector3(0.05f, 0, 0);
    insert_contact_point(manifold_, far);
    EXPECT_EQ(manifold_.getNumContacts(), 2);
}

}  // namespace
}  // namespace physhand
