#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "hand_skeleton.h"
#include "simulation.h"

namespace physhand {

// A body leaving the hand (docs/metrics.md, release_speed_ratio). Its speed as it leaves
// (the first frame after its last hand contact) against the fastest hand part that touched it
// in that last frame; with the ghost palm's speed at the last contact, which tells a throw,
// and the body's and the ghost palm's 50 ms later.
struct Release {
    std::size_t body = 0;        // as numbered in RunMetrics::add_body
    double time_s = 0.0;         // of the last contact
    double hand_speed = 0.0;     // the ghost palm's at the last contact
    double part_speed = 0.0;     // the fastest touching hand part's, at its contact point
    double leaving_speed = 0.0;  // the body's in the first frame after the last contact
    double body_speed = 0.0;     // 50 ms later
    double palm_speed = 0.0;     // the ghost palm's, 50 ms later
    // None when the part that let go had stopped (a speed under 1 mm/s).
    std::optional<double> ratio() const {
        return part_speed >= 1e-3 ? std::optional(leaving_speed / part_speed) : std::nullopt;
    }
};

struct MetricsSummary {
    double tracking_error_rms_mm = 0.0;
    double tracking_error_p99_mm = 0.0;
    double max_penetration_mm = 0.0;
    double max_shown_depth_mm = 0.0;  // Simulation::shown_depth, at every frame
    double max_joint_gap_mm = 0.0;    // the physical hand's, PhysicalHandState::max_joint_gap
    double step_us_median = 0.0;
    double step_us_p99 = 0.0;
    double jitter_mm = 0.0;        // physical joints, frame to frame, not in contact
    double ghost_jitter_mm = 0.0;  // the same for the ghost (the input noise)
    // Physical joints, frame to frame, in the frames their ghost moved under 0.1 mm, in
    // contact or not: a still hand resting on something must not shiver.
    double rest_jitter_mm = 0.0;
    // Frames that returned the previous frame's joints exactly while the ghost moved over
    // 0.1 mm and no part of that hand touched anything: a hand that judders.
    int repeated_pose_frames = 0;
    // RMS jerk (m/s^3) of the wrist and fingertips over the frames nothing touched, the
    // physical hand's and the ghost's: how smoothly the hand moves frame to frame.
    double jerk_rms = 0.0;
    double ghost_jerk_rms = 0.0;
    double max_body_speed = 0.0;       // m/s, what bodies moved with
    double max_requested_speed = 0.0;  // m/s, what the dynamics asked for before the limit
    int frames = 0;
    int nonfinite_count = 0;
    std::array<int, 2> frames_touching_bodies{};  // by HandSide: it touched a dynamic body
    // The fastest throw: of the bodies' last releases, the one whose hand let go fastest, if
    // at throwing speed (kThrowPalmSpeed); none in scenes without a throw.
    std::optional<Release> throw_release;
};

// A ghost palm slower than this at the last contact placed the body rather than threw it.
inline constexpr double kThrowPalmSpeed = 0.5;  // m/s

// Accumulates the figures of docs/metrics.md over a run, frame by frame.
class RunMetrics {
  public:
    // One hand at one displayed frame: the ghost the app's time asked for, the physical
    // joints returned, and which joints' bodies touched something.
    void add_hand(double t, HandSide side, const HandPose& ghost, const HandPose& physical,
                  const std::array<bool, kJointCount>& in_contact);
    // A dynamic body at the same frame, after the hands; `body` numbers it in this run.
    // `touching_part_speed`: the fastest hand part touching it in this frame, at its contact
    // point (0 when none).
    void add_body(double t, std::size_t body, const BodyState& state,
                  double touching_part_speed = 0.0);
    // What one frame's step measured (Simulation's figures of the frame).
    struct Frame {
        double step_us = 0.0;
        double max_penetration_m = 0.0;
        double max_shown_depth_m = 0.0;
        double max_joint_gap_m = 0.0;
        double max_body_speed = 0.0;
        double max_requested_speed = 0.0;
        bool nonfinite = false;
    };
    // Once per frame, after its hands and bodies.
    void add_frame(const Frame& frame);
    MetricsSummary summary() const;

  private:
    // The wrist and fingertips at the last frames, for their jerk.
    static constexpr std::size_t kJerkPoints = 6;
    struct JerkWindow {
        std::array<std::array<Vec3, kJerkPoints>, 3> physical{}, ghost{};  // newest first
        std::array<double, 3> t{};
        int frames = 0;  // consecutive frames held, up to 3
    };
    struct HandHistory {
        std::array<double, kJointCount> last_contact_t;
        JerkWindow jerk;
        HandPose previous_physical;
        HandPose previous_ghost;
        double previous_t = 0.0;
        std::optional<double> palm_speed;  // ghost palm at the latest frame
        bool have_previous = false;
        HandHistory() { last_contact_t.fill(-1e9); }
    };
    struct BodyHistory {
        std::optional<double> last_contact_t;  // unset once its release is measured
        HandSide hand = HandSide::Right;       // that touched it last
        double hand_speed = 0.0;               // its ghost palm's then
        double part_speed = 0.0;               // the fastest part touching it then
        std::optional<double> leaving_speed;   // in the first frame after it
        std::optional<Release> release;        // since its last contact
    };
    // Repeated poses and jerk of one hand's frame; `touching`: any of its joints in contact.
    void add_smoothness(HandHistory& h, double t, const HandPose& ghost, const HandPose& physical,
                        bool touching);

    std::array<HandHistory, 2> history_;
    std::vector<BodyHistory> bodies_;
    std::array<bool, 2> touching_now_{};
    std::array<int, 2> frames_touching_{};
    std::vector<double> errors_m_;
    double jitter_sq_ = 0.0, ghost_jitter_sq_ = 0.0;
    std::int64_t jitter_n_ = 0;
    double rest_jitter_sq_ = 0.0;
    std::int64_t rest_jitter_n_ = 0;
    int repeated_pose_frames_ = 0;
    double jerk_sq_ = 0.0, ghost_jerk_sq_ = 0.0;
    std::int64_t jerk_n_ = 0;
    std::vector<double> step_us_;
    double max_penetration_m_ = 0.0;
    double max_shown_depth_m_ = 0.0;
    double max_joint_gap_m_ = 0.0;
    double max_speed_ = 0.0;
    double max_requested_speed_ = 0.0;
    int nonfinite_ = 0;
};

}  // namespace physhand
