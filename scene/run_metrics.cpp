#include "run_metrics.h"

#include <algorithm>
#include <cmath>

#include "quantile.h"

namespace physhand {

namespace {
// docs/metrics.md: spring-back within this long after a release is not tracking lag.
constexpr double kContactMemory_s = 0.25;
// docs/metrics.md: a body is released when this long has passed since its last contact.
constexpr double kReleaseDelay_s = 0.05;
// Frame times are whole nanoseconds: "at or after" must not miss a frame by rounding.
constexpr double kTimeTolerance_s = 1e-6;
// rest_jitter_mm counts a joint in the frames in which its ghost moved less than this.
constexpr double kGhostAtRest_m = 1e-4;
}  // namespace

void RunMetrics::add_smoothness(HandHistory& h, double t, const HandPose& ghost,
                                const HandPose& physical, bool touching) {
    static constexpr std::array<Joint, kJerkPoints> kPoints = {Joint::Wrist,    Joint::ThumbTip,
                                                               Joint::IndexTip, Joint::MiddleTip,
                                                               Joint::RingTip,  Joint::LittleTip};
    JerkWindow& w = h.jerk;
    if (!h.have_previous || touching) {
        w.frames = 0;
    } else {
        double ghost_moved = 0.0;
        bool same = true;
        for (std::size_t j = 0; j < kJointCount; ++j) {
            ghost_moved =
                std::max(ghost_moved,
                         (ghost.joints[j].position - h.previous_ghost.joints[j].position).norm());
            same = same && physical.joints[j].position == h.previous_physical.joints[j].position &&
                   physical.joints[j].orientation.coeffs() ==
                       h.previous_physical.joints[j].orientation.coeffs();
        }
        if (same && ghost_moved > kGhostAtRest_m) ++repeated_pose_frames_;
    }
    if (w.frames == 3) {
        // Jerk is 6 times the third divided difference over the four frames' times.
        const std::array<double, 4> times = {t, w.t[0], w.t[1], w.t[2]};
        std::array<double, 4> weight{};
        for (std::size_t i = 0; i < 4; ++i) {
            double product = 1.0;
            for (std::size_t k = 0; k < 4; ++k) {
                if (k != i) product *= times[i] - times[k];
            }
            weight[i] = 6.0 / product;
        }
        for (std::size_t p = 0; p < kJerkPoints; ++p) {
            Vec3 jerk = weight[0] * physical[kPoints[p]].position;
            Vec3 ghost_jerk = weight[0] * ghost[kPoints[p]].position;
            for (std::size_t i = 1; i < 4; ++i) {
                jerk += weight[i] * w.physical[i - 1][p];
                ghost_jerk += weight[i] * w.ghost[i - 1][p];
            }
            jerk_sq_ += jerk.squaredNorm();
            ghost_jerk_sq_ += ghost_jerk.squaredNorm();
            ++jerk_n_;
        }
    }
    if (touching) return;
    for (std::size_t i = 2; i > 0; --i) {
        w.physical[i] = w.physical[i - 1];
        w.ghost[i] = w.ghost[i - 1];
        w.t[i] = w.t[i - 1];
    }
    for (std::size_t p = 0; p < kJerkPoints; ++p) {
        w.physical[0][p] = physical[kPoints[p]].position;
        w.ghost[0][p] = ghost[kPoints[p]].position;
    }
    w.t[0] = t;
    w.frames = std::min(w.frames + 1, 3);
}

void RunMetrics::add_hand(double t, HandSide side, const HandPose& ghost, const HandPose& physical,
                          const std::array<bool, kJointCount>& in_contact) {
    HandHistory& h = history_[static_cast<int>(side)];
    if (!ghost.active || !physical.active) {
        h.have_previous = false;
        h.jerk.frames = 0;
        h.palm_speed.reset();
        return;
    }
    add_smoothness(h, t, ghost, physical,
                   std::any_of(in_contact.begin(), in_contact.end(), [](bool c) { return c; }));
    if (h.have_previous && t > h.previous_t) {
        h.palm_speed =
            (ghost[Joint::Palm].position - h.previous_ghost[Joint::Palm].position).norm() /
            (t - h.previous_t);
    } else {
        h.palm_speed.reset();
    }
    for (std::size_t j = 0; j < kJointCount; ++j) {
        if (h.have_previous &&
            (ghost.joints[j].position - h.previous_ghost.joints[j].position).norm() <
                kGhostAtRest_m) {
            rest_jitter_sq_ +=
                (physical.joints[j].position - h.previous_physical.joints[j].position)
                    .squaredNorm();
            ++rest_jitter_n_;
        }
        if (in_contact[j]) h.last_contact_t[j] = t;
        if (t - h.last_contact_t[j] <= kContactMemory_s) continue;
        errors_m_.push_back((physical.joints[j].position - ghost.joints[j].position).norm());
        if (h.have_previous) {
            jitter_sq_ += (physical.joints[j].position - h.previous_physical.joints[j].position)
                              .squaredNorm();
            ghost_jitter_sq_ +=
                (ghost.joints[j].position - h.previous_ghost.joints[j].position).squaredNorm();
            ++jitter_n_;
        }
    }
    h.previous_physical = physical;
    h.previous_ghost = ghost;
    h.previous_t = t;
    h.have_previous = true;
}

void RunMetrics::add_body(double t, std::size_t body, const BodyState& state,
                          double touching_part_speed) {
    if (bodies_.size() <= body) bodies_.resize(body + 1);
    BodyHistory& b = bodies_[body];
    for (int side = 0; side < 2; ++side) touching_now_[side] |= state.touched_by[side];
    if (state.touched_by[0] || state.touched_by[1]) {
        b.last_contact_t = t;
        b.hand =
            state.touched_by[static_cast<int>(HandSide::Right)] ? HandSide::Right : HandSide::Left;
        b.hand_speed = history_[static_cast<int>(b.hand)].palm_speed.value_or(0.0);
        b.part_speed = touching_part_speed;
        b.leaving_speed.reset();
        b.release.reset();
        return;
    }
    if (!b.last_contact_t) return;
    if (!b.leaving_speed) b.leaving_speed = state.linear_velocity.norm();
    if (t + kTimeTolerance_s < *b.last_contact_t + kReleaseDelay_s) return;
    const std::optional<double>& palm = history_[static_cast<int>(b.hand)].palm_speed;
    if (palm) {
        b.release = Release{body,         *b.last_contact_t, b.hand_speed,
                            b.part_speed, *b.leaving_speed,  state.linear_velocity.norm(),
                            *palm};
    }
    b.last_contact_t.reset();
}

void RunMetrics::add_frame(const Frame& frame) {
    step_us_.push_back(frame.step_us);
    max_penetration_m_ = std::max(max_penetration_m_, frame.max_penetration_m);
    max_shown_depth_m_ = std::max(max_shown_depth_m_, frame.max_shown_depth_m);
    max_joint_gap_m_ = std::max(max_joint_gap_m_, frame.max_joint_gap_m);
    max_speed_ = std::max(max_speed_, frame.max_body_speed);
    max_requested_speed_ = std::max(max_requested_speed_, frame.max_requested_speed);
    if (frame.nonfinite) ++nonfinite_;
    for (int side = 0; side < 2; ++side) {
        if (touching_now_[side]) ++frames_touching_[side];
    }
    touching_now_ = {};
}

MetricsSummary RunMetrics::summary() const {
    MetricsSummary s;
    double sq = 0.0;
    for (double e : errors_m_) sq += e * e;
    if (!errors_m_.empty())
        s.tracking_error_rms_mm = std::sqrt(sq / static_cast<double>(errors_m_.size())) * 1e3;
    s.tracking_error_p99_mm = quantile(errors_m_, 0.99) * 1e3;
    s.max_penetration_mm = max_penetration_m_ * 1e3;
    s.max_shown_depth_mm = max_shown_depth_m_ * 1e3;
    s.max_joint_gap_mm = max_joint_gap_m_ * 1e3;
    s.step_us_median = quantile(step_us_, 0.5);
    s.step_us_p99 = quantile(step_us_, 0.99);
    if (jitter_n_ > 0) {
        s.jitter_mm = std::sqrt(jitter_sq_ / static_cast<double>(jitter_n_)) * 1e3;
        s.ghost_jitter_mm = std::sqrt(ghost_jitter_sq_ / static_cast<double>(jitter_n_)) * 1e3;
    }
    if (rest_jitter_n_ > 0)
        s.rest_jitter_mm = std::sqrt(rest_jitter_sq_ / static_cast<double>(rest_jitter_n_)) * 1e3;
    s.repeated_pose_frames = repeated_pose_frames_;
    if (jerk_n_ > 0) {
        s.jerk_rms = std::sqrt(jerk_sq_ / static_cast<double>(jerk_n_));
        s.ghost_jerk_rms = std::sqrt(ghost_jerk_sq_ / static_cast<double>(jerk_n_));
    }
    s.max_body_speed = max_speed_;
    s.max_requested_speed = max_requested_speed_;
    s.frames = static_cast<int>(step_us_.size());
    s.nonfinite_count = nonfinite_;
    s.frames_touching_bodies = frames_touching_;
    for (const BodyHistory& b : bodies_) {
        if (b.release && b.release->hand_speed >= kThrowPalmSpeed &&
            (!s.throw_release || b.release->hand_speed > s.throw_release->hand_speed)) {
            s.throw_release = b.release;
        }
    }
    return s;
}

}  // namespace physhand
