#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "predicates.h"
#include "run_metrics.h"
#include "scene.h"
#include "simulation.h"

namespace physhand {

// When the frames of a run are shown: `rate_hz` (20-240), each frame but the first moved by
// up to `jitter_ms` either way (under a third of a period), as physics/frame_clock.h's
// frame_jitter_ns with `jitter_seed` has it.
struct DisplayTiming {
    double rate_hz = 90.0;
    double jitter_ms = 0.0;
    std::uint64_t jitter_seed = 0;
};

struct RunOptions {
    std::optional<std::string> drive;   // a builtin drive's name; default drive if absent
    std::optional<int> substeps;        // overrides the drive's own
    std::optional<std::uint64_t> seed;  // overrides tracking.seed
    bool gating = true;
    bool sleeping = true;
    DisplayTiming display;
    // max_shown_depth_mm, measured between frames: it leaves the caches colder for the next
    // step (free_motion, implicit at 1 substep: a median step of 76-86 us became 100-112), so
    // the benchmarks that time steps leave it off (then 0).
    bool measure_shown_depth = true;
};

struct RunResult {
    std::string scene;
    std::string path = "physics";
    std::string drive;
    int substeps = 0;
    double display_hz = 90.0;
    bool success = false;
    std::vector<PredicateResult> predicates;
    MetricsSummary metrics;  // throw_release numbers bodies as `bodies` orders them
    GuardCounters guards;
    std::vector<std::pair<std::string, Pose>> bodies;  // final pose of every dynamic collider
};

// Throws std::invalid_argument for an unknown drive or substeps < 1.
SimulationSettings settings_for(const RunOptions& options);

// Throws std::invalid_argument for a rate outside 20-240 Hz or too much jitter.
void check_display_timing(const DisplayTiming& display);

// Plays a scene headless in physics/ alone: the tracked hands drive the physical hands
// frame by frame at the display rate (90 Hz unless said), and the predicates and metrics
// are evaluated.
RunResult run_scene(const Scene& scene, const RunOptions& options);
// The same with settings of one's own (a variant of a drive, say).
RunResult run_scene(const Scene& scene, const SimulationSettings& settings,
                    std::optional<std::uint64_t> seed = std::nullopt,
                    const DisplayTiming& display = {}, bool measure_shown_depth = true);

}  // namespace physhand
