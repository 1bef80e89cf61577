#include "hand_point_contacts.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "capsule_collision.h"
#include "hand_reach_dispatcher.h"
#include "world.h"

namespace physhand {
namespace {

constexpr btScalar kRadius = 0.008f;
constexpr btScalar kLength = 0.03f;      // between the capsule's end centres
constexpr btScalar kTop = 0.1f;          // every collider's top surface, y
constexpr btScalar kBoxMargin = 0.001f;  // as colliders have: rounds the box's edges

enum class Kind { Box, Plane, Hull };

// One hand part (a finger capsule unless a test sets another shape) and one static
// collider whose top is the plane y = kTop (the box and hull reach 0.1 m either side of
// x = 0), in either order in Bullet's pair, found as World finds them.
class EndContacts : public ::testing::TestWithParam<std::tuple<Kind, bool>> {
  protected:
    void SetUp() override {
        register_capsule_collision(dispatcher_);
        switch (std::get<0>(GetParam())) {
            case Kind::Box:
                collider_shape_ = std::make_unique<btBoxShape>(btVector3(0.1f, kTop, 0.1f));
                collider_shape_->setMargin(kBoxMargin);
                break;
            case Kind::Plane:
                collider_shape_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), kTop);
                break;
            case Kind::Hull: {
                // Bullet grows a hull by its margin: vertices 1 mm inside the surface.
                const btScalar h = 0.1f - 0.001f;
                auto hull = std::make_unique<btConvexHullShape>();
                for (int i = 0; i < 8; ++i) {
                    hull->addPoint(btVector3(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h));
                }
                hull->setMargin(0.001f);
                collider_shape_ = std::move(hull);
                break;
            }
        }
        collider_.setCollisionShape(collider_shape_.get());
        collider_.setUserIndex(static_cast<int>(BodyRole::Collider));
        finger_.setCollisionShape(hand_shape());
        finger_.setUserIndex(static_cast<int>(BodyRole::Hand));
        if (std::get<1>(GetParam())) {
            world_.addCollisionObject(&finger_);
            world_.addCollisionObject(&collider_);
        } else {
            world_.addCollisionObject(&collider_);
            world_.addCollisionObject(&finger_);
        }
    }
    virtual btCollisionShape* hand_shape() { return &capsule_; }
    void TearDown() override {
        world_.removeCollisionObject(&finger_);
        world_.removeCollisionObject(&collider_);
    }

    // Places the capsule's centre at `centre`, its axis along `axis`, and returns the
    // distances of the contact points Bullet and then add_hand_point_contacts found.
    std::vector<btScalar> contacts(const btVector3& centre, const btVector3& axis) {
        finger_.setWorldTransform(
            btTransform(btQuaternion(btVector3(0, 0, 1).cross(axis.normalized()),
                                     btAcos(btVector3(0, 0, 1).dot(axis.normalized()))),
                        centre));
        world_.performDiscreteCollisionDetection();
        add_hand_point_contacts(dispatcher_);
        std::vector<btScalar> d;
        for (int i = 0; i < dispatcher_.getNumManifolds(); ++i) {
            const btPersistentManifold* m = dispatcher_.getManifoldByIndexInternal(i);
            for (int p = 0; p < m->getNumContacts(); ++p) {
                d.push_back(m->getContactPoint(p).getDistance());
            }
        }
        std::sort(d.begin(), d.end());
        return d;
    }

    btDefaultCollisionConfiguration configuration_;
    HandReachDispatcher dispatcher_{&configuration_};  // as World has
    btDbvtBroadphase broadphase_;
    btCollisionWorld world_{&dispatcher_, &broadphase_, &configuration_};
    std::unique_ptr<btCollisionShape> collider_shape_;
    btCapsuleShapeZ capsule_{kRadius, kLength};
    btCollisionObject collider_;
    btCollisionObject finger_;
};

// A finger coming down tilted: one end 1 mm above the surface, the other 6 mm. Bullet alone
// holds only the lower end, so the upper one would land unopposed.
TEST_P(EndContacts, ATiltedFingerHasAContactAtEachEnd) {
    const btScalar rise = 0.005f;
    const btVector3 axis(std::sqrt(kLength * kLength - rise * rise), rise, 0);
    const btVector3 centre(0, kTop + kRadius + 0.001f + rise / 2, 0);
    const std::vector<btScalar> d = contacts(centre, axis);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_NEAR(d[0], 0.001, 1e-5);
    EXPECT_NEAR(d[1], 0.006, 1e-5);
}

// A finger lying flat 0.5 mm into the surface: a point at each end (and Bullet's own where
// it finds it), none added again however often the contacts are found.
TEST_P(EndContacts, AFingerLyingFlatKeepsOnePointAtEachEnd) {
    const btVector3 centre(0, kTop + kRadius - 0.0005f, 0);
    const std::size_t first = contacts(centre, btVector3(1, 0, 0)).size();
    EXPECT_GE(first, 2u);
    EXPECT_LE(first, 3u);
    for (int frame = 0; frame < 3; ++frame) {
        const std::vector<btScalar> d = contacts(centre, btVector3(1, 0, 0));
        ASSERT_EQ(d.size(), first);
        for (btScalar x : d) EXPECT_NEAR(x, -0.0005, 1e-5);
    }
}

// A finger across the box's edge at 45°, its middle 2 mm over the sharp edge and both ends
// clear. The middle's contact stays beside the ends'.
class EdgeContacts : public EndContacts {};

TEST_P(EdgeContacts, AFingerAcrossAnEdgeKeepsTheEdgeContact) {
    const btScalar over = 0.002f;
    const btVector3 out = btVector3(1, 1, 0).normalized();
    const btVector3 centre = btVector3(0.1f, kTop, 0) + out * (kRadius - over);
    const std::vector<btScalar> d = contacts(centre, btVector3(1, -1, 0));
    ASSERT_EQ(d.size(), 3u);
    EXPECT_NEAR(d[0], -over, 1e-5);
    EXPECT_GT(d[1], 0.0);
}

// A palm-sized box coming down tilted about z, its lowest edge 1 mm above the surface.
// Bullet finds no point between two boxes that do not overlap, and one between a box and a
// plane or hull.
class CornerContacts : public EndContacts {
  protected:
    btCollisionShape* hand_shape() override {
        palm_.setMargin(kBoxMargin);
        return &palm_;
    }
    btBoxShape palm_{btVector3(0.04f, 0.006f, 0.04f)};
};

TEST_P(CornerContacts, ATiltedPalmHasAContactAtEachOfItsFourLowestCorners) {
    const btQuaternion tilt(btVector3(0, 0, 1), 0.1f);
    const btVector3 half = palm_.getHalfExtentsWithMargin();
    auto height = [&](btScalar x) {  // of the bottom corners at side x, the centre at 0
        return quatRotate(tilt, btVector3(x * half.x(), -half.y(), 0)).y();
    };
    const btScalar low = std::min(height(-1), height(1));
    const btScalar high = std::max(height(-1), height(1));
    finger_.setWorldTransform(btTransform(tilt, btVector3(0, kTop + 0.001f - low, 0)));
    world_.performDiscreteCollisionDetection();
    add_hand_point_contacts(dispatcher_);
    std::vector<btScalar> d;
    for (int i = 0; i < dispatcher_.getNumManifolds(); ++i) {
        const btPersistentManifold* m = dispatcher_.getManifoldByIndexInternal(i);
        for (int p = 0; p < m->getNumContacts(); ++p)
            d.push_back(m->getContactPoint(p).getDistance());
    }
    std::sort(d.begin(), d.end());
    ASSERT_EQ(d.size(), 4u);
    EXPECT_NEAR(d[0], 0.001, 1e-5);
    EXPECT_NEAR(d[1], 0.001, 1e-5);
    EXPECT_NEAR(d[2], 0.001 + high - low, 1e-5);
    EXPECT_NEAR(d[3], 0.001 + high - low, 1e-5);
}

std::string name(const ::testing::TestParamInfo<std::tuple<Kind, bool>>& info) {
    static const char* const kinds[] = {"Box", "Plane", "Hull"};
    return std::string(kinds[static_cast<int>(std::get<0>(info.param))]) +
           (std::get<1>(info.param) ? "HandFirst" : "ColliderFirst");
}

INSTANTIATE_TEST_SUITE_P(Colliders, EndContacts,
                         ::testing::Combine(::testing::Values(Kind::Box, Kind::Plane, Kind::Hull),
                                            ::testing::Bool()),
                         name);
INSTANTIATE_TEST_SUITE_P(Colliders, CornerContacts,
                         ::testing::Combine(::testing::Values(Kind::Box, Kind::Plane, Kind::Hull),
                                            ::testing::Bool()),
                         name);
INSTANTIATE_TEST_SUITE_P(Box, EdgeContacts,
                         ::testing::Combine(::testing::Values(Kind::Box), ::testing::Bool()), name);

}  // namespace
}  // namespace physhand
