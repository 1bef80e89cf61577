#pragma once

#include <array>
#include <optional>

#include "hand_skeleton.h"

namespace physhand {

// One vector per joint, sample after sample.
using JointVectors = std::array<Vec3, kJointCount>;
JointVectors positions(const HandPose& hand);
// Eigen leaves its vectors uninitialised, even value-initialised in an array.
JointVectors zero_vectors();

// The third differences of per-joint vectors over samples equally spaced in time: a hand's
// smooth motion (its jerk times dt^3) all but vanishes from them, while white noise of
// variance s^2 per axis gives 20 s^2. What the noise estimates are read from.
class ThirdDifferences {
  public:
    // Starts over from `values`.
    void restart(const JointVectors& values);
    // Adds `values`, `dt` after the last; their third differences once three intervals in a
    // row were the same length.
    std::optional<JointVectors> add(const JointVectors& values, double dt);

  private:
    std::array<JointVectors, 3> history_{zero_vectors(), zero_vectors(),
                                         zero_vectors()};  // the last values, newest first
    double last_dt_ = 0.0;
    int intervals_ = 0;  // consecutive intervals of one length, up to 3
};

// Weight of the newest estimate in a running estimate that remembers `memory` seconds.
double running_weight(double dt, double memory);

}  // namespace physhand
