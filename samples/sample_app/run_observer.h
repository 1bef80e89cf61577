#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "drive.h"
#include "hand_trackers.h"
#include "predicates.h"
#include "run_metrics.h"
#include "scene.h"
#include "scene_run.h"

namespace physhand::sample {

// Judges a run through the layer as the physics-only runner judges its own (same metrics,
// same predicates), from what the API returns each frame.
class RunObserver {
  public:
    // `drive`: the hand drive the app set for the run, reported with the result.
    RunObserver(const Scene& scene, const DriveSettings& drive);

    // One displayed frame at scene time `t`: both hands, the time it took to locate them,
    // and every collider in scene order.
    void add_frame(double t, double step_us, const std::array<LocatedHand, 2>& hands,
                   const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders);
    RunResult result() const;

  private:
    const Scene& scene_;
    DriveSettings drive_;
    std::map<std::string, std::size_t> index_;  // collider id -> scene order
    RunMetrics metrics_;
    PredicateEvaluator predicates_;
    std::vector<XrPhysicalColliderLocationPHYSHAND> last_;  // the latest frame's colliders
};

}  // namespace physhand::sample
