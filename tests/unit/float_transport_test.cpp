#include "float_transport.h"

#include <gtest/gtest.h>

namespace physhand {
namespace {

double as_float(double v) {
    return static_cast<double>(static_cast<float>(v));
}

TEST(FloatTransport, RoundsEveryComponentAsOpenXrFloatsWould) {
    const HandPose hand = pose_hand(HandSide::Right,
                                    Pose{Vec3(0.1222, 1.0001, -0.2003),
                                         Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()))},
                                    HandArticulation{});
    const HandPose r = round_to_float(hand);
    for (std::size_t j = 0; j < kJointCount; ++j) {
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(r.joints[j].position[i], as_float(hand.joints[j].position[i]));
            EXPECT_NE(r.joints[j].position[i], hand.joints[j].position[i]);  // really rounded
        }
        for (int i = 0; i < 4; ++i) {
            EXPECT_EQ(r.joints[j].orientation.coeffs()[i],
                      as_float(hand.joints[j].orientation.coeffs()[i]));
        }
        EXPECT_EQ(r.radii[j], as_float(hand.radii[j]));
    }
}

TEST(FloatTransport, RoundsColliderSizesPosesAndMaterials) {
    Collider c;
    c.shape.half_extents = Vec3(0.0123456789, 0.1, 0.3);
    c.shape.vertices = {Vec3(0.1, 0.2, 0.3)};
    c.mass = 0.08;
    c.friction = 0.9;
    c.pose.position = Vec3(0.1, 0.77, -0.4);
    c.path = {{1.0, Pose{Vec3(0.3, 0.1, 0.7), Quat::Identity()}}};
    const Collider r = round_to_float(c);
    EXPECT_EQ(r.shape.half_extents.x(), as_float(0.0123456789));
    EXPECT_EQ(r.shape.vertices[0].y(), as_float(0.2));
    EXPECT_EQ(r.mass, as_float(0.08));
    EXPECT_EQ(r.friction, as_float(0.9));
    EXPECT_EQ(r.pose.position.y(), as_float(0.77));
    EXPECT_EQ(r.path[0].pose.position.x(), as_float(0.3));
    EXPECT_EQ(r.path[0].t, 1.0);  // times are not transported as floats
}

}  // namespace
}  // namespace physhand
