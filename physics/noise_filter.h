#pragma once

#include <array>

#include "hand_skeleton.h"
#include "noise_meter.h"

namespace physhand {

// Takes the tracking noise out of the ghost without a lag a person would feel: an alpha-beta
// filter (the steady-state Kalman filter of a joint moving at a slowly changing velocity) on
// each joint's position, whose gains follow the noise it measures. The noise is read from the
// joints' second differences less the whole hand's (tracking noise is each joint's own,
// a hand's motion is shared), so a clean ghost is passed on almost as it is and a noisy one
// is smoothed as much as its noise needs. The same gains for every joint keep a grip's shape:
// a hand that moves as a whole is filtered as a whole.
class NoiseFilter {
  public:
    // Starts over from `ghost`, at rest, keeping what it learned of the noise.
    void reset(const HandPose& ghost);
    // The filtered ghost for a sample `dt` after the last, for joints expected to change
    // their velocity by about `acceleration` (m/s^2); 0: the ghost as it is.
    HandPose apply(const HandPose& ghost, double dt, double acceleration);
    // Standard deviation per axis of the noise measured so far, m.
    double noise() const;
    // The noise is too little to filter: the ghost passes as it came.
    bool passes_clean() const;

  private:
    void measure_noise(const HandPose& ghost, double dt);

    HandPose state_;
    std::array<Vec3, kJointCount> velocity_{};
    ThirdDifferences differences_;  // of the raw positions
    double noise_variance_ = 0.0;
};

}  // namespace physhand
