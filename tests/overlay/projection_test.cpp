#include "projection.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace physhand::overlay {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Normalised device coordinates and depth of a world point.
std::array<float, 3> ndc(const Mat4& m, Vec3 p) {
    std::array<float, 4> clip{};
    for (int row = 0; row < 4; ++row) {
        clip[row] = m[row] * p.x + m[4 + row] * p.y + m[8 + row] * p.z + m[12 + row];
    }
    return {clip[0] / clip[3], clip[1] / clip[3], clip[2] / clip[3]};
}

Eye symmetric(float half_angle) {
    Eye eye;
    eye.angle_left = eye.angle_down = -half_angle;
    eye.angle_right = eye.angle_up = half_angle;
    return eye;
}

TEST(ViewProjection, StraightAheadIsTheCentreWithReversedDepth) {
    const Mat4 m = view_projection(symmetric(kPi / 8));
    const auto [x, y, depth] = ndc(m, {0.0f, 0.0f, -0.5f});
    EXPECT_NEAR(x, 0.0f, 1e-6);
    EXPECT_NEAR(y, 0.0f, 1e-6);
    EXPECT_NEAR(depth, kNearZ / 0.5f, 1e-6);
    EXPECT_GT(depth, ndc(m, {0.0f, 0.0f, -0.6f})[2]) << "nearer is greater";
    EXPECT_NEAR(ndc(m, {0.0f, 0.0f, -kNearZ})[2], 1.0f, 1e-6);
}

TEST(ViewProjection, FieldOfViewEdgesMapToTheImageEdgesWithYDown) {
    const Mat4 m = view_projection(symmetric(kPi / 8));
    const float edge = 0.5f * std::tan(kPi / 8);
    EXPECT_NEAR(ndc(m, {-edge, 0.0f, -0.5f})[0], -1.0f, 1e-5);
    EXPECT_NEAR(ndc(m, {edge, 0.0f, -0.5f})[0], 1.0f, 1e-5);
    EXPECT_NEAR(ndc(m, {0.0f, edge, -0.5f})[1], -1.0f, 1e-5) << "up is the top row";
    EXPECT_NEAR(ndc(m, {0.0f, -edge, -0.5f})[1], 1.0f, 1e-5);
}

TEST(ViewProjection, AsymmetricFrustum) {
    Eye eye;
    eye.angle_left = -0.9f;
    eye.angle_right = 0.7f;
    eye.angle_up = 0.8f;
    eye.angle_down = -0.6f;
    const Mat4 m = view_projection(eye);
    EXPECT_NEAR(ndc(m, {std::tan(-0.9f), 0.0f, -1.0f})[0], -1.0f, 1e-5);
    EXPECT_NEAR(ndc(m, {std::tan(0.7f), 0.0f, -1.0f})[0], 1.0f, 1e-5);
    EXPECT_NEAR(ndc(m, {0.0f, std::tan(0.8f), -1.0f})[1], -1.0f, 1e-5);
    EXPECT_NEAR(ndc(m, {0.0f, std::tan(-0.6f), -1.0f})[1], 1.0f, 1e-5);
}

TEST(ViewProjection, EyePoseMovesAndTurnsTheView) {
    Eye eye = symmetric(kPi / 4);
    eye.position = {1.0f, 2.0f, 3.0f};
    // Turned 90 degrees left about +Y: forward (-Z) becomes -X.
    eye.orientation = {0.0f, std::sin(kPi / 4), 0.0f, std::cos(kPi / 4)};
    const Mat4 m = view_projection(eye);
    const auto ahead = ndc(m, {0.5f, 2.0f, 3.0f});
    EXPECT_NEAR(ahead[0], 0.0f, 1e-5);
    EXPECT_NEAR(ahead[1], 0.0f, 1e-5);
    EXPECT_NEAR(ahead[2], kNearZ / 0.5f, 1e-5);
    // The eye's right (+X) is now world -Z.
    EXPECT_GT(ndc(m, {0.5f, 2.0f, 2.9f})[0], 0.0f);
}

}  // namespace
}  // namespace physhand::overlay
