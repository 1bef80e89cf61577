#include "tracking_gap.h"

#include <algorithm>
#include <cmath>

namespace physhand {

namespace {

// How long the lost hand keeps its momentum: a hand lifting at 0.2 m/s goes on 3 cm.
constexpr double kMomentumTime = 0.15;  // s
// The correction after a reacquisition follows a minimum-jerk path, x0 (1 - s(t/D)) with
// s(u) = 10u^3 - 15u^4 + 6u^5: it starts and ends at rest with no jump in acceleration,
// which peaks at kPeakShape x0 / D^2. D is chosen so that this stays under the limit (a
// third of gravity: a held cube never feels a jolt), and never shorter than the floor, so a
// small difference is not snapped away either. Unlike a critically damped approach, whose
// tail took 1.1 s to bring a 15 cm difference within 5 mm (stress seed 74), it is over at D
// (0.54 s for 15 cm; Simulation re-seats the hand instead for a ghost back further than a
// hand could have gone while lost).
constexpr double kMaxCorrectionAcceleration = 3.0;  // m/s^2
constexpr double kMinCorrectionTime = 0.08;         // s
constexpr double kPeakShape = 5.7735;               // max |s''(u)|, at u = 0.5 -+ sqrt(3)/6

// Every joint of `hand` moved rigidly with its wrist onto `wrist`.
HandPose move_rigidly(const HandPose& hand, const Pose& wrist) {
    const Pose delta = wrist * hand[Joint::Wrist].inverse();
    HandPose out = hand;
    for (Pose& joint : out.joints) {
        joint = delta * joint;
        joint.orientation.normalize();
    }
    return out;
}

}  // namespace

HandPose TrackingGap::predict(const HandPose& last, const Vec3& velocity, double lost_for) {
    const double travel =
        kMomentumTime * (1.0 - std::exp(-std::max(0.0, lost_for) / kMomentumTime));
    Pose wrist = last[Joint::Wrist];
    wrist.position += velocity * travel;
    return move_rigidly(last, wrist);
}

void TrackingGap::reacquire(const HandPose& predicted, const HandPose& sample) {
    const Pose& from = sample[Joint::Wrist];
    const Pose& to = predicted[Joint::Wrist];
    offset_ = to.position - from.position;
    rotation_ = rotation_between(from.orientation, to.orientation);
    elapsed_ = 0.0;
    duration_ = std::max(kMinCorrectionTime,
                         std::sqrt(kPeakShape * offset_.norm() / kMaxCorrectionAcceleration));
    active_ = true;
}

HandPose TrackingGap::correct(const HandPose& sample, double dt) {
    if (!active_) return sample;
    elapsed_ += dt;
    const double u = elapsed_ / duration_;
    if (u >= 1.0) {
        active_ = false;
        return sample;
    }
    const double remaining = 1.0 - u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
    Pose wrist = sample[Joint::Wrist];
    wrist.position += offset_ * remaining;
    const Vec3 turn = rotation_ * remaining;
    const double angle = turn.norm();
    if (angle > 0.0)
        wrist.orientation = Quat(Eigen::AngleAxisd(angle, turn / angle)) * wrist.orientation;
    return move_rigidly(sample, wrist);
}

}  // namespace physhand
