#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "drive.h"

namespace physhand::testing {

// One seeded, replayable run of pathological tracking (teleports, NaN/Inf, zero
// quaternions, dropouts, frame hitches, noise bursts, a ghost driven deep into the table),
// then clean tracking above the table.
struct PathologyResult {
    int frames = 0;
    int nonfinite_count = 0;      // frames with a non-finite hand or cube state
    double max_body_speed = 0.0;  // m/s, fastest body in any frame
    double speed_limit = 0.0;     // m/s, the configured limit it must not exceed
    // Clean tracking until every joint not in contact (some must be) is within kRecoveredM;
    // inf: never.
    double recovery_s = 0.0;
};
inline constexpr double kRecoveredM = 0.005;
inline constexpr double kMaxRecoveryS = 1.0;

PathologyResult run_pathology(const DriveSettings& drive, std::uint64_t seed);
bool passed(const PathologyResult& r);

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
