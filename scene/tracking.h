#pragma once

#include <array>
#include <vector>

#include "hand_skeleton.h"
#include "scene.h"

namespace physhand {

// The scripted hand itself, noise-free, at any time (keyframes interpolated as the
// script says; recorded tracks linearly between samples).
HandPose evaluate_script(const HandScript& script, HandSide side, double t);

// The ghost hands of a scene: the scripts sampled at tracking.rate_hz, with seeded
// Gaussian noise (noise_mm is the standard deviation per axis) and dropouts, as a
// tracking runtime would report them. Between samples a query interpolates, as runtimes
// do for the display time an app asks for.
class TrackedHands {
  public:
    explicit TrackedHands(const Scene& scene);
    HandPose ghost(HandSide side, double t) const;
    double rate_hz() const { return rate_hz_; }

  private:
    bool dropped(HandSide side, double t) const;

    double rate_hz_;
    std::vector<Dropout> dropouts_;
    std::array<std::vector<HandPose>, 2> samples_;  // empty: hand never tracked
};

}  // namespace physhand
