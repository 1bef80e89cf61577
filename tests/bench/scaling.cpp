// physhand-scaling: physics cost against the number of dynamic colliders, with both hands
// in contact with a pile, both far from everything, and one hand near; and what gating and
// sleeping save on the sample scenes (each switched off, as a ratio).
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "bench_options.h"
#include "quantile.h"
#include "raw_bullet_floor.h"
#include "run_metrics.h"
#include "scene.h"
#include "scene_run.h"
#include "svg_plot.h"

namespace fs = std::filesystem;
using namespace physhand;

namespace {

const std::vector<int> kCounts = {0, 10, 50, 200, 1000};

enum class Placement { BothInContact, BothFar, OneNear };
const char* name_of(Placement p) {
    switch (p) {
        case Placement::BothInContact:
            return "both hands in contact";
        case Placement::BothFar:
            return "both hands far (gated)";
        case Placement::OneNear:
            return "one hand near";
    }
    return "";
}

Collider box(const std::string& id, const Vec3& c, const Vec3& half, Motion motion, double mass) {
    Collider b;
    b.id = id;
    b.shape.half_extents = half;
    b.motion = motion;
    b.mass = mass;
    b.pose.position = c;
    return b;
}

// A hand coming down from 10 cm above the pile (where it is gated, so it wakes clear of the
// cubes and meets them with contacts on), pressing 2 cm into its top and sweeping through it.
HandScript pressing_hand(double x, double top, bool near) {
    HandScript h;
    h.interpolation = Interpolation::Smooth;
    for (int k = 0; k <= 12; ++k) {
        Keyframe key;
        key.t = 0.5 * k;
        const double y = !near ? top + 0.6 : k == 0 ? top + 0.1 : top - 0.02;
        key.wrist.position = Vec3(x + 0.05 * std::sin(k), y, -0.4 + 0.04 * std::cos(k));
        key.articulation.curl.fill(0.2);
        h.keyframes.push_back(key);
    }
    return h;
}

// n cubes of 4 cm in a square pile on a 2 m table, layered as needed.
Scene pile_scene(int n, Placement placement) {
    Scene s;
    s.name = "pile_" + std::to_string(n);
    s.duration_s = 6.0;
    s.colliders.push_back(
        box("table", Vec3(0, 0.725, -0.4), Vec3(1.0, 0.025, 1.0), Motion::Static, 0));
    const int side = std::max(1, static_cast<int>(std::ceil(std::sqrt(std::min(n, 400)))));
    double top = 0.75;
    for (int i = 0; i < n; ++i) {
        const int layer = i / (side * side), row = (i / side) % side, col = i % side;
        const Vec3 c(-0.021 * (side - 1) + 0.042 * col, 0.77 + 0.04 * layer,
                     -0.4 - 0.021 * (side - 1) + 0.042 * row);
        s.colliders.push_back(
            box("cube" + std::to_string(i), c, Vec3::Constant(0.02), Motion::Dynamic, 0.05));
        top = std::max(top, c.y() + 0.02);
    }
    // Palms side by side over the middle of the pile.
    s.hands[static_cast<int>(HandSide::Left)] =
        pressing_hand(-0.06, top, placement == Placement::BothInContact);
    s.hands[static_cast<int>(HandSide::Right)] =
        pressing_hand(0.06, top, placement != Placement::BothFar);
    return s;
}

struct Timing {
    double step_us = 0.0;              // median over the runs of each run's median
    std::array<double, 2> touching{};  // by HandSide: share of frames it touched a cube
};

// Each run `repeat` times, the repeats going round all of them in turn after one run left
// out, so that a busy moment of the machine does not fall on one of them alone.
std::vector<Timing> timings(const std::vector<std::pair<Scene, RunOptions>>& runs, int repeat) {
    std::vector<Timing> out(runs.size());
    std::vector<std::vector<double>> medians(runs.size());
    const auto timed = [](const std::pair<Scene, RunOptions>& run) {
        RunOptions options = run.second;
        options.measure_shown_depth = false;
        return run_scene(run.first, options);
    };
    if (!runs.empty()) timed(runs[0]);
    for (int i = 0; i < repeat; ++i) {
        for (std::size_t r = 0; r < runs.size(); ++r) {
            const MetricsSummary m = timed(runs[r]).metrics;
            medians[r].push_back(m.step_us_median);
            for (int side = 0; side < 2; ++side) {
                out[r].touching[side] =
                    static_cast<double>(m.frames_touching_bodies[side]) / m.frames;
            }
        }
    }
    for (std::size_t r = 0; r < runs.size(); ++r) out[r].step_us = quantile(medians[r], 0.5);
    return out;
}

std::string fmt(double v, const char* f = "%.0f") {
    char buf[32];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

}  // namespace

int main(int argc, char** argv) {
    // --profile-pile N: plays the both-hands pile of N cubes once and writes nothing, for a
    // profiler to watch (scripts/profile-piles.sh).
    if (argc == 3 && std::string(argv[1]) == "--profile-pile") {
        RunOptions profiled;
        profiled.measure_shown_depth = false;  // only the step is profiled
        run_scene(pile_scene(std::atoi(argv[2]), Placement::BothInContact), profiled);
        return 0;
    }
    const auto options = bench::parse_options(argc, argv, "physhand-scaling", PHYSHAND_SCENES_DIR);
    if (!options) return 2;
    const fs::path& out = options->out;
    const fs::path& scenes_dir = options->scenes_dir;
    const int repeat = options->repeat;
    std::ofstream csv(out / "scaling.csv");
    csv << "placement,dynamic_colliders,step_us_median,left_touching,right_touching\n";
    std::ofstream floor_csv(out / "scaling_floor.csv");
    floor_csv << "dynamic_colliders,both_hands_in_contact_us,both_hands_far_us\n";
    std::ofstream md(out / "scaling.md");
    md << "\n## Scaling\n\nstep_us median (default drive) against the number of dynamic 4 cm cubes "
          "piled on a table; the hands press into the pile side by side and sweep through it for "
          "6 s (the pile starts at rest, and sleeps once settled unless a hand is in it). In "
          "brackets: the share of frames in which the left / right hand touched a cube. The "
          "last two columns are the floor of the present design under the both-hands-in-contact "
          "and both-hands-far scenes: the same table and cubes in a plain Bullet world with "
          "Bullet's defaults, one step a frame, each hand a kinematic palm box and finger "
          "capsules set to its ghost (tests/bench/raw_bullet_floor); what lies above it is "
          "physhand's own cost.\n\n"
          "![scaling](bench/scaling.svg)\n\n| dynamic colliders |";
    for (Placement p : {Placement::BothInContact, Placement::OneNear, Placement::BothFar})
        md << ' ' << name_of(p) << " |";
    md << " raw Bullet, both in contact | raw Bullet, both far |\n|---|---|---|---|---|---|\n";
    SvgPlot plot("Scaling: cost against dynamic colliders", "dynamic colliders (+1)",
                 "step_us median", "colliders");
    std::vector<std::vector<SvgPlot::Point>> series(3);
    constexpr std::array kPlacements = {Placement::BothInContact, Placement::OneNear,
                                        Placement::BothFar};
    for (int n : kCounts) {
        md << "| " << n << " |";
        std::vector<std::pair<Scene, RunOptions>> runs;
        for (Placement p : kPlacements) runs.emplace_back(pile_scene(n, p), RunOptions{});
        // Large piles take minutes a run; their timings need no repeats to be seen.
        const std::vector<Timing> t = timings(runs, n >= 200 ? 1 : repeat);
        for (std::size_t k = 0; k < kPlacements.size(); ++k) {
            csv << '"' << name_of(kPlacements[k]) << "\"," << n << ',' << t[k].step_us << ','
                << t[k].touching[0] << ',' << t[k].touching[1] << '\n';
            md << ' ' << fmt(t[k].step_us) << " (" << fmt(100 * t[k].touching[0]) << " / "
               << fmt(100 * t[k].touching[1]) << " %) |";
            series[k].push_back({n + 1.0, t[k].step_us, std::to_string(n), false, false});
        }
        floor_csv << n;
        for (std::size_t k : {std::size_t{0}, std::size_t{2}}) {
            std::vector<double> floor;
            for (int i = 0; i < (n >= 200 ? 1 : repeat); ++i)
                floor.push_back(bench::raw_bullet_step_us(runs[k].first));
            const double floor_us = quantile(floor, 0.5);
            floor_csv << ',' << floor_us;
            md << ' ' << fmt(floor_us) << " |";
        }
        floor_csv << '\n';
        md << '\n';
    }
    for (std::size_t k = 0; k < kPlacements.size(); ++k)
        plot.add_series(name_of(kPlacements[k]), series[k]);
    std::ofstream(out / "scaling.svg") << plot.render();

    md << "\n## What skipping saves\n\nstep_us median with each skip switched off, divided by the "
          "same run with everything on (default drive; higher is more saved).\n\n| scene | on "
          "(µs) | no gating | no sleeping | neither |\n|---|---|---|---|---|\n";
    std::vector<std::pair<std::string, Scene>> cases = {
        {"pile of 200, both hands far", pile_scene(200, Placement::BothFar)},
        {"pile of 50, one hand near", pile_scene(50, Placement::OneNear)},
        {"pile of 50, both hands in contact", pile_scene(50, Placement::BothInContact)}};
    for (const char* name :
         {"free_motion", "press_table", "lift_hold", "stack", "throw", "sphere"}) {
        cases.emplace_back(name, load_scene(scenes_dir / (std::string(name) + ".json")));
    }
    for (const auto& [label, scene] : cases) {
        RunOptions on, no_gating, no_sleeping, neither;
        no_gating.gating = neither.gating = false;
        no_sleeping.sleeping = neither.sleeping = false;
        const std::vector<Timing> t = timings(
            {{scene, on}, {scene, no_gating}, {scene, no_sleeping}, {scene, neither}}, repeat);
        md << "| " << label << " | " << fmt(t[0].step_us) << " |";
        for (std::size_t k = 1; k < t.size(); ++k)
            md << ' ' << fmt(t[k].step_us / t[0].step_us, "%.2f") << "× |";
        md << '\n';
    }
    std::cout << "wrote " << (out / "scaling.csv") << ", " << (out / "scaling.md")
              << " and scaling.svg\n";
    return 0;
}
