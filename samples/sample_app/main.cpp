// physhand-sample: the sample app. Plays a scene file through the OpenXR loader, the physhand
// layer and the runtime (the simulated one plays the scene's hands), and prints the same
// result as physhand-scene, with "path": "layer".
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>

#include "run_report.h"
#include "scene.h"
#include "xr_app.h"

namespace {

constexpr const char* kUsage =
    "usage: physhand-sample [--headless] SCENE.json [--json]\n"
    "  --headless  run without graphics (XR_MND_headless); the only mode so far\n"
    "  --json      print the result as one JSON object (default: one summary line)\n";

int usage_error(const std::string& message) {
    std::cerr << "physhand-sample: " << message << "\n" << kUsage;
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene_path;
    bool headless = false;
    bool json = false;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg == "--headless") {
            headless = true;
        } else if (arg == "--json") {
            json = true;
        } else if (arg == "-h" || arg == "--help") {
            std::cout << kUsage;
            return 0;
        } else if (!arg.empty() && arg[0] == '-') {
            return usage_error("unknown option " + std::string(arg));
        } else if (scene_path.empty()) {
            scene_path = arg;
        } else {
            return usage_error("only one scene file");
        }
    }
    if (scene_path.empty()) return usage_error("no scene file");
    if (!headless) {
        return usage_error(
            "the Vulkan mode is not available yet; run with --headless (XR_MND_headless)");
    }

    try {
        const physhand::Scene scene = physhand::load_scene(scene_path);
        // The simulated runtime plays the hands of the scene this names (DESIGN.md); one set
        // by the user wins.
        const std::string absolute = std::filesystem::absolute(scene_path).string();
        setenv("PHYSHAND_SIM_SCENE", absolute.c_str(), 0);

        // A temporary app: its OpenXR objects are gone before anything is printed.
        const physhand::RunResult result = physhand::sample::XrApp(scene).run();
        if (json) {
            std::cout << physhand::to_json(result).dump() << "\n";
        } else {
            std::cout << physhand::summary_line(result) << "\n";
        }
    } catch (const physhand::SceneError& e) {
        std::cerr << "physhand-sample: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "physhand-sample: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
