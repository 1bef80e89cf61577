#pragma once

#include <array>

#include "hand_skeleton.h"

namespace physhand {

// How much the drive smooths the ghost it follows: a One-Euro filter (Casiez, Roussel and
// Vogel 2012) per joint, position and orientation, whose cutoff rises with speed, so a still
// hand's tracking noise is filtered out while a moving hand is followed with little lag.
// The speed is the faster of the whole hand's (the mean of its joints' velocities, where
// per-joint noise averages out) and the joint's own less `joint_speed_floor` (the noise's
// share of it), so fingers that move while the hand stands still are not held back.
struct GhostSmoothing {
    double min_cutoff_hz = 0.0;  // 0: no smoothing, the drive follows the ghost itself
    double beta = 0.0;           // Hz of cutoff per m/s of speed
    double derivative_cutoff_hz = 1.0;
    double joint_speed_floor = 0.05;  // m/s
    bool enabled() const { return min_cutoff_hz > 0.0; }
};

class GhostFilter {
  public:
    // Starts over from `ghost` (first sample, or after a jump), at rest.
    void reset(const HandPose& ghost);
    // Starts over from `ghost`, moving as it has since `previous`, `dt` before: smoothing
    // that resumes mid-motion then knows how fast the hand goes and does not hold it back.
    void restart(const HandPose& ghost, const HandPose& previous, double dt);
    // The smoothed ghost after a sample `dt` seconds after the last; unchanged when the
    // smoothing is off.
    HandPose apply(const HandPose& ghost, double dt, const GhostSmoothing& smoothing);

  private:
    HandPose state_;
    std::array<Vec3, kJointCount> velocity_{};
};

}  // namespace physhand
