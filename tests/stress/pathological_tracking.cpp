#include "pathological_tracking.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "stress_bench.h"

namespace physhand::testing {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kPathologyFrames = 400;
constexpr double kFrameS = 1 / 90.0;
constexpr double kHitchS = 0.2;
constexpr int kLongestDropoutFrames = 270;  // 3 s
constexpr double kContactMemoryS = 0.25;    // as tracking error counts joints (docs/metrics.md)

// Where each hand hovers while tracking is clean: above the table, beside the cube.
const std::array<Vec3, 2> kHome = {Vec3(-0.1, 0.85, -0.30), Vec3(0.1, 0.85, -0.30)};

// The hand placed so that its palm joint is at `palm`.
HandPose hand_with_palm_at(HandSide side, const Vec3& palm, const Quat& orientation, double curl) {
    const Vec3 palm_from_wrist =
        hand_pose(side, Vec3::Zero(), curl, orientation)[Joint::Palm].position;
    return hand_pose(side, palm - palm_from_wrist, curl, orientation);
}

// Palm against one side of the cube, pressed `depth` into it: with the other hand doing the
// same from the other side, the cube is squeezed between them.
HandPose squeezing(HandSide side, const Vec3& cube, double depth) {
    const double outward = side == HandSide::Right ? 1.0 : -1.0;
    // Palms (-Y) face the cube, fingers (-Z) point away from the body.
    const Quat facing(Eigen::AngleAxisd(-outward * std::numbers::pi / 2, Vec3::UnitZ()));
    const double reach =
        kStressCubeHalf + hand_pose(side, Vec3::Zero(), 0.0, facing).radii[index_of(Joint::Palm)];
    return hand_with_palm_at(side, cube + Vec3(outward * (reach - depth), 0, 0), facing, 0.5);
}

// How far `point` lies outside the stress bench's cube (0 inside it), m.
double outside_cube(const Vec3& point, const Pose& cube) {
    const Vec3 local = cube.inverse() * point;
    return (local.cwiseAbs() - Vec3::Constant(kStressCubeHalf)).cwiseMax(0.0).norm();
}

// A whole number >= 0 from all of `text`, or nullopt.
std::optional<std::uint64_t> whole(const std::string& text) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
        text.size() > 18) {
        return std::nullopt;
    }
    return std::stoull(text);
}

// One hand's ongoing pathologies.
struct HandTrouble {
    int dropout_frames = 0;
    int burst_frames = 0;
    double burst_m = 0.0;
};

}  // namespace

PathologyResult run_pathology(const DriveSettings& drive, std::uint64_t seed) {
    SimulationSettings settings;
    settings.drive = drive;
    StressBench b{settings};
    PathologyResult result;
    result.speed_limit = settings.max_body_speed;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    auto u = [&] { return uniform(rng); };
    auto pick = [&](int n) { return std::min(static_cast<int>(u() * n), n - 1); };

    double t = 0.0;
    std::array<std::array<double, kJointCount>, 2> last_contact_t;
    for (auto& hand : last_contact_t) hand.fill(-kInf);
    auto step = [&](const std::array<HandPose, 2>& ghosts) {
        b.sim.step_to(t, ghosts);
        ++result.frames;
        if (!b.sim.state_is_finite()) ++result.nonfinite_count;
        result.max_body_speed = std::max(result.max_body_speed, b.sim.last_max_body_speed());
        result.max_requested_speed =
            std::max(result.max_requested_speed, b.sim.last_max_requested_speed());
        for (HandSide side : kHandSides) {
            const PhysicalHandState& hand = b.sim.hand(side);
            for (std::size_t j = 0; j < kJointCount; ++j) {
                if (hand.in_contact[j]) last_contact_t[static_cast<int>(side)][j] = t;
            }
        }
    };

    std::array<HandTrouble, 2> trouble{};
    int squeeze_frames = 0, overlap_frames = 0;
    for (int frame = 0; frame < kPathologyFrames; ++frame) {
        t += u() < 0.05 ? kHitchS : kFrameS;
        if (squeeze_frames == 0 && overlap_frames == 0) {
            const double r = u();
            if (r < 0.02)
                squeeze_frames = 30 + pick(90);
            else if (r < 0.04)
                overlap_frames = 10 + pick(50);
        }
        const Vec3 cube = b.sim.body_state(b.cube)->pose.position;
        std::array<HandPose, 2> ghosts;
        for (HandSide side : kHandSides) {
            const int s = static_cast<int>(side);
            HandPose& g = ghosts[s];
            if (squeeze_frames > 0) {
                g = squeezing(side, cube, 0.01 + 0.02 * u());
            } else {
                // Both hands where the right one is, while they overlap.
                const Vec3 home = kHome[overlap_frames > 0 ? 1 : s];
                g = hand_pose(side, home + Vec3(0.05 * std::sin(t * 3), -0.1 * u(), 0), u());
            }
            HandTrouble& h = trouble[s];
            const double r = u();
            if (r < 0.03) {  // teleport up to 10 m
                g = hand_pose(side, Vec3(20 * u() - 10, 10 * u(), 20 * u() - 10), 0.2);
            } else if (r < 0.05) {  // into the cube, or into the table
                const Vec3 inside = u() < 0.5 ? cube : Vec3(cube.x(), 0.71, cube.z());
                g = hand_with_palm_at(side, inside, Quat::Identity(), u());
            } else if (r < 0.10) {  // NaN or ±Inf in any component of any joint
                const auto j = static_cast<std::size_t>(pick(kJointCount));
                const double bad = std::array{kNaN, kInf, -kInf}[static_cast<std::size_t>(pick(3))];
                const int component = pick(8);
                if (component < 3)
                    g.joints[j].position[component] = bad;
                else if (component < 7)
                    g.joints[j].orientation.coeffs()[component - 3] = bad;
                else
                    g.radii[j] = bad;
            } else if (r < 0.12) {
                g.joints[static_cast<std::size_t>(pick(kJointCount))]
                    .orientation.coeffs()
                    .setZero();
            } else if (r < 0.15) {  // non-unit quaternions, 1e-3 to 1e3 long
                const double length = std::pow(10.0, 6 * u() - 3);
                for (Pose& p : g.joints) p.orientation.coeffs() *= length;
            } else if (r < 0.18 && h.dropout_frames == 0) {  // one frame to 3 s, log-uniform
                h.dropout_frames = static_cast<int>(
                    std::lround(std::exp(u() * std::log(double{kLongestDropoutFrames}))));
            } else if (r < 0.21 && h.burst_frames == 0) {
                h.burst_frames = 1 + pick(10);
                h.burst_m = 0.005 + 0.045 * u();
            }
            if (h.burst_frames > 0) {
                --h.burst_frames;
                std::uniform_real_distribution<double> noise(-h.burst_m, h.burst_m);
                for (Pose& p : g.joints) p.position += Vec3(noise(rng), noise(rng), noise(rng));
            }
            if (h.dropout_frames > 0) {
                --h.dropout_frames;
                g.active = false;
            }
        }
        squeeze_frames = std::max(0, squeeze_frames - 1);
        overlap_frames = std::max(0, overlap_frames - 1);
        step(ghosts);
    }

    // Recovery: clean tracking of both hands above the table.
    const std::array<HandPose, 2> clean = {hand_pose(HandSide::Left, kHome[0], 0.2),
                                           hand_pose(HandSide::Right, kHome[1], 0.2)};
    result.recovery_s = kInf;
    const double stopped = t;
    const int window = static_cast<int>(std::lround(kRecoveryWindowS / kFrameS));
    for (int frame = 1; frame <= window; ++frame) {
        t = stopped + frame * kFrameS;
        step(clean);
        bool recovered = true;
        const Pose cube = b.sim.body_state(b.cube)->pose;
        for (HandSide side : kHandSides) {
            const int s = static_cast<int>(side);
            const PhysicalHandState& hand = b.sim.hand(side);
            int counted = 0;
            for (std::size_t j = 0; j < kJointCount; ++j) {
                if (t - last_contact_t[s][j] <= kContactMemoryS) continue;
                // The cube may have come to rest under the clean hand: a joint whose ghost reaches
                // within its radius and kRecoveredM of it may rest on it, or be held off it
                // without touching (a part nearing a movable object, PhysicalHand::contact_aim).
                if (outside_cube(clean[s].joints[j].position, cube) <
                    clean[s].radii[j] + kRecoveredM)
                    continue;
                ++counted;
                const double error =
                    (hand.joints.joints[j].position - clean[s].joints[j].position).norm();
                recovered = recovered && error < kRecoveredM;
            }
            // A hand held everywhere by contact has not shown that it recovered.
            recovered = recovered && counted > 0;
        }
        if (recovered) {
            result.recovery_s = frame * kFrameS;
            break;
        }
    }
    result.speed_clamps = b.sim.guard_counters().speed_clamps;
    return result;
}

bool passed(const PathologyResult& r, const DriveSettings& drive) {
    return r.nonfinite_count == 0 && r.max_body_speed <= r.speed_limit &&
           (drive.law == DriveLaw::Explicit || r.max_requested_speed <= r.speed_limit) &&
           r.recovery_s <= kMaxRecoveryS;
}

StressPlan stress_plan_from_env() {
    StressPlan plan;
    if (const char* seeds = std::getenv("PHYSHAND_STRESS_SEEDS")) {
        const std::string text = seeds;
        const auto dash = text.find('-');
        const auto first = whole(text.substr(0, dash));
        const auto last = dash == std::string::npos ? first : whole(text.substr(dash + 1));
        if (!first || !last || *last < *first) {
            throw std::invalid_argument("PHYSHAND_STRESS_SEEDS must be A or A-B (A <= B), not \"" +
                                        text + "\"");
        }
        plan.first_seed = *first;
        plan.last_seed = *last;
    }
    if (const char* seconds = std::getenv("PHYSHAND_STRESS_SECONDS")) {
        const auto s = whole(seconds);
        if (!s) {
            throw std::invalid_argument("PHYSHAND_STRESS_SECONDS must be a whole number, not \"" +
                                        std::string(seconds) + "\"");
        }
        plan.seconds = static_cast<double>(*s);
    }
    if (const char* drive = std::getenv("PHYSHAND_STRESS_DRIVE")) {
        if (!find_drive(drive)) {
            throw std::invalid_argument("PHYSHAND_STRESS_DRIVE: no drive \"" + std::string(drive) +
                                        "\"");
        }
        plan.drive = drive;
    }
    return plan;
}

}  // namespace physhand::testing
