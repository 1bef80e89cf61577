#include "ghost_filter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace physhand {

namespace {

// The weight of a new sample in a first-order low-pass at `cutoff_hz`.
double blend(double cutoff_hz, double dt) {
    const double tau = 1.0 / (2.0 * std::numbers::pi * cutoff_hz);
    return 1.0 / (1.0 + tau / dt);
}

}  // namespace

void GhostFilter::reset(const HandPose& ghost) {
    state_ = ghost;
    velocity_.fill(Vec3::Zero());
}

double GhostFilter::estimate_speed(const HandPose& ghost, double dt,
                                   const GhostSmoothing& smoothing) {
    const double a_velocity = blend(smoothing.derivative_cutoff_hz, dt);
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const Vec3 raw = (ghost.joints[j].position - state_.joints[j].position) / dt;
        velocity_[j] += a_velocity * (raw - velocity_[j]);
    }
    return hand_velocity().norm();
}

Vec3 GhostFilter::hand_velocity() const {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : velocity_) mean += v;
    return mean / kJointCount;
}

void GhostFilter::follow(const HandPose& ghost, double dt, const GhostSmoothing& smoothing) {
    if (dt > 0.0) estimate_speed(ghost, dt, smoothing);
    state_ = ghost;
}

HandPose GhostFilter::apply(const HandPose& ghost, double dt, const GhostSmoothing& smoothing) {
    if (!smoothing.enabled() || !(dt > 0.0)) {
        follow(ghost, dt, smoothing);
        return ghost;
    }
    const double hand_speed = estimate_speed(ghost, dt, smoothing);
    HandPose out = ghost;
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const double speed =
            std::max(hand_speed, velocity_[j].norm() - smoothing.joint_speed_floor);
        const double a = blend(smoothing.min_cutoff_hz + smoothing.beta * speed, dt);
        Vec3& p = out.joints[j].position;
        p = state_.joints[j].position + a * (p - state_.joints[j].position);
    }
    state_ = out;
    return out;
}

}  // namespace physhand
