// physhand-sample: the sample app. Plays scene files through the OpenXR loader, the physhand
// layer and the runtime (the simulated one plays the scene's hands; a headset, the user's),
// draws them with Vulkan unless headless, and prints the same result as physhand-scene, with
// "path": "layer".
#include <cmath>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hand_drive.h"
#include "run_report.h"
#include "scene.h"
#include "scene_run.h"
#include "xr_app.h"

namespace {

constexpr const char* kUsage =
    "usage: physhand-sample [options] SCENE.json [SCENE.json ...]\n"
    "  --headless      run without graphics (XR_MND_headless); default: Vulkan\n"
    "                  (XR_KHR_vulkan_enable2), drawing colliders and hands\n"
    "  --live          for a headset: scenes never end on their own; type a line on stdin:\n"
    "                  r (reset the scene), n (next scene file), q (quit)\n"
    "  --drive NAME    the hand drive the sample sets (bones, implicit, paper;\n"
    "                  default: the default drive, whatever the layer's config says)\n"
    "  --substeps N    physics substeps per frame, 1 to 64 (default: the drive's own)\n"
    "  --hover-cm X    objects start to turn translucent within X cm of a hand (default 3;\n"
    "                  0: only while touched)\n"
    "  --no-feedback   touched objects stay opaque\n"
    "  --no-hands      draw no hands of the app's own (the layer's overlay still may)\n"
    "  --view-size N   each view N pixels wide (default: the runtime's recommendation)\n"
    "  --json          print each result as one JSON object (default: one summary line)\n"
    "A line for each touch that begins (hand part, object, impact speed) goes to stdout, or\n"
    "to stderr with --json.\n";

int usage_error(const std::string& message) {
    std::cerr << "physhand-sample: " << message << "\n" << kUsage;
    return 2;
}

// The text after option argv[i] (i moves on to it), or "" when there is none.
std::string option_value(int& i, int argc, char** argv) {
    return i + 1 < argc ? argv[++i] : "";
}

// `text` as a number in [low, high] (whole when `whole`), or nullopt; nan and inf are in no
// range.
std::optional<double> number_in(const std::string& text, double low, double high, bool whole) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !(value >= low && value <= high)) return std::nullopt;
    if (whole && value != std::floor(value)) return std::nullopt;
    return value;
}

void print(const physhand::sample::ScenePlayed& played, bool json) {
    if (json) {
        nlohmann::json object = physhand::to_json(played.result);
        if (!played.rendering.is_null()) object.update(played.rendering);
        std::cout << object.dump() << std::endl;
        return;
    }
    std::cout << physhand::summary_line(played.result);
    if (!played.rendering.is_null()) {
        std::cout << " frame_ms_median=" << played.rendering["frame_ms_median"].get<double>();
    }
    std::cout << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
    using physhand::sample::UserCommand;
    std::vector<std::string> scene_paths;
    physhand::sample::AppOptions options;
    bool json = false;
    physhand::RunOptions drive_options;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--headless") {
            options.rendered = false;
        } else if (arg == "--live") {
            options.live = true;
        } else if (arg == "--no-feedback") {
            options.drawing.feedback = false;
        } else if (arg == "--no-hands") {
            options.drawing.hands = false;
        } else if (arg == "--hover-cm") {
            const std::string text = option_value(i, argc, argv);
            const auto cm = number_in(text, 0.0, 100.0, false);
            if (!cm) {
                return usage_error("--hover-cm: \"" + text +
                                   "\" is not a distance in cm from 0 (no hover) to 100");
            }
            options.drawing.hover_m = *cm / 100.0;
        } else if (arg == "--drive") {
            drive_options.drive = option_value(i, argc, argv);
        } else if (arg == "--substeps") {
            const std::string text = option_value(i, argc, argv);
            const auto n = number_in(text, 1, physhand::kMaxSubsteps, true);
            if (!n) {
                return usage_error("--substeps: \"" + text + "\" is not a whole number from 1 to " +
                                   std::to_string(physhand::kMaxSubsteps));
            }
            drive_options.substeps = static_cast<int>(*n);
        } else if (arg == "--view-size") {
            const std::string text = option_value(i, argc, argv);
            const auto size = number_in(text, 16, 8192, true);
            if (!size) {
                return usage_error("--view-size: \"" + text +
                                   "\" is not a width in pixels from 16 to 8192");
            }
            options.view_width = static_cast<std::uint32_t>(*size);
        } else if (arg == "--json") {
            json = true;
        } else if (arg == "-h" || arg == "--help") {
            std::cout << kUsage;
            return 0;
        } else if (!arg.empty() && arg[0] == '-') {
            return usage_error("unknown option " + std::string(arg));
        } else {
            scene_paths.emplace_back(arg);
        }
    }
    try {
        options.drive = physhand::settings_for(drive_options).drive;
    } catch (const std::invalid_argument& e) {
        return usage_error(std::string("--drive: ") + e.what());
    }
    if (scene_paths.empty()) return usage_error("no scene file");
    if (json) options.touch_lines = &std::cerr;
    if (options.live && !options.rendered) return usage_error("--live needs the rendered mode");

    try {
        std::vector<physhand::Scene> scenes;
        for (const std::string& path : scene_paths) scenes.push_back(physhand::load_scene(path));
        // The simulated runtime plays the hands of the scene this names, read when an
        // instance is created (docs/design.md); one set by the user wins.
        const bool user_scene = std::getenv("PHYSHAND_SIM_SCENE") != nullptr;
        // The simulated head looks straight ahead; the paper scenes are on a table below.
        setenv("PHYSHAND_SIM_HEAD_PITCH_DEG", "-50", 0);
        const auto name_scene = [&](std::size_t i) {
            if (user_scene) return;
            const std::string absolute = std::filesystem::absolute(scene_paths[i]).string();
            setenv("PHYSHAND_SIM_SCENE", absolute.c_str(), 1);
        };
        if (options.live) {
            name_scene(0);
            physhand::sample::XrApp app(options);
            std::size_t i = 0;
            for (;;) {
                const physhand::sample::ScenePlayed played = app.play(scenes[i]);
                print(played, json);
                if (played.next == UserCommand::Quit) break;
                if (played.next == UserCommand::Next) i = (i + 1) % scenes.size();
            }
        } else {
            for (std::size_t i = 0; i < scenes.size(); ++i) {
                name_scene(i);
                // A temporary app per scene: the simulated runtime plays one scene per
                // instance, and the OpenXR objects are gone before anything is printed.
                const physhand::sample::ScenePlayed played =
                    physhand::sample::XrApp(options).play(scenes[i]);
                print(played, json);
            }
        }
    } catch (const physhand::FormatError& e) {
        std::cerr << "physhand-sample: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "physhand-sample: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
