#include "pathological_tracking.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace physhand::testing {
namespace {

constexpr const char* kTestName = "Stress.RandomPathologicalTrackingStaysFiniteAndRecovers";

// Every drive, per the plan (stress_plan_from_env): the suite's short run by default, the
// long one from scripts/stress.sh. Each run reports nonfinite_count, max_body_speed and
// recovery_s; a failing one is printed with the command that replays it alone.
TEST(Stress, RandomPathologicalTrackingStaysFiniteAndRecovers) {
    const StressPlan plan = stress_plan_from_env();
    std::vector<DriveSettings> drives;
    for (const DriveSettings& d : builtin_drives()) {
        if (!plan.drive || d.name == *plan.drive) drives.push_back(d);
    }
    struct Tally {
        int runs = 0, frames = 0, nonfinite = 0, failed = 0;
        double max_speed = 0.0, max_requested = 0.0, limit = 0.0;
        std::uint64_t clamps = 0;
        std::vector<double> recovery_s;
    };
    std::map<std::string, Tally> tallies;
    const std::string binary = std::filesystem::read_symlink("/proc/self/exe").string();
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(plan.seconds);
    std::uint64_t seed = plan.first_seed;
    for (; seed <= plan.last_seed || std::chrono::steady_clock::now() < deadline; ++seed) {
        for (const DriveSettings& drive : drives) {
            const PathologyResult r = run_pathology(drive, seed);
            Tally& t = tallies[drive.name];
            ++t.runs;
            t.frames += r.frames;
            t.nonfinite += r.nonfinite_count;
            t.max_speed = std::max(t.max_speed, r.max_body_speed);
            t.max_requested = std::max(t.max_requested, r.max_requested_speed);
            t.clamps += r.speed_clamps;
            t.limit = r.speed_limit;
            t.recovery_s.push_back(r.recovery_s);
            if (passed(r, drive)) continue;
            ++t.failed;
            ADD_FAILURE() << "drive " << drive.name << " seed " << seed << ": nonfinite_count "
                          << r.nonfinite_count << ", max_body_speed " << r.max_body_speed
                          << " m/s (requested " << r.max_requested_speed << ", limit "
                          << r.speed_limit << "), recovery_s " << r.recovery_s << " (limit "
                          << kMaxRecoveryS << ")\n  replay: PHYSHAND_STRESS_SEEDS=" << seed
                          << " PHYSHAND_STRESS_DRIVE=" << drive.name << " " << binary
                          << " --gtest_filter=" << kTestName;
        }
    }
    for (const auto& [name, t] : tallies) {
        std::vector<double> rec = t.recovery_s;
        std::sort(rec.begin(), rec.end());
        std::cout << "stress: drive " << name << ": seeds " << plan.first_seed << "-" << seed - 1
                  << " (" << t.runs << " runs, " << t.frames << " frames), nonfinite_count "
                  << t.nonfinite << ", max_body_speed " << t.max_speed << " m/s (limit " << t.limit
                  << "; requested at most " << t.max_requested << ", speed_clamps " << t.clamps
                  << "), recovery_s median " << rec[rec.size() / 2] << " max " << rec.back()
                  << ", failed runs " << t.failed << "\n";
    }
}

// The plan's variables as they were, put back when it goes (a long run's plan survives this
// test when it runs in the same process).
class SavedPlanEnvironment {
  public:
    SavedPlanEnvironment() {
        for (const char* name : kNames) {
            const char* value = std::getenv(name);
            saved_.emplace_back(name, value ? std::optional<std::string>(value) : std::nullopt);
        }
    }
    ~SavedPlanEnvironment() {
        for (const auto& [name, value] : saved_) {
            if (value)
                ::setenv(name, value->c_str(), 1);
            else
                ::unsetenv(name);
        }
    }
    SavedPlanEnvironment(const SavedPlanEnvironment&) = delete;
    SavedPlanEnvironment& operator=(const SavedPlanEnvironment&) = delete;

  private:
    static constexpr const char* kNames[] = {"PHYSHAND_STRESS_SEEDS", "PHYSHAND_STRESS_SECONDS",
                                             "PHYSHAND_STRESS_DRIVE"};
    std::vector<std::pair<const char*, std::optional<std::string>>> saved_;
};

TEST(Stress, PlanComesFromTheEnvironmentAndRejectsNonsense) {
    const SavedPlanEnvironment saved;
    ::setenv("PHYSHAND_STRESS_SEEDS", "5-9", 1);
    ::setenv("PHYSHAND_STRESS_SECONDS", "2", 1);
    ::setenv("PHYSHAND_STRESS_DRIVE", "paper", 1);
    const StressPlan plan = stress_plan_from_env();
    EXPECT_EQ(plan.first_seed, 5u);
    EXPECT_EQ(plan.last_seed, 9u);
    EXPECT_EQ(plan.seconds, 2.0);
    EXPECT_EQ(plan.drive, "paper");
    ::setenv("PHYSHAND_STRESS_SEEDS", "7", 1);
    EXPECT_EQ(stress_plan_from_env().last_seed, 7u);
    for (const char* bad : {"9-5", "x", "1-", "-3", ""}) {
        ::setenv("PHYSHAND_STRESS_SEEDS", bad, 1);
        EXPECT_THROW(stress_plan_from_env(), std::invalid_argument) << bad;
    }
    ::unsetenv("PHYSHAND_STRESS_SEEDS");
    ::setenv("PHYSHAND_STRESS_DRIVE", "nope", 1);
    EXPECT_THROW(stress_plan_from_env(), std::invalid_argument);
    ::setenv("PHYSHAND_STRESS_DRIVE", "paper", 1);
    ::setenv("PHYSHAND_STRESS_SECONDS", "1.5", 1);
    EXPECT_THROW(stress_plan_from_env(), std::invalid_argument);
}

TEST(Stress, ARunIsReplayableFromItsSeed) {
    const PathologyResult a = run_pathology(default_drive(), 11);
    const PathologyResult b = run_pathology(default_drive(), 11);
    EXPECT_EQ(a.frames, b.frames);
    EXPECT_EQ(a.max_body_speed, b.max_body_speed);
    EXPECT_EQ(a.recovery_s, b.recovery_s);
}

}  // namespace
}  // namespace physhand::testing
