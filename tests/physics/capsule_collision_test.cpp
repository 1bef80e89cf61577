#include "capsule_collision.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <random>

#include "ball_contact.h"

namespace physhand {
namespace {

constexpr btScalar kRadius = 0.008f;
constexpr btScalar kLength = 0.03f;
const btVector3 kHalf(0.05f, 0.02f, 0.03f);

// Distance from `p` to the segment from `a` to `b`.
btScalar to_segment(const btVector3& p, const btVector3& a, const btVector3& b) {
    const btVector3 ab = b - a;
    const btScalar t = btMax(btScalar(0), btMin(btScalar(1), (p - a).dot(ab) / ab.length2()));
    return (p - (a + ab * t)).length();
}

// Capsules in random poses around and through a turned box, in either pair order: the one
// point found each time is the capsule's nearest to the box (or deepest in it) as dense
// sampling of its segment finds it, or an end within kDeeper of that, and joins the box's
// surface to the capsule's.
class CapsuleBoxCollision : public ::testing::TestWithParam<bool> {};

TEST_P(CapsuleBoxCollision, FindsTheSegmentsNearestPointAsDenseSamplingDoes) {
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher(&configuration);
    register_capsule_collision(dispatcher);
    btDbvtBroadphase broadphase;
    btCollisionWorld world(&dispatcher, &broadphase, &configuration);
    btBoxShape box_shape(kHalf);
    btCapsuleShapeZ capsule_shape(kRadius, kLength);
    btCollisionObject box, capsule;
    box.setCollisionShape(&box_shape);
    capsule.setCollisionShape(&capsule_shape);
    const btTransform box_pose(btQuaternion(btVector3(1, 2, 3).normalized(), 0.7f),
                               btVector3(0.1f, 0.2f, 0.3f));
    box.setWorldTransform(box_pose);
    world.addCollisionObject(GetParam() ? &box : &capsule);
    world.addCollisionObject(GetParam() ? &capsule : &box);

    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1, 1);
    int found = 0;
    for (int i = 0; i < 300; ++i) {
        const btVector3 axis = btVector3(unit(rng), unit(rng), unit(rng)).normalized();
        const btVector3 local(unit(rng) * 0.08f, unit(rng) * 0.05f, unit(rng) * 0.06f);
        const btTransform pose(btQuaternion(btVector3(0, 0, 1).cross(axis).normalized(),
                                            btAcos(btVector3(0, 0, 1).dot(axis))),
                               box_pose * local);
        capsule.setWorldTransform(pose);
        for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
            dispatcher.getManifoldByIndexInternal(m)->clearManifold();
        world.performDiscreteCollisionDetection();

        const btVector3 a = pose * btVector3(0, 0, kLength / 2);
        const btVector3 b = pose * btVector3(0, 0, -kLength / 2);
        btScalar least = BT_LARGE_FLOAT;
        for (int s = 0; s <= 4000; ++s) {
            const btVector3 p = a + (b - a) * (btScalar(s) / 4000);
            least = btMin(least, ball_box_contact(p, kRadius, box_pose, kHalf).distance);
        }
        ASSERT_EQ(dispatcher.getNumManifolds(), 1);
        const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(0);
        if (least > manifold.getContactBreakingThreshold()) {
            EXPECT_EQ(manifold.getNumContacts(), 0) << "pose " << i;
            continue;
        }
        ASSERT_EQ(manifold.getNumContacts(), 1) << "pose " << i;
        ++found;
        const btManifoldPoint& point = manifold.getContactPoint(0);
        // Sampling misses a kink of the distance by up to half a sample: 4 µm.
        EXPECT_GE(point.getDistance(), least - 4e-6) << "pose " << i;
        EXPECT_LE(point.getDistance(), least + kDeeper + 1e-6) << "pose " << i;
        const bool capsule_first = manifold.getBody0() == &capsule;
        const btVector3 on_capsule =
            capsule_first ? point.getPositionWorldOnA() : point.getPositionWorldOnB();
        const btVector3 on_box =
            capsule_first ? point.getPositionWorldOnB() : point.getPositionWorldOnA();
        // On the capsule's surface; deep inside, on the ball around the deepest point of the
        // segment, which other points of the segment may be nearer.
        if (point.getDistance() > -kRadius)
            EXPECT_NEAR(to_segment(on_capsule, a, b), kRadius, 1e-5) << "pose " << i;
        else
            EXPECT_LE(to_segment(on_capsule, a, b), kRadius + 1e-5) << "pose " << i;
        const btVector3 in_box = box_pose.invXform(on_box);
        const btVector3 slack = kHalf - in_box.absolute();
        EXPECT_NEAR(btMin(slack.x(), btMin(slack.y(), slack.z())), 0, 1e-5) << "pose " << i;
    }
    EXPECT_GT(found, 100);
}

INSTANTIATE_TEST_SUITE_P(PairOrder, CapsuleBoxCollision, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "BoxFirst" : "CapsuleFirst"; });

}  // namespace
}  // namespace physhand
