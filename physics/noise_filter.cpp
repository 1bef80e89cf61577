#include "noise_filter.h"

#include <algorithm>
#include <cmath>

namespace physhand {

namespace {

// How long the noise estimate remembers, s.
constexpr double kNoiseMemory = 0.5;
// Measured noise below this is taken for none, m.
constexpr double kCleanNoise = 0.25e-3;

}  // namespace

void NoiseFilter::reset(const HandPose& ghost) {
    state_ = ghost;
    velocity_.fill(Vec3::Zero());
    differences_.restart(positions(ghost));
}

double NoiseFilter::noise() const {
    return std::sqrt(noise_variance_);
}

bool NoiseFilter::passes_clean() const {
    return noise() <= kCleanNoise;
}

void NoiseFilter::measure_noise(const HandPose& ghost, double dt) {
    const std::optional<JointVectors> third = differences_.add(positions(ghost), dt);
    if (!third) return;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& d : *third) mean += d;
    mean /= kJointCount;
    double sum = 0.0;
    for (const Vec3& d : *third) sum += (d - mean).squaredNorm();
    // Less the hand's mean share, which the whole hand's motion would also leave.
    const double variance = sum / (3.0 * kJointCount * 20.0 * (1.0 - 1.0 / kJointCount));
    noise_variance_ += running_weight(dt, kNoiseMemory) * (variance - noise_variance_);
}

HandPose NoiseFilter::apply(const HandPose& ghost, double dt, double acceleration) {
    if (!(dt > 0.0) || !(acceleration > 0.0)) {
        reset(ghost);
        return ghost;
    }
    measure_noise(ghost, dt);
    // Noise under the floor is clean tracking (a smooth motion's own third differences
    // read as up to 0.13 mm in the sample scenes): passed on exactly, its velocity kept for
    // when the noise rises.
    if (passes_clean()) {
        for (std::size_t j = 0; j < kJointCount; ++j)
            velocity_[j] = (ghost.joints[j].position - state_.joints[j].position) / dt;
        state_ = ghost;
        return ghost;
    }
    // Kalata's steady-state gains for the tracking index lambda.
    const double lambda = acceleration * dt * dt / (noise() - kCleanNoise);
    const double r = (4.0 + lambda - std::sqrt(8.0 * lambda + lambda * lambda)) / 4.0;
    const double alpha = 1.0 - r * r;
    const double beta = 2.0 * (2.0 - alpha) - 4.0 * r;
    HandPose out = ghost;
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const Vec3 predicted = state_.joints[j].position + velocity_[j] * dt;
        const Vec3 residual = ghost.joints[j].position - predicted;
        out.joints[j].position = predicted + alpha * residual;
        velocity_[j] += beta / dt * residual;
    }
    state_ = out;
    return out;
}

}  // namespace physhand
