#pragma once

#include <array>

#include "hand_skeleton.h"

namespace physhand {

// How much the drive smooths the ghost it follows: a One-Euro filter (Casiez, Roussel and
// Vogel 2012) on each joint's position, whose cutoff rises with speed, so a still hand's
// tracking noise is filtered out while a moving hand is followed with little lag.
// Orientations pass unsmoothed: a knuckle turns in place, where no speed would lift its
// cutoff, and the bone it carries would trail.
// The speed is the faster of the whole hand's (the mean of its joints' velocities, where
// per-joint noise averages out) and the joint's own less `joint_speed_floor` (the noise's
// share of it), so fingers that move while the hand stands still are not held back.
struct GhostSmoothing {
    double min_cutoff_hz = 0.0;  // 0: no smoothing, the drive follows the ghost itself
    double beta = 0.0;           // Hz of cutoff per m/s of speed
    double derivative_cutoff_hz = 1.0;
    double joint_speed_floor = 0.05;  // m/s
    // Before all that, and whether or not the hand touches anything, the NoiseFilter's
    // expected joint acceleration, m/s^2 (0: off).
    double noise_acceleration = 0.0;
    // Before that, the tracking noise that no hand could make is taken out (SkeletonFit).
    bool fit_skeleton = false;
    bool enabled() const { return min_cutoff_hz > 0.0; }
};

class GhostFilter {
  public:
    // Starts over from `ghost` (first sample, or after a jump), at rest.
    void reset(const HandPose& ghost);
    // Passes a sample `dt` after the last through unsmoothed, still estimating the hand's
    // speed, so that smoothing that resumes mid-motion (after a touch, or once the hand is
    // simulated again) knows how fast the hand goes.
    void follow(const HandPose& ghost, double dt, const GhostSmoothing& smoothing);
    // The smoothed ghost after a sample `dt` after the last; unchanged when the smoothing is
    // off.
    HandPose apply(const HandPose& ghost, double dt, const GhostSmoothing& smoothing);
    // The hand's velocity, the mean of its joints' estimates (estimated whether or not the
    // smoothing is on: it carries a hand through a tracking loss).
    Vec3 hand_velocity() const;

  private:
    // Updates the speed estimates with a sample `dt` after the last; the hand's speed.
    double estimate_speed(const HandPose& ghost, double dt, const GhostSmoothing& smoothing);

    HandPose state_;
    std::array<Vec3, kJointCount> velocity_{};
};

}  // namespace physhand
