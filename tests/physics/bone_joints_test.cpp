#include "bone_joints.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <memory>

#include "bullet_convert.h"

namespace physhand {
namespace {

constexpr double kH = 1.0 / 90.0;
constexpr double kBoneLength = 0.04;

// A palm (0.3 kg) and a finger of two bones (0.1 kg each) along -z, as PhysicalHand joins
// them: each bone's centre halfway along it.
class BoneJoints : public ::testing::Test {
  protected:
    BoneJoints() {
        palm_ = make(0.3, Vec3(0, 0, 0));
        first_ = make(0.1, Vec3(0, 0, -0.05 - kBoneLength / 2));
        second_ = make(0.1, Vec3(0, 0, -0.05 - 1.5 * kBoneLength));
        const Vec3 start(0, 0, kBoneLength / 2);
        joints_.push_back({palm_.get(), first_.get(), Vec3(0, 0, -0.05), start, -start, {}});
        joints_.push_back({first_.get(), second_.get(), -start, start, -start, start});
    }

    std::unique_ptr<btRigidBody> make(double mass, const Vec3& at) {
        shapes_.push_back(std::make_unique<btCapsuleShapeZ>(0.008f, float(kBoneLength)));
        auto body =
            std::make_unique<btRigidBody>(static_cast<btScalar>(mass), nullptr,
                                          shapes_.back().get(), btVector3(1e-4f, 1e-4f, 1e-4f));
        body->setWorldTransform(to_bt(Pose{at, Quat::Identity()}));
        return body;
    }

    static Vec3 position(const btRigidBody& b) {
        return from_bt(b.getWorldTransform().getOrigin());
    }

    double largest_gap() const {
        double gap = 0.0;
        for (const BoneJoint& j : joints_) {
            const Vec3 end = from_bt(j.parent->getWorldTransform()) * j.end_in_parent;
            const Vec3 start = from_bt(j.child->getWorldTransform()) * j.start_in_child;
            gap = std::max(gap, (end - start).norm());
        }
        return gap;
    }

    std::vector<std::unique_ptr<btCollisionShape>> shapes_;
    std::unique_ptr<btRigidBody> palm_, first_, second_;
    std::vector<BoneJoint> joints_;
};

TEST_F(BoneJoints, AJoinedHandIsLeftAsItWas) {
    close_joint_gaps(joints_, kH);
    EXPECT_LT((position(*palm_)).norm(), 1e-9);
    EXPECT_LT(from_bt(second_->getLinearVelocity()).norm(), 1e-9);
}

// The tip bone held 1 cm away (a fingertip caught while the hand moved on): the gaps close,
// the tip bone turns about its far end rather than leaving it, and every body takes up the
// move as velocity, as an impulse would give it.
TEST_F(BoneJoints, AGapClosesWithEachSideMovingByItsShare) {
    const Vec3 away(0.01, 0, 0);
    const Vec3 tip_end = position(*second_) + Vec3(0, 0, -kBoneLength / 2) + away;
    second_->setWorldTransform(to_bt(Pose{position(*second_) + away, Quat::Identity()}));
    close_joint_gaps(joints_, kH);
    EXPECT_LT(largest_gap(), 0.0003 + 1e-6);  // the joint's give
    // The tip bent toward the finger: its far end stayed where it was caught.
    const Vec3 far = from_bt(second_->getWorldTransform()) * Vec3(0, 0, -kBoneLength / 2);
    EXPECT_LT((far - tip_end).norm(), 0.003);
    // The finger bent to meet its tip; the palm, three times a bone's mass, barely moved.
    const double first_moved = (position(*first_) - Vec3(0, 0, -0.05 - kBoneLength / 2)).norm();
    EXPECT_GT(first_moved, 0.001);
    EXPECT_LT(position(*palm_).norm(), 0.1 * first_moved);
    EXPECT_LT((from_bt(palm_->getLinearVelocity()) - position(*palm_) / kH).norm(), 1e-5);
    EXPECT_GT(from_bt(first_->getAngularVelocity()).norm(), 0.1);
}

}  // namespace
}  // namespace physhand
