#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "hand_skeleton.h"

namespace physhand {

struct MetricsSummary {
    double tracking_error_rms_mm = 0.0;
    double tracking_error_p99_mm = 0.0;
    double max_penetration_mm = 0.0;
    double step_us_median = 0.0;
    double step_us_p99 = 0.0;
    double jitter_mm = 0.0;        // physical joints, frame to frame, not in contact
    double ghost_jitter_mm = 0.0;  // the same for the ghost (the input noise)
    double max_body_speed = 0.0;
    int frames = 0;
    int nonfinite_count = 0;
};

// Accumulates the figures of shared/METRICS.md over a run, frame by frame.
class RunMetrics {
  public:
    // One hand at one displayed frame: the ghost the app's time asked for, the physical
    // joints returned, and which joints' bodies touched something.
    void add_hand(double t, HandSide side, const HandPose& ghost, const HandPose& physical,
                  const std::array<bool, kJointCount>& in_contact);
    // Once per frame, after its hands.
    void add_frame(double step_us, double max_penetration_m, double max_speed, bool nonfinite);
    MetricsSummary summary() const;

  private:
    struct HandHistory {
        std::array<double, kJointCount> last_contact_t;
        HandPose previous_physical;
        HandPose previous_ghost;
        bool have_previous = false;
        HandHistory() { last_contact_t.fill(-1e9); }
    };
    std::array<HandHistory, 2> history_;
    std::vector<double> errors_m_;
    double jitter_sq_ = 0.0, ghost_jitter_sq_ = 0.0;
    std::int64_t jitter_n_ = 0;
    std::vector<double> step_us_;
    double max_penetration_m_ = 0.0;
    double max_speed_ = 0.0;
    int nonfinite_ = 0;
};

// Value at quantile q (0..1) by nearest rank; 0 for an empty set.
double quantile(std::vector<double> values, double q);

}  // namespace physhand
