#pragma once

#include "hand_skeleton.h"

namespace physhand {

// Bridges a short loss of tracking (optical trackers lose a hand for 100-300 ms in fast
// motion and occlusion). While the ghost is lost, the hand goes on as it was moving, its
// velocity decaying, the fingers closed as they were; when the ghost comes back elsewhere,
// the hand is brought onto it with bounded acceleration instead of in one jump, so what it
// holds is carried along rather than left behind.
class TrackingGap {
  public:
    // Where `last` (the target at the loss, moving at `velocity`) has gone `lost_for`
    // seconds later: every joint moved rigidly by the wrist's decaying motion.
    static HandPose predict(const HandPose& last, const Vec3& velocity, double lost_for);

    // The ghost is back at `sample` while the hand was following `predicted`: from now on
    // `correct` eases the difference away.
    void reacquire(const HandPose& predicted, const HandPose& sample);
    // `sample` (a step `dt` after the last) with what remains of the difference, applied
    // rigidly about the wrist, so the grip (the fingers' shape) is the sample's.
    HandPose correct(const HandPose& sample, double dt);
    void reset() { active_ = false; }

  private:
    bool active_ = false;
    Vec3 offset_ = Vec3::Zero();    // wrist position, predicted minus sample, at reacquisition
    Vec3 rotation_ = Vec3::Zero();  // wrist rotation vector, sample to predicted
    double elapsed_ = 0.0;
    double duration_ = 0.0;
};

}  // namespace physhand
