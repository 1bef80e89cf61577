#include "run_report.h"

#include <cstdio>

#include "frame_clock.h"

namespace physhand {

namespace {

nlohmann::json vec(const Vec3& v) {
    return {v.x(), v.y(), v.z()};
}

}  // namespace

nlohmann::json to_json(const RunResult& r) {
    nlohmann::json predicates = nlohmann::json::array();
    for (const PredicateResult& p : r.predicates) {
        nlohmann::json j = {
            {"type", p.type}, {"subject", p.subject}, {"passed", p.passed}, {"detail", p.detail}};
        if (p.slip_mm) j["slip_mm"] = *p.slip_mm;
        predicates.push_back(j);
    }
    nlohmann::json bodies = nlohmann::json::object();
    for (const auto& [id, pose] : r.bodies) {
        const Quat& q = pose.orientation;
        bodies[id] = {{"position", vec(pose.position)},
                      {"orientation", {q.x(), q.y(), q.z(), q.w()}}};
    }
    const MetricsSummary& m = r.metrics;
    const std::optional<double> ratio = m.throw_release ? m.throw_release->ratio() : std::nullopt;
    nlohmann::json release;  // null: nothing was thrown
    if (m.throw_release) {
        const Release& t = *m.throw_release;
        release = {{"body", r.bodies.at(t.body).first}, {"time_s", t.time_s},
                   {"hand_speed", t.hand_speed},        {"part_speed", t.part_speed},
                   {"leaving_speed", t.leaving_speed},  {"body_speed", t.body_speed},
                   {"palm_speed", t.palm_speed}};
    }
    // An app sees neither contact distances nor speeds before the limit through the API: the
    // layer path cannot measure them.
    const bool through_layer = r.path == "layer";
    return {
        {"scene", r.scene},
        {"path", r.path},
        {"drive", r.drive},
        {"substeps", r.substeps},
        {"display_hz", r.display_hz},
        {"success", r.success},
        {"predicates", predicates},
        {"tracking_error_rms_mm", m.tracking_error_rms_mm},
        {"tracking_error_p99_mm", m.tracking_error_p99_mm},
        {"max_penetration_mm",
         through_layer ? nlohmann::json() : nlohmann::json(m.max_penetration_mm)},
        {"max_shown_depth_mm",
         through_layer ? nlohmann::json() : nlohmann::json(m.max_shown_depth_mm)},
        {"max_joint_gap_mm", through_layer ? nlohmann::json() : nlohmann::json(m.max_joint_gap_mm)},
        {"step_us_median", m.step_us_median},
        {"step_us_p99", m.step_us_p99},
        {"jitter_mm", m.jitter_mm},
        {"ghost_jitter_mm", m.ghost_jitter_mm},
        {"rest_jitter_mm", m.rest_jitter_mm},
        {"repeated_pose_frames", m.repeated_pose_frames},
        {"jerk_rms", m.jerk_rms},
        {"ghost_jerk_rms", m.ghost_jerk_rms},
        {"max_body_speed", m.max_body_speed},
        {"max_requested_speed",
         through_layer ? nlohmann::json() : nlohmann::json(m.max_requested_speed)},
        {"release_speed_ratio", ratio ? nlohmann::json(*ratio) : nlohmann::json()},
        {"release", release},
        {"frames", m.frames},
        {"nonfinite_count", m.nonfinite_count},
        {"rejected_samples", r.guards.rejected_samples},
        {"reseats", r.guards.reseats},
        {"dropouts", r.guards.dropouts},
        {"reacquisitions", r.guards.reacquisitions},
        {"speed_clamps", r.guards.speed_clamps},
        {"bodies", bodies},
    };
}

std::string summary_line(const RunResult& r) {
    char buf[320];
    std::snprintf(
        buf, sizeof buf,
        "%-13s %-4s %-7s drive=%s/%d  error %.2f mm rms  step %.0f us median  nonfinite %d",
        r.scene.c_str(), r.success ? "OK" : "FAIL", r.path.c_str(), r.drive.c_str(), r.substeps,
        r.metrics.tracking_error_rms_mm, r.metrics.step_us_median, r.metrics.nonfinite_count);
    std::string line = buf;
    if (r.display_hz != kFrameRateHz) {
        std::snprintf(buf, sizeof buf, "  display %g Hz", r.display_hz);
        line += buf;
    }
    if (r.path != "layer") {
        std::snprintf(buf, sizeof buf, "  penetration %.2f mm (shown %.2f mm)",
                      r.metrics.max_penetration_mm, r.metrics.max_shown_depth_mm);
        line += buf;
    }
    if (const auto ratio =
            r.metrics.throw_release ? r.metrics.throw_release->ratio() : std::nullopt) {
        std::snprintf(buf, sizeof buf, "  release speed ratio %.2f", *ratio);
        line += buf;
    }
    for (const PredicateResult& p : r.predicates) {
        if (p.slip_mm) {
            std::snprintf(buf, sizeof buf, "  slip %.2f mm", *p.slip_mm);
            line += buf;
        }
    }
    return line;
}

}  // namespace physhand
