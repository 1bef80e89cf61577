// physhand-robustness: variant_success (docs/metrics.md). Plays every variant of the paper scenes
// and lift_hold (scene/scene_variants) for every drive and writes the success per family
// and overall, each failure with its cause, as CSV and Markdown, then the squeeze sweep of
// lift_hold, the mass sweep, the dropout sweep and the off-centre grasp sweep of every task.
// `--repeat N` is the number of seeds of the noise, tracking and dropout families; `--shifts N`
// plays each variant N times, the scene moved by 0, 0.44, 0.87 ... mm each time
// (scene/scene_variants shifted): whether a contact-rich run succeeds can turn on the last bit of a
// float, so a change is judged on many plays of each variant, not one.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_options.h"
#include "scene.h"
#include "scene_run.h"
#include "scene_variants.h"
#include "success_interval.h"

namespace fs = std::filesystem;
using namespace physhand;

namespace {

const std::vector<std::string> kScenes = {"throw", "sphere", "displacement", "stack", "lift_hold"};
// Each drive at its own substeps, the default also at 2 and 4 (what more run time buys), and
// the reference at the 8 its stability needs on 15 g bodies.
const std::vector<std::pair<std::string, int>> kConfigurations = {
    {"bones", 1}, {"bones", 2}, {"bones", 4}, {"implicit", 2}, {"paper", 4}, {"paper", 8}};

// The mass sweep's factors: the 4 cm, 80 g cubes the hand holds from 24 g (light plastic) to
// 400 g (nearly solid iron), and everything else that moves with them.
const std::vector<double> kMassFactors = {0.3, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0};

// The dropout sweep: how long the hand is lost, and how often a loss starts through a task.
const std::vector<double> kLossLengths = {0.3, 0.5, 0.7, 0.9};  // s
constexpr double kLossSpacing = 0.5;                            // s

// The off-centre grasp sweep: how far the objects the hand handles lie from where the script
// grasps them (by as much as a person's aim at a centre misses), along each horizontal axis
// either way.
const std::vector<double> kGraspOffsets = {0.003, 0.006};  // m
const std::vector<Vec3> kGraspDirections = {Vec3::UnitX(), -Vec3::UnitX(), Vec3::UnitZ(),
                                            -Vec3::UnitZ()};

// The k-th play's offset: sub-millimetre, along no axis.
Vec3 shift_of(int k) {
    return Vec3(0.00037, 0.0, -0.00023) * k;
}

// `scene` played at each of the first `shifts` shifts, added to `plays`.
void add_shifted(std::vector<Scene>& plays, const Scene& scene, int shifts) {
    for (int shift = 0; shift < shifts; ++shift) plays.push_back(shifted(scene, shift_of(shift)));
}

// Where a run left the dynamic body `id`.
Vec3 final_position(const RunResult& r, const std::string& id) {
    const auto body = std::find_if(r.bodies.begin(), r.bodies.end(),
                                   [&](const auto& b) { return b.first == id; });
    if (body == r.bodies.end()) throw std::runtime_error("no body " + id);
    return body->second.position;
}

struct Tally {
    int played = 0;
    int passed = 0;
};

// The share, then the count and where the share lies at 95 %: the variants are few.
std::string percent(const Tally& t) {
    const SuccessInterval interval = success_interval(t.passed, t.played);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.0f %% (%d/%d; %.0f-%.0f %%)",
                  t.played ? 100.0 * t.passed / t.played : 0.0, t.passed, t.played,
                  100.0 * interval.low, 100.0 * interval.high);
    return buffer;
}

// What failed: every predicate that did not hold, with what it measured.
std::string cause_of(const RunResult& r) {
    std::string cause;
    for (const PredicateResult& p : r.predicates) {
        if (p.passed) continue;
        if (!cause.empty()) cause += "; ";
        cause += p.type + " " + p.subject + ": " + p.detail;
    }
    if (r.metrics.nonfinite_count > 0) cause += "; non-finite state";
    return cause;
}

// How a column ("drive/substeps") plays a scene.
RunOptions run_of(const std::string& column) {
    const auto slash = column.find('/');
    RunOptions run;
    run.drive = column.substr(0, slash);
    run.substeps = std::stoi(column.substr(slash + 1));
    return run;
}

// A sweep's cell: how many of the plays `plays_of` makes of each task succeeded in `column`,
// then the tasks that failed in any, with how many of their plays succeeded.
std::string sweep_cell(const std::vector<Scene>& tasks, const std::string& column,
                       const std::function<std::vector<Scene>(const Scene&)>& plays_of) {
    Tally all;
    std::string failed;
    for (const Scene& task : tasks) {
        Tally t;
        for (const Scene& play : plays_of(task)) {
            ++t.played;
            t.passed += run_scene(play, run_of(column)).success;
        }
        all.played += t.played;
        all.passed += t.passed;
        if (t.passed < t.played) {
            failed += (failed.empty() ? " (" : ", ") + task.name + " " + std::to_string(t.passed) +
                      "/" + std::to_string(t.played);
        }
    }
    return std::to_string(all.passed) + '/' + std::to_string(all.played) +
           (failed.empty() ? "" : failed + ")");
}

// The task with its right hand lost for `length` seconds, once for each start kLossSpacing
// apart from 1 s on, the loss ending at least half a second before the task does.
std::vector<Scene> with_losses(const Scene& task, double length) {
    std::vector<Scene> plays;
    for (double from = 1.0; from + length < task.duration_s - 0.5; from += kLossSpacing) {
        Scene play = task;
        play.tracking.dropouts.push_back({HandSide::Right, from, from + length});
        plays.push_back(std::move(play));
    }
    return plays;
}

// A table's head: its first column's title, then one column per drive configuration.
std::string table_head(const std::string& first, const std::vector<std::string>& columns) {
    std::string head = "| " + first + " |";
    for (const std::string& c : columns) head += ' ' + c + " |";
    head += "\n|---|";
    for (std::size_t i = 0; i < columns.size(); ++i) head += "---|";
    return head + '\n';
}

std::string csv_field(const std::string& text) {
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace

int main(int argc, char** argv) {
    const auto options =
        bench::parse_options(argc, argv, "physhand-robustness", PHYSHAND_SCENES_DIR, true, true);
    if (!options) return 2;
    const VariantOptions variant_options{.seeds = options->repeat};

    std::ofstream csv(options->out / "robustness.csv");
    csv << "scene,family,variant,drive,substeps,success,max_penetration_mm,max_shown_depth_mm,"
           "max_body_speed,"
           "reseats,cause,adapted,shift\n";
    std::vector<std::string> columns;
    std::map<std::string, std::map<std::string, Tally>> tallies;  // column -> family -> tally
    std::map<std::string, std::vector<std::string>> failures;     // column -> lines
    std::vector<std::string> families;
    std::vector<std::string> adapted;  // "variant: how its motion was adapted"
    for (const std::string& name : kScenes) {
        if (!bench::selected(options->only_scenes, name)) continue;
        const Scene base = load_scene(options->scenes_dir / (name + ".json"));
        for (const SceneVariant& v : scene_variants(base, variant_options)) {
            if (std::find(families.begin(), families.end(), v.family) == families.end())
                families.push_back(v.family);
            if (!v.adapted.empty()) adapted.push_back(v.scene.name + ": " + v.adapted);
            for (const auto& [drive, substeps] : kConfigurations) {
                if (!bench::selected(options->only_drives, drive)) continue;
                if (!bench::selected(options->only_substeps, substeps)) continue;
                for (int shift = 0; shift < options->shifts; ++shift) {
                    RunOptions run;
                    run.drive = drive;
                    run.substeps = substeps;
                    const RunResult r = run_scene(shifted(v.scene, shift_of(shift)), run);
                    const std::string column = drive + "/" + std::to_string(substeps);
                    if (std::find(columns.begin(), columns.end(), column) == columns.end())
                        columns.push_back(column);
                    for (const std::string& key : {v.family, std::string("overall")}) {
                        Tally& t = tallies[column][key];
                        ++t.played;
                        t.passed += r.success ? 1 : 0;
                    }
                    const std::string cause = r.success ? "" : cause_of(r);
                    if (!r.success) {
                        failures[column].push_back(
                            v.scene.name + (shift ? " (shift " + std::to_string(shift) + ")" : "") +
                            ": " + cause);
                    }
                    csv << name << ',' << v.family << ',' << v.name << ',' << drive << ','
                        << substeps << ',' << (r.success ? "true" : "false") << ','
                        << r.metrics.max_penetration_mm << ',' << r.metrics.max_shown_depth_mm
                        << ',' << r.metrics.max_body_speed << ',' << r.guards.reseats << ','
                        << csv_field(cause) << ',' << csv_field(v.adapted) << ',' << shift << '\n';
                }
            }
        }
    }

    std::ostringstream md;
    md << table_head("family", columns);
    families.push_back("overall");
    for (const std::string& family : families) {
        md << "| " << (family == "overall" ? "**overall**" : family) << " |";
        for (const std::string& c : columns) md << ' ' << percent(tallies[c][family]) << " |";
        md << '\n';
    }
    for (const std::string& c : columns) {
        md << "\nFailures of " << c << ": " << failures[c].size()
           << (failures[c].empty() ? "." : "") << "\n\n";
        for (const std::string& f : failures[c]) md << "- " << f << '\n';
    }
    md << "\nVariants whose motion was adapted: " << adapted.size() << (adapted.empty() ? "." : "")
       << "\n\n";
    for (const std::string& a : adapted) md << "- " << a << '\n';
    md << "\n### Squeeze\n\nsqueeze_penetration_mm (docs/metrics.md): lift_hold with the four "
          "fingers' final curl raised from 0.3 to 1.0, max_penetration_mm (in brackets "
          "max_shown_depth_mm, how deep the hand as shown went), whether the cube stayed held "
          "and, if it did, squeeze_push_mm: how far from the unsqueezed cube it ends.\n\n"
       << table_head("final curl", columns);
    if (bench::selected(options->only_scenes, std::string("lift_hold"))) {
        const Scene lift = load_scene(options->scenes_dir / "lift_hold.json");
        std::vector<Vec3> unsqueezed;
        for (const std::string& c : columns)
            unsqueezed.push_back(final_position(run_scene(lift, run_of(c)), "cube"));
        for (double curl = 0.3; curl < 1.05; curl += 0.1) {
            md << "| " << std::to_string(curl).substr(0, 3) << " |";
            for (std::size_t i = 0; i < columns.size(); ++i) {
                const RunResult r = run_scene(squeezed(lift, curl), run_of(columns[i]));
                char cell[96];
                if (r.success) {
                    std::snprintf(cell, sizeof cell,
                                  " %.2f mm (shown %.2f mm), held, pushed %.0f mm |",
                                  r.metrics.max_penetration_mm, r.metrics.max_shown_depth_mm,
                                  1e3 * (final_position(r, "cube") - unsqueezed[i]).norm());
                } else {
                    std::snprintf(cell, sizeof cell, " %.2f mm (shown %.2f mm), **dropped** |",
                                  r.metrics.max_penetration_mm, r.metrics.max_shown_depth_mm);
                }
                md << cell;
            }
            md << '\n';
        }
    }
    md << "\n### Mass\n\nEach task with every dynamic object's mass times the factor, the "
          "motion unchanged (scene/scene_variants heavier), played at each of the "
       << options->shifts
       << " shifts: how many plays succeeded, then the tasks that failed in any, with how many "
          "of their plays succeeded.\n\n"
       << table_head("mass", columns);
    std::vector<Scene> tasks;
    for (const std::string& name : kScenes) {
        if (bench::selected(options->only_scenes, name))
            tasks.push_back(load_scene(options->scenes_dir / (name + ".json")));
    }
    for (double factor : kMassFactors) {
        md << "| x" << factor << " |";
        for (const std::string& c : columns) {
            md << ' ' << sweep_cell(tasks, c, [&](const Scene& task) {
                std::vector<Scene> plays;
                add_shifted(plays, heavier(task, factor), options->shifts);
                return plays;
            }) << " |";
        }
        md << '\n';
    }
    md << "\n### Dropouts\n\nEach task with the hand lost once for 0.3 to 0.9 s, the loss "
          "starting at 1 s and then every "
       << kLossSpacing
       << " s for as long as it ends half a second before the task does (the robustness "
          "family's losses last 300 ms): how many plays succeeded, then the tasks that failed "
          "in any, with how many of their plays succeeded. A loss over a release (the throw's, "
          "the sphere's flick) keeps the fingers closed through it, as the hand last was.\n\n"
       << table_head("lost for", columns);
    for (double length : kLossLengths) {
        md << "| " << length << " s |";
        for (const std::string& c : columns) {
            md << ' '
               << sweep_cell(tasks, c, [&](const Scene& task) { return with_losses(task, length); })
               << " |";
        }
        md << '\n';
    }
    md << "\n### Off-centre grasps\n\nEach task with the objects its hand handles lying off "
          "where the script grasps them (scene/scene_variants grasped_off_centre), along +x, -x, "
          "+z and -z, the motion unchanged, as a person's grasp lands beside the centre they "
          "aimed at, played at each of the "
       << options->shifts
       << " shifts: how many plays succeeded, then the tasks that failed in any, with how many "
          "of their plays succeeded. What the hand carries to a place (the displacement task's "
          "hole) arrives off it by as much.\n\n"
       << table_head("off by", columns);
    for (double offset : kGraspOffsets) {
        md << "| " << offset * 1e3 << " mm |";
        for (const std::string& c : columns) {
            md << ' ' << sweep_cell(tasks, c, [&](const Scene& task) {
                std::vector<Scene> plays;
                for (const Vec3& direction : kGraspDirections)
                    add_shifted(plays, grasped_off_centre(task, offset * direction),
                                options->shifts);
                return plays;
            }) << " |";
        }
        md << '\n';
    }
    std::ofstream(options->out / "robustness.md") << md.str();
    std::cout << md.str();
    return 0;
}
