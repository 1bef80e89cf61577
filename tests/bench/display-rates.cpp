// physhand-display-rates: the sample scenes shown at 72, 90, 120 and 144 Hz and at 90 Hz
// with +-2 ms of frame jitter (physhand-scene --display-hz / --frame-jitter-ms), for each
// drive at its own substeps: free-space tracking error, smoothness against the ghost's,
// repeated poses, step cost, and the paper scenes' and lift_hold's success and shown depth.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_options.h"
#include "scene.h"
#include "scene_run.h"

using namespace physhand;

namespace {

const std::vector<std::string> kTasks = {"throw", "sphere", "displacement", "stack", "lift_hold"};
const std::vector<std::pair<std::string, int>> kConfigurations = {
    {"bones", 1}, {"implicit", 2}, {"paper", 4}};
const std::vector<DisplayTiming> kTimings = {
    {72.0, 0.0}, {90.0, 0.0}, {120.0, 0.0}, {144.0, 0.0}, {90.0, 2.0}};

std::string timing_name(const DisplayTiming& t) {
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, t.jitter_ms > 0.0 ? "%.0f Hz +-%.0f ms" : "%.0f Hz",
                  t.rate_hz, t.jitter_ms);
    return buffer;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

// "1.26 / 0.17 / ...": each task's max_shown_depth_mm.
std::string joined(const std::vector<double>& depths) {
    std::string out;
    char one[32];
    for (double d : depths) {
        std::snprintf(one, sizeof one, "%.2f", d);
        out += (out.empty() ? "" : " / ") + std::string(one);
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    const auto options =
        bench::parse_options(argc, argv, "physhand-display-rates", PHYSHAND_SCENES_DIR, true);
    if (!options) return 2;
    const Scene free_motion = load_scene(options->scenes_dir / "free_motion.json");
    std::vector<Scene> tasks;
    for (const std::string& name : kTasks) {
        if (bench::selected(options->only_scenes, name))
            tasks.push_back(load_scene(options->scenes_dir / (name + ".json")));
    }

    std::ofstream csv(options->out / "display_rates.csv");
    csv << "drive,substeps,display_hz,jitter_ms,tracking_error_rms_mm,jerk_rms,ghost_jerk_rms,"
           "repeated_pose_frames,step_us_median,tasks_passed,tasks";
    std::string depth_header;
    for (const Scene& task : tasks) {
        csv << ",shown_depth_mm_" << task.name;
        depth_header += (depth_header.empty() ? "" : " / ") + task.name;
    }
    csv << '\n';
    std::ostringstream md;
    md << "| drive | display | free_motion error RMS mm | jerk RMS m/s³ (ghost) | repeated poses "
          "| step_us median | tasks passed | failed | shown depth mm ("
       << depth_header << ") |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& [drive, substeps] : kConfigurations) {
        if (!bench::selected(options->only_drives, drive)) continue;
        for (const DisplayTiming& timing : kTimings) {
            RunOptions run;
            run.drive = drive;
            run.substeps = substeps;
            run.display = timing;
            run.measure_shown_depth = false;  // timed
            std::vector<double> step_us;
            RunResult free;
            for (int r = 0; r < options->repeat; ++r) {
                free = run_scene(free_motion, run);
                step_us.push_back(free.metrics.step_us_median);
            }
            int passed = 0;
            std::string failed;
            std::vector<double> depths;
            RunOptions measured = run;
            measured.measure_shown_depth = true;
            for (const Scene& task : tasks) {
                const RunResult result = run_scene(task, measured);
                if (result.success) {
                    ++passed;
                } else {
                    failed += (failed.empty() ? "" : ", ") + task.name;
                }
                depths.push_back(result.metrics.max_shown_depth_mm);
            }
            const MetricsSummary& m = free.metrics;
            char row[256];
            std::snprintf(row, sizeof row,
                          "| %s/%d | %s | %.3f | %.0f (%.0f) | %d | %.1f | %d/%zu | %s | %s |\n",
                          drive.c_str(), substeps, timing_name(timing).c_str(),
                          m.tracking_error_rms_mm, m.jerk_rms, m.ghost_jerk_rms,
                          m.repeated_pose_frames, median(step_us), passed, tasks.size(),
                          failed.empty() ? "-" : failed.c_str(), joined(depths).c_str());
            md << row;
            csv << drive << ',' << substeps << ',' << timing.rate_hz << ',' << timing.jitter_ms
                << ',' << m.tracking_error_rms_mm << ',' << m.jerk_rms << ',' << m.ghost_jerk_rms
                << ',' << m.repeated_pose_frames << ',' << median(step_us) << ',' << passed << ','
                << tasks.size();
            for (double d : depths) csv << ',' << d;
            csv << '\n';
        }
    }
    std::ofstream(options->out / "display_rates.md") << md.str();
    std::cout << md.str();
    return 0;
}
