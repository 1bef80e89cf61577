#include "box_face_collision.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <set>
#include <utility>

namespace physhand {
namespace {

constexpr btScalar kMargin = 0.001f;
const btVector3 kHalf(0.3f, 0.02f, 0.2f);  // a table top
constexpr btScalar kRodHalfLength = 0.25f;
constexpr btScalar kRodRadius = 0.05f;

// A turned box and one convex object near its top face, collided in either pair order.
class BoxFace : public ::testing::TestWithParam<bool> {
  protected:
    BoxFace() {
        register_box_face_collision(dispatcher_);
        box_.setCollisionShape(&box_shape_);
        box_.setWorldTransform(box_pose_);
        rod_shape_.setMargin(kMargin);
    }

    // The manifold after placing `convex` at `pose` (box frame).
    const btPersistentManifold& collide(btCollisionShape& shape, const btTransform& pose) {
        convex_.setCollisionShape(&shape);
        convex_.setWorldTransform(box_pose_ * pose);
        box_.setWorldTransform(box_pose_);
        if (world_.getNumCollisionObjects() == 0) {
            world_.addCollisionObject(GetParam() ? &box_ : &convex_);
            world_.addCollisionObject(GetParam() ? &convex_ : &box_);
        }
        world_.performDiscreteCollisionDetection();
        EXPECT_EQ(dispatcher_.getNumManifolds(), 1);
        return *dispatcher_.getManifoldByIndexInternal(0);
    }

    // Where a point of `manifold` lies on the box and on the convex, box frame.
    btVector3 on_box(const btPersistentManifold& m, const btManifoldPoint& p) const {
        return box_pose_.invXform(m.getBody0() == &box_ ? p.getPositionWorldOnA()
                                                        : p.getPositionWorldOnB());
    }
    btVector3 on_convex(const btPersistentManifold& m, const btManifoldPoint& p) const {
        return box_pose_.invXform(m.getBody0() == &box_ ? p.getPositionWorldOnB()
                                                        : p.getPositionWorldOnA());
    }
    // The point's normal, out of the box, box frame.
    btVector3 out_of_box(const btPersistentManifold& m, const btManifoldPoint& p) const {
        return box_pose_.getBasis().transpose() *
               (m.getBody0() == &box_ ? -p.m_normalWorldOnB : p.m_normalWorldOnB);
    }

    btTransform box_pose_{btQuaternion(btVector3(1, 2, 3).normalized(), 0.4f),
                          btVector3(0.1f, 0.75f, -0.2f)};
    btCylinderShapeX rod_shape_{btVector3(kRodHalfLength, kRodRadius, kRodRadius)};

  private:
    btDefaultCollisionConfiguration configuration_;
    btCollisionDispatcher dispatcher_{&configuration_};
    btDbvtBroadphase broadphase_;
    btCollisionWorld world_{&dispatcher_, &broadphase_, &configuration_};
    btBoxShape box_shape_{kHalf};
    btCollisionObject box_, convex_;
};

// A rod lying along the face, 0.5 mm into it: it rests on both ends of its lowest line, each
// point as deep as the rod lies, on the face, with the face's normal.
TEST_P(BoxFace, ARodLyingOnAFaceRestsOnBothEndsOfItsLowestLine) {
    const btScalar depth = 0.0005f;
    const btTransform pose(btQuaternion::getIdentity(),
                           btVector3(0.02f, kHalf.y() + kRodRadius - depth, 0.03f));
    const btPersistentManifold& m = collide(rod_shape_, pose);
    ASSERT_GE(m.getNumContacts(), 2);
    btScalar least_x = BT_LARGE_FLOAT, most_x = -BT_LARGE_FLOAT;
    for (int i = 0; i < m.getNumContacts(); ++i) {
        const btManifoldPoint& p = m.getContactPoint(i);
        EXPECT_NEAR(p.getDistance(), -depth, 2e-6);
        EXPECT_NEAR(on_box(m, p).y(), kHalf.y(), 2e-6);
        EXPECT_NEAR(on_convex(m, p).z(), 0.03f, 0.0006f);  // the tilt's reach
        EXPECT_NEAR(out_of_box(m, p).y(), 1.0, 1e-6);
        least_x = btMin(least_x, on_convex(m, p).x());
        most_x = btMax(most_x, on_convex(m, p).x());
    }
    // Its flat ends are rounded by the margin.
    EXPECT_NEAR(least_x, 0.02f - (kRodHalfLength - kMargin), 1e-5);
    EXPECT_NEAR(most_x, 0.02f + (kRodHalfLength - kMargin), 1e-5);
}

// A brick-shaped hull on its face rests on the four corners of that face, on a turned box and
// on one square with the world (where a brick square on it tied at its corners).
TEST_P(BoxFace, AHullOnAFaceRestsOnTheCornersOfItsLowestFace) {
    btConvexHullShape brick;
    for (const btScalar x : {-0.04f, 0.04f}) {
        for (const btScalar y : {-0.01f, 0.01f}) {
            for (const btScalar z : {-0.02f, 0.02f}) brick.addPoint(btVector3(x, y, z));
        }
    }
    brick.setMargin(kMargin);
    const btScalar depth = 0.0003f;
    const btTransform pose(btQuaternion::getIdentity(),
                           btVector3(-0.1f, kHalf.y() + 0.01f + kMargin - depth, 0.05f));
    for (const btTransform& box_pose : {box_pose_, btTransform::getIdentity()}) {
        box_pose_ = box_pose;
        const btPersistentManifold& m = collide(brick, pose);
        ASSERT_EQ(m.getNumContacts(), 4);
        std::set<std::pair<bool, bool>> corners;
        for (int i = 0; i < m.getNumContacts(); ++i) {
            const btManifoldPoint& p = m.getContactPoint(i);
            EXPECT_NEAR(p.getDistance(), -depth, 2e-6);
            // The hull collides its margin outside its points: its lowest face is the face of
            // its points, moved down by the margin.
            const btVector3 corner = on_convex(m, p);
            EXPECT_NEAR(btFabs(corner.x() + 0.1f), 0.04f, 1e-5);
            EXPECT_NEAR(btFabs(corner.z() - 0.05f), 0.02f, 1e-5);
            corners.insert({corner.x() > -0.1f, corner.z() > 0.05f});
        }
        EXPECT_EQ(corners.size(), 4u);
    }
}

// Over the face's edge the face alone does not say where the rod touches: GJK finds it.
TEST_P(BoxFace, ARodOverTheEdgeIsStillFoundTouching) {
    const btScalar depth = 0.0005f;
    const btTransform pose(btQuaternion::getIdentity(),
                           btVector3(kHalf.x(), kHalf.y() + kRodRadius - depth, 0.0f));
    const btPersistentManifold& m = collide(rod_shape_, pose);
    ASSERT_GE(m.getNumContacts(), 1);
    for (int i = 0; i < m.getNumContacts(); ++i)
        EXPECT_NEAR(m.getContactPoint(i).getDistance(), -depth, 0.001);
}

TEST_P(BoxFace, ARodAboveTheFaceTouchesNothing) {
    const btTransform pose(btQuaternion::getIdentity(),
                           btVector3(0.0f, kHalf.y() + kRodRadius + 0.05f, 0.0f));
    EXPECT_EQ(collide(rod_shape_, pose).getNumContacts(), 0);
}

INSTANTIATE_TEST_SUITE_P(EitherOrder, BoxFace, ::testing::Bool());

}  // namespace
}  // namespace physhand
