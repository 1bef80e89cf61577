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

struct RunOptions {
    std::optional<std::string> drive;   // a builtin drive's name; default drive if absent
    std::optional<int> substeps;        // overrides the drive's own
    std::optional<std::uint64_t> seed;  // overrides tracking.seed
    bool gating = true;
    bool sleeping = true;
};

struct RunResult {
    std::string scene;
    std::string path = "physics";
    std::string drive;
    int substeps = 0;
    bool success = false;
    std::vector<PredicateResult> predicates;
    MetricsSummary metrics;  // throw_release numbers bodies as `bodies` orders them
    GuardCounters guards;
    std::vector<std::pair<std::string, Pose>> bodies;  // final pose of every dynamic collider
};

// Throws std::invalid_argument for an unknown drive or substeps < 1.
SimulationSettings settings_for(const RunOptions& options);

// Plays a scene headless in physics/ alone: the tracked hands drive the physical hands
// frame by frame at 90 Hz, and the predicates and metrics are evaluated.
RunResult run_scene(const Scene& scene, const RunOptions& options);
// The same with settings of one's own (a variant of a drive, say).
RunResult run_scene(const Scene& scene, const SimulationSettings& settings,
                    std::optional<std::uint64_t> seed = std::nullopt);

}  // namespace physhand
