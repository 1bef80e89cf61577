#include "tracking_gap.h"

#include <gtest/gtest.h>

#include <cmath>

#include "../physics/test_scenes.h"

namespace physhand {
namespace {

using testing::right_hand;

// Distance between thumb and index tips: the grip's shape.
double pinch_width(const HandPose& hand) {
    return (hand[Joint::ThumbTip].position - hand[Joint::IndexTip].position).norm();
}

TEST(TrackingGap, ALostHandGoesOnAsItMovedAndComesToRest) {
    const HandPose last = right_hand(Vec3(0.1, 0.9, -0.3), 0.4);
    const Vec3 velocity(0, 0.2, 0);
    const double y0 = last[Joint::Wrist].position.y();
    EXPECT_NEAR(TrackingGap::predict(last, velocity, 0.0)[Joint::Wrist].position.y(), y0, 1e-12);
    const HandPose later = TrackingGap::predict(last, velocity, 0.3);
    EXPECT_NEAR(later[Joint::Wrist].position.y() - y0, 0.2 * 0.15 * (1 - std::exp(-2.0)), 1e-9);
    // However long it is lost, it never travels further than its momentum carries it.
    EXPECT_LE(TrackingGap::predict(last, velocity, 100.0)[Joint::Wrist].position.y() - y0,
              0.2 * 0.15 + 1e-12);
    EXPECT_NEAR(pinch_width(later), pinch_width(last), 1e-9);
}

TEST(TrackingGap, AGhostBackElsewhereIsReachedWithBoundedAcceleration) {
    const HandPose sample = right_hand(Vec3(0.1, 0.9, -0.3), 0.4);
    const HandPose predicted = right_hand(Vec3(0.1, 0.94, -0.29), 0.4);
    TrackingGap gap;
    gap.reacquire(predicted, sample);
    const double dt = 1.0 / 90.0;
    std::vector<double> y;
    for (int f = 0; f < 150; ++f) {
        const HandPose out = gap.correct(sample, dt);
        EXPECT_NEAR(pinch_width(out), pinch_width(sample), 1e-9);
        y.push_back(out[Joint::Wrist].position.y());
    }
    // The first frame is still where the hand was predicted, not at the ghost.
    EXPECT_GT(y.front() - sample[Joint::Wrist].position.y(), 0.035);
    // The velocity starts at zero and the acceleration stays under 3 m/s^2 (with the
    // discretisation's share): a held object feels no jolt.
    EXPECT_LT(std::abs(y[1] - y[0]) / dt, 3.0 * 2 * dt + 1e-6);
    for (std::size_t i = 2; i < y.size(); ++i)
        EXPECT_LT(std::abs(y[i] - 2 * y[i - 1] + y[i - 2]) / (dt * dt), 3.0 * 1.05);
    // The correction is over within its duration, sqrt(5.77 x0 / 3 m/s^2) (0.28 s for these
    // 4 cm), and the sample passes exactly from then on.
    EXPECT_EQ(y[static_cast<std::size_t>(std::ceil(0.28 / dt))], sample[Joint::Wrist].position.y());
    EXPECT_EQ(y.back(), sample[Joint::Wrist].position.y());
}

TEST(TrackingGap, WithoutAReacquisitionTheSamplePassesUnchanged) {
    const HandPose sample = right_hand(Vec3(0.1, 0.9, -0.3), 0.4);
    TrackingGap gap;
    const HandPose out = gap.correct(sample, 1.0 / 90.0);
    for (std::size_t j = 0; j < kJointCount; ++j)
        EXPECT_EQ(out.joints[j].position, sample.joints[j].position);
}

}  // namespace
}  // namespace physhand
