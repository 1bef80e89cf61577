#include "bone_joints.h"

#include <btBulletDynamicsCommon.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

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
        joints_.push_back(joint(*palm_, *first_, Vec3(0, 0, -0.05), std::nullopt));
        joints_.push_back(joint(*first_, *second_, -start, start));
    }

    // A bone joined at its start, turning about its far end.
    static BoneJoint joint(btRigidBody& parent, btRigidBody& child, const Vec3& end_in_parent,
                           const std::optional<Vec3>& parent_start) {
        BoneJoint j;
        j.parent = &parent;
        j.child = &child;
        j.end_in_parent = end_in_parent;
        j.start_in_child = Vec3(0, 0, kBoneLength / 2);
        j.far_in_child = -j.start_in_child;
        j.parent_start = parent_start;
        return j;
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

// The tip bone pulled 1 cm along the finger: turning about its start, the first bone cannot
// reach it, so it slides, which opens its joint with the palm, already found closed in that
// sweep. The sweeps after it close that joint again.
TEST_F(BoneJoints, AJointOpenedByTheNextOneIsClosedAgain) {
    second_->setWorldTransform(
        to_bt(Pose{position(*second_) + Vec3(0, 0, -0.01), Quat::Identity()}));
    close_joint_gaps(joints_, kH);
    EXPECT_LT(largest_gap(), 0.0003 + 1e-6);   // the joint's give
    EXPECT_GT(position(*palm_).norm(), 1e-4);  // the palm took its share of the pull
}

// Flexion, abduction and twist (radians) of a turn, as JointRange measures them.
Vec3 bend_of(const Quat& turn) {
    const Vec3 tip = turn * Vec3(0, 0, -1);
    return Vec3(std::atan2(-tip.y(), -tip.z()), std::asin(tip.x()),
                2.0 * std::atan2(turn.z(), turn.w()));
}

Quat flexed(double flexion) {
    return Quat(Eigen::AngleAxisd(-flexion, Vec3::UnitX()));
}

const JointRange kRange(-0.2, 1.5, 0.3, 0.25);

TEST(JointRanges, ATurnWithinItsRangeIsLeftAsItIs) {
    EXPECT_FALSE(kRange.bring_within(flexed(1.2)));
    EXPECT_FALSE(kRange.bring_within(Quat(Eigen::AngleAxisd(0.25, Vec3::UnitY())) * flexed(0.5) *
                                     Quat(Eigen::AngleAxisd(-0.2, Vec3::UnitZ()))));
}

// A turn of given flexion, abduction and twist, as JointRange measures them.
Quat bent_by(double flexion, double abduction, double twist) {
    const Vec3 tip(std::sin(abduction), -std::sin(flexion) * std::cos(abduction),
                   -std::cos(flexion) * std::cos(abduction));
    return Quat::FromTwoVectors(Vec3(0, 0, -1), tip) *
           Quat(Eigen::AngleAxisd(twist, Vec3::UnitZ()));
}

// Whether a turn lies within is told without trigonometry: on either side of every limit
// (0.01 rad away), the quick test agrees with the measures.
TEST(JointRanges, EveryTurnIsToldWithinOrPastItsRange) {
    const double off = 0.01;
    for (double f : {-0.2 - off, -0.2 + off, 0.7, 1.5 - off, 1.5 + off, -2.5, 3.0}) {
        for (double a : {-0.3 - off, -0.3 + off, 0.0, 0.3 - off, 0.3 + off}) {
            for (double t : {-0.25 - off, -0.25 + off, 0.0, 0.25 - off, 0.25 + off}) {
                const bool within =
                    f >= -0.2 && f <= 1.5 && std::abs(a) <= 0.3 && std::abs(t) <= 0.25;
                EXPECT_EQ(!kRange.bring_within(bent_by(f, a, t)), within)
                    << f << " " << a << " " << t;
            }
        }
    }
}

TEST(JointRanges, ATurnPastItsRangeIsBroughtToItsEdge) {
    const std::optional<Quat> back = kRange.bring_within(flexed(-0.9));
    ASSERT_TRUE(back);
    EXPECT_NEAR(bend_of(*back).x(), -0.2, 1e-6);
    EXPECT_NEAR(bend_of(*back).y(), 0.0, 1e-6);

    // Bent past every limit at once: each of the three is brought to its edge.
    const Quat bent = bent_by(1.7, -0.5, 0.4);
    const Vec3 was = bend_of(bent);
    ASSERT_GT(was.x(), kRange.most_flexion());
    ASSERT_GT(std::abs(was.y()), kRange.abduction());
    ASSERT_GT(std::abs(was.z()), kRange.twist());
    const std::optional<Quat> within = kRange.bring_within(bent);
    ASSERT_TRUE(within);
    const Vec3 now = bend_of(*within);
    EXPECT_NEAR(now.x(), kRange.most_flexion(), 1e-6);
    EXPECT_NEAR(now.y(), std::copysign(kRange.abduction(), was.y()), 1e-6);
    EXPECT_NEAR(now.z(), std::copysign(kRange.twist(), was.z()), 1e-6);
}

// The tip bone bent 60 degrees back (pressed on what it touches): it turns back to the edge of
// its range about the joint, which stays closed, and takes up the turn as velocity.
TEST_F(BoneJoints, ABoneBentPastItsRangeTurnsBackAboutItsJoint) {
    joints_[1].range = kRange;
    const Vec3 joint(0, 0, -0.05 - kBoneLength);
    const Quat back = flexed(-60.0 * std::numbers::pi / 180.0);
    second_->setWorldTransform(to_bt(Pose{joint + back * Vec3(0, 0, -kBoneLength / 2), back}));
    close_joint_gaps(joints_, kH);
    const Quat first = from_bt(first_->getWorldTransform()).orientation;
    const Quat second = from_bt(second_->getWorldTransform()).orientation;
    EXPECT_NEAR(bend_of(first.inverse() * second).x(), kRange.least_flexion(), 2e-3);
    EXPECT_LT(largest_gap(), 0.0003 + 1e-6);
    EXPECT_LT(from_bt(second_->getAngularVelocity()).x(), -1.0);  // turning toward the palm
    EXPECT_LT(from_bt(first_->getAngularVelocity()).norm(), 1e-9);
}

// The tip bone stopped 1 cm short (a fingertip held by what it squeezes): the finger bends to
// meet it and it stays all but where the contact put it. (Turning cannot bring the first
// bone's end all the way, so that bone slides as well, opening its joint with the palm; the
// sweeps after the held ones close what is left by every body's share.)
TEST_F(BoneJoints, ASqueezingBoneStaysAndTheBoneBeforeItTakesTheGap) {
    const Vec3 away(0.01, 0, 0);
    const Pose caught{position(*second_) + away, Quat::Identity()};
    second_->setWorldTransform(to_bt(caught));
    close_joint_gaps(joints_, kH, {second_.get()});
    EXPECT_LT(largest_gap(), 0.0003 + 1e-6);
    EXPECT_LT((position(*second_) - caught.position).norm(), 1e-4);
    EXPECT_GT((position(*first_) - Vec3(0, 0, -0.05 - kBoneLength / 2)).norm(), 0.004);

    // Not squeezing, it comes halfway to meet the finger.
    second_->setWorldTransform(to_bt(caught));
    first_->setWorldTransform(to_bt(Pose{Vec3(0, 0, -0.05 - kBoneLength / 2), Quat::Identity()}));
    palm_->setWorldTransform(to_bt(Pose{}));
    close_joint_gaps(joints_, kH);
    EXPECT_GT((position(*second_) - caught.position).norm(), 0.002);
}

// Pulled 1 cm along the finger while it squeezes, with the palm held fixed: the bone before it
// cannot reach it, so the later sweeps move it too, and it takes none of that move as velocity.
// Kept as velocity, the move drove a squeezing bone on into what it held every substep, the
// joint pulling it one way and the contact the other, and spun the cube out of the grip.
TEST_F(BoneJoints, ASqueezingBoneMovedByItsJointKeepsItsVelocity) {
    palm_ = make(0.0, Vec3::Zero());
    joints_[0].parent = palm_.get();
    const Vec3 velocity(0.0, 0.05, 0.0);
    const Pose caught{position(*second_) + Vec3(0, 0, -0.01), Quat::Identity()};
    second_->setWorldTransform(to_bt(caught));
    second_->setLinearVelocity(to_bt(velocity));
    close_joint_gaps(joints_, kH, {second_.get()});
    EXPECT_LT(largest_gap(), 0.0003 + 1e-6);
    EXPECT_GT((position(*second_) - caught.position).norm(), 0.002);
    EXPECT_LT((from_bt(second_->getLinearVelocity()) - velocity).norm(), 1e-9);
    EXPECT_LT(from_bt(second_->getAngularVelocity()).norm(), 1e-9);

    // Not squeezing, it takes the move as velocity.
    second_->setWorldTransform(to_bt(caught));
    second_->setLinearVelocity(to_bt(velocity));
    first_->setWorldTransform(to_bt(Pose{Vec3(0, 0, -0.05 - kBoneLength / 2), Quat::Identity()}));
    close_joint_gaps(joints_, kH);
    EXPECT_GT((from_bt(second_->getLinearVelocity()) - velocity).norm(), 0.1);
}

// Bent 30 degrees back while it squeezes: the bone before it turns instead, so the joint comes
// back within its range with the squeezing bone all but where it was.
TEST_F(BoneJoints, ASqueezingBonePastItsRangeTurnsTheBoneBeforeIt) {
    joints_[1].range = kRange;
    const Vec3 joint(0, 0, -0.05 - kBoneLength);
    const Quat back = flexed(-30.0 * std::numbers::pi / 180.0);
    const Pose bent{joint + back * Vec3(0, 0, -kBoneLength / 2), back};
    second_->setWorldTransform(to_bt(bent));
    close_joint_gaps(joints_, kH, {second_.get()});
    const Quat first = from_bt(first_->getWorldTransform()).orientation;
    const Quat second = from_bt(second_->getWorldTransform()).orientation;
    EXPECT_GT(bend_of(first.inverse() * second).x(), kRange.least_flexion() - 2e-3);
    EXPECT_LT(largest_gap(), 0.0003 + 1e-6);
    EXPECT_LT((position(*second_) - bent.position).norm(), 1e-3);
    EXPECT_GT(from_bt(first_->getAngularVelocity()).norm(), 1.0);
}

}  // namespace
}  // namespace physhand
