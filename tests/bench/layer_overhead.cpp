// overhead_ns (docs/metrics.md): how much longer an OpenXR call takes through the physhand
// layer than straight to the runtime, measured in one process through the real loader and
// the simulated runtime. Each benchmark creates its own instance (the loader allows one at
// a time), with the implicit layer disabled by DISABLE_XR_APILAYER_PHYSHAND_physical_hands=1
// (which the loader reads at instance creation) or enabled.
//
//   xrLocateSpace          a call the layer does not intercept: it hands the app the
//                          runtime's own function, so the overhead should be nil.
//   xrLocateHandJointsEXT  intercepted. Gated: the only collider is 2 m from the hand, so
//                          the layer returns the runtime's joints and steps nothing. In contact:
//                          the scene's hand rests pressed on a static box created through the
//                          extension, so every call steps the physics.
//   xrEndFrame             intercepted, in a Vulkan session (on lavapipe unless
//                          VK_ICD_FILENAMES names another driver) that shows a projection
//                          layer each frame. With the overlay (the layer's default) each frame
//                          steps the simulation and draws the hands; without it (the config
//                          turns it off) the frame passes through. Timed per whole frame
//                          (xrWaitFrame, xrBeginFrame, the swapchain image's acquire, wait and
//                          release, xrEndFrame): the layer intercepts only xrEndFrame of these,
//                          so the difference is its cost.
//
// After the runs, a Markdown table of medians and overhead_ns goes to stdout, or to FILE with
// --summary FILE. CPU time per call, which another process on the machine disturbs less
// than wall time; but wall time for xrEndFrame, as the overlay's drawing runs on lavapipe's
// own threads (and would on a GPU), which the calling thread's CPU time leaves out. Google
// Benchmark's flags apply, e.g. --benchmark_repetitions=5 for medians over repetitions,
// --benchmark_out=F.json --benchmark_out_format=json.
//
// Usage: physhand-overhead [--benchmark_...] [--summary FILE]

#include <benchmark/benchmark.h>
#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sim_app.h"

namespace {

using physhand::test::check;
using physhand::test::SimApp;
using physhand::test::xr;

// Frames before the check and the timing: pressing_hand.json's hand comes down for 1 s,
// then rests on the box (one already inside a collider when simulated passes through it).
constexpr int kSettleFrames = 135;
// The box under the hand: its top at y = 1 m, 2 cm above where the ghost palm stops.
constexpr XrVector3f kBoxHalfExtents = {0.15f, 0.05f, 0.15f};
constexpr XrVector3f kBoxCentre = {0.0f, 0.95f, -0.35f};
// Gated: the same box 2 m to the side, so the layer looks for colliders near the hand and
// finds none.
constexpr XrVector3f kFarBoxCentre = {2.0f, 0.95f, -0.35f};

enum class Path { Runtime, LayerGated, LayerContact, LayerOverlay, LayerNoOverlay };

// The layer's config that turns its overlay off, written once.
std::filesystem::path no_overlay_config() {
    static const std::filesystem::path path = [] {
        const auto file = std::filesystem::temp_directory_path() /
                          ("physhand-overhead-" + std::to_string(::getpid()) + ".json");
        std::ofstream(file) << R"({"overlay": false})";
        return file;
    }();
    return path;
}

SimApp make_app(Path path, bool vulkan = false) {
    return SimApp(
        {.layer = path != Path::Runtime,
         .extension = path == Path::LayerContact || path == Path::LayerGated,
         .scene = PHYSHAND_OVERHEAD_SCENE,
         .config = path == Path::LayerNoOverlay ? no_overlay_config() : std::filesystem::path(),
         .vulkan = vulkan});
}

void create_box(const SimApp& app, XrTime time, const XrVector3f& centre) {
    auto info =
        xr<XrPhysicalColliderCreateInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND);
    info.shape = XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND;
    info.motion = XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND;
    info.halfExtents = kBoxHalfExtents;
    info.friction = 0.8f;
    info.space = app.space(XR_REFERENCE_SPACE_TYPE_STAGE);
    info.pose = {{0.0f, 0.0f, 0.0f, 1.0f}, centre};
    info.time = time;
    XrPhysicalColliderPHYSHAND box = XR_NULL_HANDLE;
    check(app.function<PFN_xrCreatePhysicalColliderPHYSHAND>("xrCreatePhysicalColliderPHYSHAND")(
              app.session(), &info, &box),
          "xrCreatePhysicalColliderPHYSHAND");
}

// xrLocateHandJointsEXT of the right hand in STAGE, as an app calls it once per frame.
class RightHand {
  public:
    explicit RightHand(const SimApp& app)
        : locate_(app.function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")),
          tracker_(app.hand_tracker(XR_HAND_RIGHT_EXT)) {
        info_.baseSpace = app.space(XR_REFERENCE_SPACE_TYPE_STAGE);
        locations_.jointCount = XR_HAND_JOINT_COUNT_EXT;
        locations_.jointLocations = joints_.data();
    }

    XrResult locate(XrTime time) {
        info_.time = time;
        return locate_(tracker_, &info_, &locations_);
    }

    // The layer's state of the hand at `time`, read with its structure chained (only for
    // the checks: the timed calls chain nothing).
    XrHandJointsPhysicalStatePHYSHAND physical_state(XrTime time) {
        auto state =
            xr<XrHandJointsPhysicalStatePHYSHAND>(XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND);
        state.jointCount = XR_HAND_JOINT_COUNT_EXT;
        state.inContact = contacts_.data();
        locations_.next = &state;
        const XrResult result = locate(time);
        locations_.next = nullptr;
        check(result, "xrLocateHandJointsEXT");
        return state;
    }

    bool any_contact() const {
        return std::any_of(contacts_.begin(), contacts_.end(), [](XrBool32 c) { return c; });
    }

  private:
    PFN_xrLocateHandJointsEXT locate_;
    XrHandTrackerEXT tracker_;
    XrHandJointsLocateInfoEXT info_ =
        xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
    XrHandJointLocationsEXT locations_ =
        xr<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
    std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT> joints_{};
    std::array<XrBool32, XR_HAND_JOINT_COUNT_EXT> contacts_{};
};

void locate_space(benchmark::State& state, Path path) {
    const SimApp app = make_app(path);
    const XrSpace view = app.space(XR_REFERENCE_SPACE_TYPE_VIEW);
    const XrSpace stage = app.space(XR_REFERENCE_SPACE_TYPE_STAGE);
    const XrTime time = app.frame().predictedDisplayTime;
    auto location = xr<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    check(xrLocateSpace(view, stage, time, &location), "xrLocateSpace");
    for (auto _ : state) {
        benchmark::DoNotOptimize(xrLocateSpace(view, stage, time, &location));
    }
}

// Each call locates the hand one display period after the last, as an app does once per
// frame, so the layer advances its simulation on every call (a second locate at the same
// time steps nothing). The frame calls themselves stay out of the loop: the layer does not
// intercept them, and the simulated runtime answers for any time, so they would only add
// the same cost, and noise, to both sides of the difference.
void locate_hand(benchmark::State& state, Path path) {
    const SimApp app = make_app(path);
    const XrFrameState frame = app.frame();
    XrTime time = frame.predictedDisplayTime;
    if (path == Path::LayerContact) create_box(app, time, kBoxCentre);
    if (path == Path::LayerGated) create_box(app, time, kFarBoxCentre);
    RightHand hand(app);
    for (int i = 0; i < kSettleFrames; ++i) {
        time += frame.predictedDisplayPeriod;
        check(hand.locate(time), "xrLocateHandJointsEXT");
    }
    // Gated or in contact, as the benchmark says, before and after the timed calls.
    const auto as_named = [&] {
        if (path == Path::Runtime) return true;
        const bool simulated = hand.physical_state(time).isSimulated;
        return simulated == (path == Path::LayerContact) && simulated == hand.any_contact();
    };
    if (!as_named()) {
        state.SkipWithError("the hand is not gated or in contact as named");
        return;
    }
    for (auto _ : state) {
        time += frame.predictedDisplayPeriod;
        benchmark::DoNotOptimize(hand.locate(time));
    }
    if (!as_named()) state.SkipWithError("the hand changed from gated or in contact as named");
}

// One whole frame per iteration, as a Vulkan app renders it.
void end_frame(benchmark::State& state, Path path) {
    const SimApp app = make_app(path, true);
    for (auto _ : state) benchmark::DoNotOptimize(app.frame());
}

struct Benchmark {
    const char* name;
    void (*run)(benchmark::State&, Path);
    Path path;
};

constexpr std::array<Benchmark, 8> kBenchmarks = {{
    {"xrLocateSpace/without_layer", locate_space, Path::Runtime},
    {"xrLocateSpace/with_layer", locate_space, Path::LayerGated},
    {"xrLocateHandJointsEXT/without_layer", locate_hand, Path::Runtime},
    {"xrLocateHandJointsEXT/with_layer/gated", locate_hand, Path::LayerGated},
    {"xrLocateHandJointsEXT/with_layer/contact", locate_hand, Path::LayerContact},
    {"xrEndFrame/without_layer", end_frame, Path::Runtime},
    {"xrEndFrame/with_layer/no_overlay", end_frame, Path::LayerNoOverlay},
    {"xrEndFrame/with_layer/overlay", end_frame, Path::LayerOverlay},
}};

enum class Clock { Cpu, Wall };

// The rows of the summary: benchmarks compared by name.
struct Comparison {
    const char* call;
    const char* what;
    const char* without_layer;
    const char* with_layer;
    Clock clock;
};

constexpr std::array<Comparison, 5> kComparisons = {{
    {"xrLocateSpace", "pass-through (not intercepted)", "xrLocateSpace/without_layer",
     "xrLocateSpace/with_layer", Clock::Cpu},
    {"xrLocateHandJointsEXT", "hand gated (no collider near it)",
     "xrLocateHandJointsEXT/without_layer", "xrLocateHandJointsEXT/with_layer/gated", Clock::Cpu},
    {"xrLocateHandJointsEXT", "hand in contact with a static box",
     "xrLocateHandJointsEXT/without_layer", "xrLocateHandJointsEXT/with_layer/contact", Clock::Cpu},
    {"xrEndFrame", "Vulkan session, overlay off (wall time)", "xrEndFrame/without_layer",
     "xrEndFrame/with_layer/no_overlay", Clock::Wall},
    {"xrEndFrame", "Vulkan session, overlay drawing the hand (wall time)",
     "xrEndFrame/without_layer", "xrEndFrame/with_layer/overlay", Clock::Wall},
}};

// Passes everything on to the display reporter that --benchmark_format chose, and keeps each
// benchmark's median CPU and wall time per iteration (its only run's without repetitions).
class MedianRecorder : public benchmark::BenchmarkReporter {
  public:
    explicit MedianRecorder(benchmark::BenchmarkReporter* display) : display_(display) {}

    bool ReportContext(const Context& context) override { return display_->ReportContext(context); }
    void ReportRuns(const std::vector<Run>& runs) override {
        display_->ReportRuns(runs);
        for (const Run& run : runs) {
            const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
            const bool only_run = run.run_type == Run::RT_Iteration && run.repetitions <= 1;
            if (!run.error_occurred && (median || only_run)) {
                medians_ns_[{run.run_name.function_name, Clock::Cpu}] = run.GetAdjustedCPUTime();
                medians_ns_[{run.run_name.function_name, Clock::Wall}] = run.GetAdjustedRealTime();
            }
        }
    }
    void Finalize() override { display_->Finalize(); }

    std::optional<double> median_ns(const std::string& name, Clock clock) const {
        const auto it = medians_ns_.find({name, clock});
        return it == medians_ns_.end() ? std::nullopt : std::optional<double>(it->second);
    }

  private:
    benchmark::BenchmarkReporter* display_;  // owned by the benchmark library
    std::map<std::pair<std::string, Clock>, double> medians_ns_;
};

std::string summary(const MedianRecorder& recorder) {
    std::ostringstream out;
    out << std::fixed << std::setprecision(0);
    out << "| call | case | without layer (ns) | with layer (ns) | overhead_ns |\n"
        << "|---|---|---:|---:|---:|\n";
    for (const Comparison& c : kComparisons) {
        const std::optional<double> without = recorder.median_ns(c.without_layer, c.clock);
        const std::optional<double> with = recorder.median_ns(c.with_layer, c.clock);
        if (!without || !with) continue;  // filtered out, or skipped with an error
        out << "| " << c.call << " | " << c.what << " | " << *without << " | " << *with << " | "
            << std::showpos << *with - *without << std::noshowpos << " |\n";
    }
    return out.str();
}

}  // namespace

int main(int argc, char** argv) {
#ifdef PHYSHAND_LAVAPIPE_ICD
    // The Vulkan sessions on lavapipe, unless the caller named a driver.
    setenv("VK_ICD_FILENAMES", PHYSHAND_LAVAPIPE_ICD, 0);
    setenv("VK_DRIVER_FILES", PHYSHAND_LAVAPIPE_ICD, 0);
#endif
    benchmark::Initialize(&argc, argv);
    std::optional<std::string> summary_file;
    if (argc == 3 && std::strcmp(argv[1], "--summary") == 0) {
        summary_file = argv[2];
        argc = 1;
    }
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
    for (const Benchmark& b : kBenchmarks) {
        benchmark::RegisterBenchmark(b.name, b.run, b.path)->Unit(benchmark::kNanosecond);
    }
    MedianRecorder recorder(benchmark::CreateDefaultDisplayReporter());
    benchmark::RunSpecifiedBenchmarks(&recorder);
    benchmark::Shutdown();
    std::filesystem::remove(no_overlay_config());

    const std::string table = summary(recorder);
    if (!summary_file) {
        std::cout << '\n' << table;
    } else if (!(std::ofstream(*summary_file) << table)) {
        std::fprintf(stderr, "physhand-overhead: cannot write %s\n", summary_file->c_str());
        return 1;
    }
    return 0;
}
