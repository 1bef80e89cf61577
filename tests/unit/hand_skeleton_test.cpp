#include "hand_skeleton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace physhand {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kTol = 1e-9;

HandPose flat_right() {
    return pose_hand(HandSide::Right, Pose{}, HandArticulation{});
}

TEST(HandSkeleton, ParentsFollowTheExtensionsTree) {
    EXPECT_FALSE(joint_parent(Joint::Wrist));
    EXPECT_EQ(joint_parent(Joint::Palm), Joint::Wrist);
    EXPECT_EQ(joint_parent(Joint::ThumbMetacarpal), Joint::Wrist);
    EXPECT_EQ(joint_parent(Joint::ThumbTip), Joint::ThumbDistal);
    for (Joint mc : {Joint::IndexMetacarpal, Joint::MiddleMetacarpal, Joint::RingMetacarpal,
                     Joint::LittleMetacarpal}) {
        EXPECT_EQ(joint_parent(mc), Joint::Wrist);
    }
    EXPECT_EQ(joint_parent(Joint::LittleTip), Joint::LittleDistal);
    EXPECT_EQ(joint_parent(Joint::MiddleIntermediate), Joint::MiddleProximal);
    EXPECT_EQ(joint_name(Joint::RingDistal), "ring_distal");
}

TEST(HandSkeleton, FlatHandMatchesTheDocumentedDimensions) {
    const HandPose h = flat_right();
    EXPECT_TRUE(h.active);
    // Middle finger straight along -Z: knuckle at 78 mm, then 45 + 28 + 23 mm.
    EXPECT_NEAR((h[Joint::MiddleProximal].position - Vec3(0, 0, -0.078)).norm(), 0, kTol);
    EXPECT_NEAR((h[Joint::MiddleTip].position - Vec3(0, 0, -0.174)).norm(), 0, kTol);
    // Palm: centre of the middle metacarpal.
    EXPECT_NEAR((h[Joint::Palm].position - Vec3(0, 0, -0.044)).norm(), 0, kTol);
    EXPECT_NEAR(h.radii[index_of(Joint::Wrist)], 0.018, kTol);
    EXPECT_NEAR(h.radii[index_of(Joint::IndexTip)], 0.007, kTol);
    // Thumb on the -X side of a right hand.
    EXPECT_LT(h[Joint::ThumbTip].position.x(), -0.05);
}

TEST(HandSkeleton, JointAxesPointAlongTheBoneAndOutOfTheBackOfTheHand) {
    const HandPose h = flat_right();
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const Joint joint = static_cast<Joint>(j);
        const Quat& q = h.joints[j].orientation;
        EXPECT_NEAR(q.norm(), 1.0, kTol) << joint_name(joint);
        const auto parent = joint_parent(joint);
        if (!parent || *parent == Joint::Wrist || joint == Joint::Palm) continue;
        // The parent's -Z points at this joint.
        const Vec3 bone =
            (h.joints[j].position - (*parent == Joint::Wrist ? Vec3::Zero() : h[*parent].position))
                .normalized();
        const Vec3 forward = h[*parent].orientation * Vec3(0, 0, -1);
        EXPECT_GT(bone.dot(forward), 0.999) << joint_name(joint);
    }
    // Flat hand: every finger joint's +Y is world +Y (back of the hand up).
    EXPECT_NEAR((h[Joint::IndexIntermediate].orientation * Vec3::UnitY() - Vec3::UnitY()).norm(), 0,
                kTol);
}

TEST(HandSkeleton, CurlFlexesTheFingerJointsByTheDocumentedAngles) {
    HandArticulation a;
    a.curl = {0, 1, 0, 0, 0};  // index in a fist, the rest flat
    const HandPose h = pose_hand(HandSide::Right, Pose{}, a);
    const HandPose flat = flat_right();
    auto angle_between = [](const Quat& p, const Quat& c) {
        return Eigen::AngleAxisd(p.conjugate() * c).angle();
    };
    EXPECT_NEAR(
        angle_between(flat[Joint::IndexProximal].orientation, h[Joint::IndexProximal].orientation),
        90 * kDeg, 1e-9);
    EXPECT_NEAR(
        angle_between(h[Joint::IndexProximal].orientation, h[Joint::IndexIntermediate].orientation),
        100 * kDeg, 1e-9);
    EXPECT_NEAR(
        angle_between(h[Joint::IndexIntermediate].orientation, h[Joint::IndexDistal].orientation),
        70 * kDeg, 1e-9);
    // Flexion bends toward the palm (-Y), and the other fingers are untouched.
    EXPECT_LT(h[Joint::IndexIntermediate].position.y(), -0.039);
    EXPECT_NEAR((h[Joint::MiddleTip].position - flat[Joint::MiddleTip].position).norm(), 0, kTol);
    // Proximal phalanx after 90 degrees of MCP flexion points straight down.
    const Vec3 bone = h[Joint::IndexIntermediate].position - h[Joint::IndexProximal].position;
    EXPECT_NEAR(bone.normalized().dot(Vec3(0, -1, 0)), 1.0, 1e-9);
    EXPECT_NEAR(bone.norm(), 0.040, 1e-9);
}

TEST(HandSkeleton, ThumbCurlOpposesTowardThePalm) {
    HandArticulation a;
    a.curl = {1, 0, 0, 0, 0};
    const HandPose h = pose_hand(HandSide::Right, Pose{}, a);
    const HandPose flat = flat_right();
    auto angle = [&](const HandPose& a, Joint ja, const HandPose& b, Joint jb) {
        return Eigen::AngleAxisd(a[ja].orientation.conjugate() * b[jb].orientation).angle();
    };
    // Carpometacarpal: 40 degrees of flexion after 45 of opposition about the hand's axis.
    const Quat oppose(Eigen::AngleAxisd(45 * kDeg, Vec3::UnitZ()));
    EXPECT_NEAR(Eigen::AngleAxisd((oppose * flat[Joint::ThumbMetacarpal].orientation).conjugate() *
                                  h[Joint::ThumbMetacarpal].orientation)
                    .angle(),
                40 * kDeg, 1e-9);
    EXPECT_NEAR(angle(h, Joint::ThumbMetacarpal, h, Joint::ThumbProximal), 50 * kDeg, 1e-9);
    EXPECT_NEAR(angle(h, Joint::ThumbProximal, h, Joint::ThumbDistal), 70 * kDeg, 1e-9);
    EXPECT_GT(h[Joint::ThumbTip].position.x(),
              flat[Joint::ThumbTip].position.x() + 0.05);  // across the palm
}

TEST(HandSkeleton, SpreadFansFingersAboutTheMiddle) {
    HandArticulation fan;
    fan.spread = 1.0;
    HandArticulation together;
    together.spread = -1.0;
    const HandPose f = pose_hand(HandSide::Right, Pose{}, fan);
    const HandPose t = pose_hand(HandSide::Right, Pose{}, together);
    auto direction = [](const HandPose& h, Joint j) { return h[j].orientation * Vec3(0, 0, -1); };
    // Pressed together: parallel to the middle finger; fanned: 15 degrees per finger.
    EXPECT_NEAR(direction(t, Joint::IndexProximal).dot(direction(t, Joint::MiddleProximal)), 1.0,
                1e-9);
    EXPECT_NEAR(
        std::acos(direction(f, Joint::IndexProximal).dot(direction(f, Joint::MiddleProximal))),
        15 * kDeg, 1e-9);
    EXPECT_NEAR(
        std::acos(direction(f, Joint::LittleProximal).dot(direction(f, Joint::MiddleProximal))),
        30 * kDeg, 1e-9);
    EXPECT_LT(direction(f, Joint::IndexProximal).x(), 0);  // toward the thumb
}

TEST(HandSkeleton, LeftHandIsTheMirrorImageWithRightHandedFrames) {
    HandArticulation a;
    a.curl = {0.5, 0.3, 0.6, 0.2, 0.9};
    a.spread = 0.4;
    const HandPose r = pose_hand(HandSide::Right, Pose{}, a);
    const HandPose l = pose_hand(HandSide::Left, Pose{}, a);
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const Vec3 p = r.joints[j].position;
        EXPECT_NEAR((l.joints[j].position - Vec3(-p.x(), p.y(), p.z())).norm(), 0, kTol);
        const Eigen::Matrix3d m = l.joints[j].orientation.toRotationMatrix();
        EXPECT_NEAR(m.determinant(), 1.0, 1e-9);
        // Same -Z and +Y directions as the right hand's, mirrored.
        const Vec3 rz = r.joints[j].orientation * Vec3::UnitZ();
        EXPECT_NEAR((m.col(2) - Vec3(-rz.x(), rz.y(), rz.z())).norm(), 0, 1e-9);
    }
}

TEST(HandSkeleton, WristPoseAndScaleTransformTheWholeHand) {
    const Pose wrist{Vec3(0.1, 1.0, -0.3),
                     Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()))};
    const HandPose local = pose_hand(HandSide::Right, Pose{}, HandArticulation{}, 1.2);
    const HandPose world = pose_hand(HandSide::Right, wrist, HandArticulation{}, 1.2);
    EXPECT_NEAR((local[Joint::MiddleTip].position - Vec3(0, 0, -0.174 * 1.2)).norm(), 0, 1e-9);
    EXPECT_NEAR(local.radii[index_of(Joint::Palm)], 0.016 * 1.2, 1e-12);
    for (std::size_t j = 0; j < kJointCount; ++j) {
        EXPECT_NEAR((world.joints[j].position - wrist * local.joints[j].position).norm(), 0, 1e-9);
    }
}

}  // namespace
}  // namespace physhand
