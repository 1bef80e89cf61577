#pragma once

#include <array>
#include <cstddef>

#include "hand_skeleton.h"
#include "noise_meter.h"

namespace physhand {

// Takes out of the ghost the part of its tracking noise that no hand could make: a joint
// moving on its own, so that the bone to it changes length or leaves the direction its
// parent joint's orientation gives it. Each bone is known twice: from the two joints'
// positions, and as the parent's orientation turning the bone as it has been (its offset in
// the parent's frame, learned). The two are weighed by the noise measured on each, the bones
// chained from the wrist, and the chain placed where the joints are on average. A runtime
// whose positions and orientations agree (one skeleton fitted to its cameras) passes as it
// came, and so does a clean ghost; per-joint position noise is cut to what the whole hand
// shares, which moves a grip without loosening it.
class SkeletonFit {
  public:
    // Learns `ghost`'s bones and measures the noise anew from it (a first sample, or one after
    // a loss); what was learned of the bones is kept.
    void restart(const HandPose& ghost);
    // The fitted ghost for a sample `dt` after the last (none: restarts from it).
    HandPose apply(const HandPose& ghost, double dt);
    // Per-axis noise of the bones as the positions give them, m.
    double position_noise() const;

  private:
    // Each joint's bone from its parent, as the parent's orientation turns the learned offset.
    JointVectors bones_from_orientations(const HandPose& ghost) const;
    // Learns the bones of `ghost`, `dt` after the last sample (0: the first after a restart).
    void learn(const HandPose& ghost, const JointVectors& from_positions, double dt);
    void measure_noise(const JointVectors& from_positions, const JointVectors& from_orientations,
                       double dt);

    struct Bone {
        double samples = 0.0;  // the offset's weight, in samples (0: not learned)
        int outliers = 0;      // samples in a row too far from it to learn
        double drift = 0.0;    // mean squared distance of the recent mean from it, m²
    };
    JointVectors offset_ = zero_vectors();  // each joint in its parent's frame
    JointVectors recent_ = zero_vectors();  // the same over the last kNoiseMemory
    std::array<Bone, kJointCount> bones_{};
    bool started_ = false;
    bool measuring_ = false;  // the noise, while positions and orientations disagree
    ThirdDifferences position_differences_;
    ThirdDifferences orientation_differences_;
    double position_variance_ = 0.0;
    // Per axis, of a bone as its parent's orientation gives it, over its length squared.
    double orientation_variance_ = 0.0;
    double disagreement_variance_ = 0.0;  // between the two, per axis
};

}  // namespace physhand
