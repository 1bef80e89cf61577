#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "drive.h"

namespace physhand::testing {

// One seeded, replayable run of pathological tracking of both hands over a table with a
// cube: teleports up to 10 m (some into the cube or the table), NaN and ±Inf in any
// component, zero and non-unit quaternions, dropouts from one frame to 3 s, 200 ms frame
// hitches, noise bursts, both hands in one place, and both hands squeezing the cube from
// either side; then clean tracking above the table.
struct PathologyResult {
    int frames = 0;
    int nonfinite_count = 0;  // frames in which Simulation::state_is_finite() was false
    // m/s: the fastest any body moved (the limit bounds it, for every drive) and the fastest
    // the dynamics asked for before the limit (the shipped drives never need the limit).
    double max_body_speed = 0.0;
    double max_requested_speed = 0.0;
    double speed_limit = 0.0;
    std::uint64_t speed_clamps = 0;
    // Clean tracking until, in both hands, every joint that touched nothing in the last
    // 0.25 s (as tracking error counts them, docs/metrics.md), and whose ghost does not reach
    // within its radius and kRecoveredM of the cube, is within kRecoveredM of its ghost; inf:
    // not within kRecoveryWindowS.
    double recovery_s = 0.0;
};
inline constexpr double kRecoveredM = 0.005;
inline constexpr double kMaxRecoveryS = 1.0;
inline constexpr double kRecoveryWindowS = 2.0;

PathologyResult run_pathology(const DriveSettings& drive, std::uint64_t seed);
// `drive` is the one that ran: the paper's explicit drive is the unprotected reference, so
// only what its bodies moved with is held to the limit, not what it asked for.
bool passed(const PathologyResult& r, const DriveSettings& drive);

// Which runs to make, from the environment (the test suite's short run when unset):
//   PHYSHAND_STRESS_SEEDS=A or A-B    seeds (default 1-3)
//   PHYSHAND_STRESS_SECONDS=S         then further seeds until S seconds of wall time passed
//   PHYSHAND_STRESS_DRIVE=NAME        one drive only (default: every builtin drive)
struct StressPlan {
    std::uint64_t first_seed = 1;
    std::uint64_t last_seed = 3;
    double seconds = 0.0;
    std::optional<std::string> drive;
};
// Throws std::invalid_argument naming the variable on a malformed value.
StressPlan stress_plan_from_env();

}  // namespace physhand::testing
