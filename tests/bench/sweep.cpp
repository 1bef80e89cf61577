// physhand-sweep: run time against error. Sweeps every builtin drive over substep counts on
// the measurement scenes and writes a CSV, one SVG plot per scene and the Markdown report.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench_options.h"
#include "quantile.h"
#include "run_metrics.h"
#include "scene.h"
#include "scene_run.h"
#include "svg_plot.h"

namespace fs = std::filesystem;
using namespace physhand;

namespace {

struct SceneAxis {
    std::string scene;
    std::string metric;  // the error this scene is judged by
};
const std::vector<SceneAxis> kScenes = {{"free_motion", "tracking_error_rms_mm"},
                                        {"press_table", "max_penetration_mm"},
                                        {"lift_hold", "slip_mm"},
                                        {"stack", "tracking_error_rms_mm"},
                                        {"jitter", "jitter_mm"}};
const std::vector<int> kSubsteps = {1, 2, 4, 8, 16};

struct Row {
    std::string scene, drive;
    int substeps = 0;
    MetricsSummary m;
    double fastest_us = 0.0;  // the lowest step_us median of the repeats
    double slip_mm = NAN;
    bool success = false;
    double error() const;
    std::string metric;
    std::uint64_t speed_clamps = 0;
    // Stable: the scene succeeded, every value stayed finite and no body ever reached the
    // speed limit (where the guard clamps an exploding hand).
    bool stable() const { return success && m.nonfinite_count == 0 && speed_clamps == 0; }
};

double Row::error() const {
    if (metric == "tracking_error_rms_mm") return m.tracking_error_rms_mm;
    if (metric == "max_penetration_mm") return m.max_penetration_mm;
    if (metric == "slip_mm") return slip_mm;
    return m.jitter_mm;
}

RunOptions options_of(const std::string& drive, int substeps) {
    RunOptions options;
    options.measure_shown_depth = false;  // timed
    options.drive = drive;
    options.substeps = substeps;
    return options;
}

// Every configuration of one scene, `repeat` times: the repeats go round all of them in
// turn, after one run left out, so that a slow start or a busy moment of the machine does
// not fall on one configuration alone.
std::vector<Row> measure(const Scene& scene, const SceneAxis& axis,
                         const std::vector<std::pair<std::string, int>>& configurations,
                         int repeat) {
    std::vector<Row> rows;
    std::vector<std::vector<double>> medians(configurations.size()), p99s(configurations.size());
    if (!configurations.empty()) {
        run_scene(scene, options_of(configurations[0].first, configurations[0].second));
    }
    for (int i = 0; i < repeat; ++i) {
        for (std::size_t c = 0; c < configurations.size(); ++c) {
            const auto& [drive, substeps] = configurations[c];
            const RunResult r = run_scene(scene, options_of(drive, substeps));
            medians[c].push_back(r.metrics.step_us_median);
            p99s[c].push_back(r.metrics.step_us_p99);
            if (i > 0) continue;  // runs are deterministic: only the timings differ
            Row row;
            row.scene = axis.scene;
            row.drive = drive;
            row.substeps = substeps;
            row.m = r.metrics;
            row.success = r.success;
            row.metric = axis.metric;
            row.speed_clamps = r.guards.speed_clamps;
            for (const PredicateResult& p : r.predicates) {
                if (p.slip_mm) row.slip_mm = *p.slip_mm;
            }
            rows.push_back(row);
        }
    }
    for (std::size_t c = 0; c < rows.size(); ++c) {
        rows[c].m.step_us_median = quantile(medians[c], 0.5);
        rows[c].m.step_us_p99 = quantile(p99s[c], 0.5);
        rows[c].fastest_us = *std::min_element(medians[c].begin(), medians[c].end());
    }
    return rows;
}

// Errors closer than this are equal: the scenes do not resolve them (a configuration's
// slip or penetration moves by more between substep counts, which change nothing a hand
// could feel), and no one sees a hundredth of a millimetre.
constexpr double kErrorResolutionMm = 0.01;

// Timings closer than this share are equal. Compared by each configuration's fastest
// repeat: on a shared machine interference only ever adds time, and a whole run's median
// moves by 30 % with it.
constexpr double kTimeResolution = 0.1;

bool faster(const Row& a, const Row& b) {
    return a.fastest_us < (1.0 - kTimeResolution) * b.fastest_us;
}

// `a` is at least as good as `b` on both axes, and better on one, beyond noise.
bool dominates(const Row& a, const Row& b) {
    const bool better_error = a.error() < b.error() - kErrorResolutionMm;
    return !faster(b, a) && a.error() <= b.error() + kErrorResolutionMm &&
           (faster(a, b) || better_error);
}

// Points no other stable point dominates.
std::vector<bool> pareto(const std::vector<Row>& rows) {
    std::vector<bool> front(rows.size(), false);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!rows[i].stable()) continue;
        front[i] = std::none_of(rows.begin(), rows.end(),
                                [&](const Row& o) { return o.stable() && dominates(o, rows[i]); });
    }
    return front;
}

std::string fmt(double v, int digits = 3) {
    if (std::isnan(v)) return "–";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

// One line for the report: is the default (rows[d]) on the front, how it compares with
// paper at its own substep count, and with every stable paper configuration.
std::string verdict(const std::vector<Row>& rows, const std::vector<bool>& front, std::size_t d) {
    const Row& me = rows[d];
    std::ostringstream v;
    v << "- " << me.scene << ": the default (" << me.drive << ", " << me.substeps << " substep"
      << (me.substeps == 1 ? "" : "s") << ", " << fmt(me.m.step_us_median, 0) << " µs, "
      << me.metric << " " << fmt(me.error()) << ")"
      << (!me.stable() ? " FAILED"
          : front[d]   ? " is on the Pareto front"
                       : " is NOT on the Pareto front");
    // Faster beyond noise, and as accurate within the resolution.
    auto ahead = [&](const Row& p) {
        return me.stable() && faster(me, p) && me.error() <= p.error() + kErrorResolutionMm;
    };
    auto describe = [&](const Row& p) {
        std::ostringstream o;
        o << "paper/" << p.substeps << " (" << fmt(p.m.step_us_median, 0) << " µs, "
          << fmt(p.error()) << ")";
        return o.str();
    };
    int stable = 0, beaten = 0;
    std::vector<std::string> not_beaten;
    for (const Row& p : rows) {
        if (p.drive != "paper") continue;
        if (p.substeps == me.substeps) {
            v << "; paper at " << p.substeps << " substep" << (p.substeps == 1 ? "" : "s") << ": "
              << (!p.stable() ? "unstable"
                  : ahead(p)  ? "slower and no more accurate, " + describe(p)
                              : "NOT slower and no more accurate, " + describe(p));
        }
        if (!p.stable()) continue;
        ++stable;
        if (ahead(p))
            ++beaten;
        else
            not_beaten.push_back(describe(p));
    }
    v << "; ahead of " << beaten << " of " << stable << " stable paper configurations";
    for (std::size_t i = 0; i < not_beaten.size(); ++i)
        v << (i == 0 ? " (not of " : ", ") << not_beaten[i];
    v << (not_beaten.empty() ? "." : ").");
    return v.str();
}

}  // namespace

int main(int argc, char** argv) {
    const auto options =
        bench::parse_options(argc, argv, "physhand-sweep", PHYSHAND_SCENES_DIR, true);
    if (!options) return 2;
    const fs::path& out = options->out;
    const fs::path& scenes_dir = options->scenes_dir;
    const int repeat = options->repeat;
    std::ofstream csv(out / "sweep.csv");
    csv << "scene,drive,substeps,step_us_median,step_us_fastest,step_us_p99,tracking_error_rms_mm,"
           "tracking_error_p99_mm,max_penetration_mm,slip_mm,jitter_mm,ghost_jitter_mm,"
           "max_body_speed,nonfinite_count,success,speed_clamps\n";
    std::ostringstream md;
    const DriveSettings& chosen = default_drive();
    std::vector<std::string> verdicts;
    for (const SceneAxis& axis : kScenes) {
        if (!bench::selected(options->only_scenes, axis.scene)) continue;
        const Scene scene = load_scene(scenes_dir / (axis.scene + ".json"));
        std::vector<std::pair<std::string, int>> configurations;
        for (const DriveSettings& d : builtin_drives()) {
            if (!bench::selected(options->only_drives, d.name)) continue;
            for (int n : options->only_substeps.empty() ? kSubsteps : options->only_substeps)
                configurations.emplace_back(d.name, n);
        }
        const std::vector<Row> rows = measure(scene, axis, configurations, repeat);
        const std::vector<bool> front = pareto(rows);
        md << "\n### " << axis.scene << " (error: " << axis.metric << ")\n\n![" << axis.scene
           << "](bench/" << axis.scene
           << ".svg)\n\n| drive | substeps | step_us median | fastest repeat | p99 | "
           << axis.metric
           << " | success | nonfinite | speed clamps | Pareto "
              "|\n|---|---|---|---|---|---|---|---|---|---|\n";
        SvgPlot plot(axis.scene + ": run time against error", "step_us median (µs per 90 Hz frame)",
                     axis.metric, "substeps");
        std::map<std::string, std::vector<std::size_t>> by_drive;
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const Row& r = rows[i];
            csv << r.scene << ',' << r.drive << ',' << r.substeps << ',' << r.m.step_us_median
                << ',' << r.fastest_us << ',' << r.m.step_us_p99 << ',' << r.m.tracking_error_rms_mm
                << ',' << r.m.tracking_error_p99_mm << ',' << r.m.max_penetration_mm << ','
                << (std::isnan(r.slip_mm) ? std::string() : std::to_string(r.slip_mm)) << ','
                << r.m.jitter_mm << ',' << r.m.ghost_jitter_mm << ',' << r.m.max_body_speed << ','
                << r.m.nonfinite_count << ',' << (r.success ? "true" : "false") << ','
                << r.speed_clamps << '\n';
            md << "| " << r.drive << " | " << r.substeps << " | " << fmt(r.m.step_us_median, 0)
               << " | " << fmt(r.fastest_us, 0) << " | " << fmt(r.m.step_us_p99, 0) << " | "
               << fmt(r.error()) << " | " << (r.success ? "yes" : "**no**") << " | "
               << r.m.nonfinite_count << " | " << r.speed_clamps << " | " << (front[i] ? "●" : "")
               << " |\n";
            by_drive[r.drive].push_back(i);
        }
        for (const auto& [drive, idx] : by_drive) {
            std::vector<SvgPlot::Point> pts;
            for (std::size_t i : idx) {
                pts.push_back({rows[i].m.step_us_median, rows[i].error(),
                               std::to_string(rows[i].substeps), front[i], !rows[i].stable()});
            }
            plot.add_series(drive, pts);
        }
        std::ofstream(out / (axis.scene + ".svg")) << plot.render();

        for (std::size_t i = 0; i < rows.size(); ++i) {
            if (rows[i].drive == chosen.name && rows[i].substeps == chosen.substeps)
                verdicts.push_back(verdict(rows, front, i));
        }
    }
    std::ofstream report(out / "sweep.md");
    report << "## Default drive against the sweep\n\n";
    for (const std::string& v : verdicts) report << v << "\n";
    report << md.str();
    std::cout << "wrote " << (out / "sweep.csv") << ", " << (out / "sweep.md")
              << " and one SVG per scene\n";
    return 0;
}
