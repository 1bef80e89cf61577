#include "tracking_gap.h"

#include <algorithm>
#include <cmath>

namespace physhand {

namespace {

// How long the lost hand keeps its momentum: a hand lifting at 0.2 m/s goes on 3 cm.
constexpr double kMomentumTime = 0.15;  // s
// The correction after a reacquisition is critically damped, x(t) = x0 (1 + t/T) e^(-t/T),
// whose acceleration peaks at x0 / T^2 at its start: T is chosen so that this stays under
// the limit (a third of gravity: a held cube never feels a jolt), and never shorter than
// the floor, so a small difference is not snapped away either.
constexpr double kMaxCorrectionAcceleration = 3.0;  // m/s^2
constexpr double kMinCorrectionTime = 0.08;         // s
// Below this share of the initial difference the correction is over.
constexpr double kCorrectionDone = 1e-3;

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
    time_constant_ =
        std::max(kMinCorrectionTime, std::sqrt(offset_.norm() / kMaxCorrectionAcceleration));
    active_ = true;
}

HandPose TrackingGap::correct(const HandPose& sample, double dt) {
    if (!active_) return sample;
    elapsed_ += dt;
    const double x = elapsed_ / time_constant_;
    const double remaining = (1.0 + x) * std::exp(-x);
    if (remaining < kCorrectionDone) {
        active_ = false;
        return sample;
    }
    Pose wrist = sample[Joint::Wrist];
    wrist.position += offset_ * remaining;
    const Vec3 turn = rotation_ * remaining;
    const double angle = turn.norm();
    if (angle > 0.0)
        wrist.orientation = Quat(Eigen::AngleAxisd(angle, turn / angle)) * wrist.orientation;
    return move_rigidly(sample, wrist);
}

}  // namespace physhand
