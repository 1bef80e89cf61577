#include "hand_depenetration.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <random>

#include "ball_contact.h"
#include "capsule_collision.h"
#include "hand_reach_dispatcher.h"
#include "pair_depth.h"
#include "world.h"

namespace physhand {
namespace {

constexpr btScalar kRadius = 0.008f;
constexpr btScalar kLength = 0.03f;
const btVector3 kHalf(0.02f, 0.02f, 0.02f);

// A finger capsule and boxes in a collision world set up as World's is.
class HandDepenetration : public ::testing::Test {
  protected:
    HandDepenetration() { register_capsule_collision(dispatcher_); }

    // A body of `role`: dynamic (mass > 0) or fixed.
    btRigidBody& add(btCollisionShape& shape, const btTransform& pose, double mass, BodyRole role) {
        btVector3 inertia(0, 0, 0);
        if (mass > 0) shape.calculateLocalInertia(static_cast<btScalar>(mass), inertia);
        bodies_.push_back(
            std::make_unique<btRigidBody>(static_cast<btScalar>(mass), nullptr, &shape, inertia));
        btRigidBody& body = *bodies_.back();
        body.setWorldTransform(pose);
        body.setUserIndex(static_cast<int>(role));
        world_.addCollisionObject(&body);
        return body;
    }

    // The deepest any point of `capsule`'s segment, swollen by its radius, lies in the box
    // at `box`: dense sampling, as the capsule-box test measures it.
    static double sampled_depth(const btCollisionObject& capsule, const btTransform& box) {
        const btVector3 a = capsule.getWorldTransform() * btVector3(0, 0, kLength / 2);
        const btVector3 b = capsule.getWorldTransform() * btVector3(0, 0, -kLength / 2);
        double deepest = 0.0;
        for (int s = 0; s <= 4000; ++s) {
            const btVector3 p = a + (b - a) * (btScalar(s) / 4000);
            deepest = std::max(
                deepest, -static_cast<double>(ball_box_contact(p, kRadius, box, kHalf).distance));
        }
        return deepest;
    }

    btDefaultCollisionConfiguration configuration_;
    HandReachDispatcher dispatcher_{&configuration_};
    btDbvtBroadphase broadphase_;
    btCollisionWorld world_{&dispatcher_, &broadphase_, &configuration_};
    btCapsuleShapeZ capsule_{kRadius, kLength};
    btBoxShape box_{kHalf};
    btBoxShape floor_{btVector3(0.2f, 0.02f, 0.2f)};
    std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

// Across and through a box's edges and corners, where Bullet's closest-point query read a
// capsule 0.2 mm deep that lay 3 mm in: the pair's depth is its deepest point's.
TEST_F(HandDepenetration, APairsDepthIsItsDeepestPoint) {
    const btTransform box_pose(btQuaternion(btVector3(1, 2, 3).normalized(), 0.7f),
                               btVector3(0.1f, 0.2f, 0.3f));
    btRigidBody& box = add(box_, box_pose, 0.08, BodyRole::Collider);
    btRigidBody& finger = add(capsule_, btTransform::getIdentity(), 0.1, BodyRole::Hand);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(-1, 1);
    int inside = 0;
    for (int i = 0; i < 300; ++i) {
        const btVector3 axis = btVector3(unit(rng), unit(rng), unit(rng)).normalized();
        const btVector3 local(unit(rng) * 0.03f, unit(rng) * 0.03f, unit(rng) * 0.03f);
        finger.setWorldTransform(
            btTransform(btQuaternion(btVector3(0, 0, 1).cross(axis).normalized(),
                                     btAcos(btVector3(0, 0, 1).dot(axis))),
                        box_pose * local));
        const double expected = sampled_depth(finger, box_pose);
        const PairDepth found = pair_depth(world_, finger, box);
        EXPECT_NEAR(found.depth, expected, 2e-5) << "pose " << i;
        inside += expected > 0.0;
    }
    EXPECT_GT(inside, 100);
}

// A finger squeezed into a held cube, its manifold still holding an anchor from before that
// claims 9 mm along an old normal: the finger alone is moved out to the allowed depth, the
// cube stays where it was, and the anchor is put at the pair's deepest point, keeping the
// impulse the solver gave it.
TEST_F(HandDepenetration, APartIsMovedOutAloneAndAnchorsClaimingMoreDepthAreSettled) {
    const btTransform cube_pose(btQuaternion(btVector3(0, 1, 0), 0.3f), btVector3(0, 0.1f, 0));
    btRigidBody& cube = add(box_, cube_pose, 0.08, BodyRole::Collider);
    // Across the cube's +x face, 6 mm in.
    const btTransform in(btQuaternion::getIdentity(),
                         cube_pose * btVector3(kHalf.x() + kRadius - 0.006f, 0, 0));
    btRigidBody& finger = add(capsule_, in, 0.1, BodyRole::Hand);
    world_.performDiscreteCollisionDetection();
    ASSERT_EQ(dispatcher_.getNumManifolds(), 1);
    btPersistentManifold& manifold = *dispatcher_.getManifoldByIndexInternal(0);
    const bool finger_first = manifold.getBody0() == &finger;
    const btVector3 old_normal = cube_pose.getBasis() * btVector3(0, 1, 0);
    const btVector3 on_cube = cube_pose * btVector3(kHalf.x() - 0.002f, kHalf.y(), 0);
    const btVector3 on_finger = on_cube - old_normal * 0.009f;
    btManifoldPoint anchor(
        finger_first ? finger.getWorldTransform().invXform(on_finger) : cube_pose.invXform(on_cube),
        finger_first ? cube_pose.invXform(on_cube) : finger.getWorldTransform().invXform(on_finger),
        finger_first ? old_normal : -old_normal, -0.009f);
    anchor.m_appliedImpulse = 0.05f;  // what the solver pushed with in this substep
    manifold.addManifoldPoint(anchor);
    ASSERT_EQ(manifold.getNumContacts(), 2);

    depenetrate_hands(world_);
    EXPECT_NEAR(sampled_depth(finger, cube_pose), kHandDepthAllowed, 2e-5);
    EXPECT_EQ(cube.getWorldTransform().getOrigin(), cube_pose.getOrigin());
    EXPECT_EQ(cube.getWorldTransform().getRotation(), cube_pose.getRotation());
    EXPECT_EQ(finger.getWorldTransform().getRotation(), in.getRotation());
    ASSERT_EQ(manifold.getNumContacts(), 2);
    float impulse = 0.0f;
    for (int p = 0; p < 2; ++p) {
        const btManifoldPoint& kept = manifold.getContactPoint(p);
        const btVector3 a = manifold.getBody0()->getWorldTransform() * kept.m_localPointA;
        const btVector3 b = manifold.getBody1()->getWorldTransform() * kept.m_localPointB;
        EXPECT_NEAR((a - b).dot(kept.m_normalWorldOnB), -kHandDepthAllowed, 2e-5) << p;
        impulse += kept.m_appliedImpulse;
    }
    EXPECT_EQ(impulse, 0.05f);
}

// Wedged between a cube and the table under it, a finger moved out of the cube's underside
// would go into the table: it is moved out of the table as well, which it may not stay in.
TEST_F(HandDepenetration, APartMovedOutOfAnObjectIsNotLeftInAFixedOne) {
    add(floor_, btTransform(btQuaternion::getIdentity(), btVector3(0, -0.02f, 0)), 0.0,
        BodyRole::Collider);
    const btTransform cube_pose(btQuaternion::getIdentity(), btVector3(0, 0.024f, 0));
    add(box_, cube_pose, 0.08, BodyRole::Collider);
    btRigidBody& finger =
        add(capsule_, btTransform(btQuaternion::getIdentity(), btVector3(0, 0.008f, 0)), 0.1,
            BodyRole::Hand);
    ASSERT_NEAR(sampled_depth(finger, cube_pose), 0.012, 1e-6);
    world_.performDiscreteCollisionDetection();
    depenetrate_hands(world_);
    // The table's top is at y = 0.
    EXPECT_GE(finger.getWorldTransform().getOrigin().y(), kRadius - kHandDepthAllowed - 1e-6);
}

// A part with its contact response off (a hand fading in) is left where it is.
TEST_F(HandDepenetration, APartWithoutContactResponseIsLeftAlone) {
    const btTransform cube_pose(btQuaternion::getIdentity(), btVector3(0, 0.1f, 0));
    add(box_, cube_pose, 0.08, BodyRole::Collider);
    const btTransform in(btQuaternion::getIdentity(), btVector3(0, 0.1f, 0));
    btRigidBody& finger = add(capsule_, in, 0.1, BodyRole::Hand);
    finger.setCollisionFlags(finger.getCollisionFlags() |
                             btCollisionObject::CF_NO_CONTACT_RESPONSE);
    world_.performDiscreteCollisionDetection();
    depenetrate_hands(world_);
    EXPECT_EQ(finger.getWorldTransform().getOrigin(), in.getOrigin());
}

}  // namespace
}  // namespace physhand
