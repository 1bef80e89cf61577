// physhand-scene: plays a scene file in physics/ alone, headless, and prints its result.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <string_view>

#include "run_report.h"
#include "scene.h"
#include "scene_run.h"

namespace {

constexpr const char* kUsage =
    "usage: physhand-scene SCENE.json [--drive NAME] [--substeps N] [--seed S] [--json]\n"
    "                      [--no-gating] [--no-sleeping] [--display-hz HZ]\n"
    "                      [--frame-jitter-ms MS]\n"
    "  --json             print the result as one JSON object (default: one summary line)\n"
    "  --display-hz       frames shown at HZ, 20 to 240 (default 90)\n"
    "  --frame-jitter-ms  each frame shown up to MS early or late (seeded)\n";

int usage_error(const std::string& message) {
    std::cerr << "physhand-scene: " << message << "\n" << kUsage;
    return 2;
}

bool parse_double(std::string_view text, double& out) {
    char* end = nullptr;
    const std::string s(text);
    out = std::strtod(s.c_str(), &end);
    return !s.empty() && end == s.c_str() + s.size();
}

bool parse_int(std::string_view text, long long& out) {
    char* end = nullptr;
    const std::string s(text);
    out = std::strtoll(s.c_str(), &end, 10);
    return !s.empty() && end == s.c_str() + s.size();
}

}  // namespace

int main(int argc, char** argv) {
    std::string scene_path;
    physhand::RunOptions options;
    bool json = false;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        auto value = [&]() -> std::string_view { return i + 1 < argc ? argv[++i] : ""; };
        long long n = 0;
        if (arg == "--json") {
            json = true;
        } else if (arg == "--no-gating") {
            options.gating = false;
        } else if (arg == "--no-sleeping") {
            options.sleeping = false;
        } else if (arg == "--drive") {
            const std::string_view v = value();
            if (v.empty()) return usage_error("--drive needs a name");
            options.drive = std::string(v);
        } else if (arg == "--substeps") {
            if (!parse_int(value(), n) || n < 1 || n > 1000) {
                return usage_error("--substeps needs a whole number from 1 to 1000");
            }
            options.substeps = static_cast<int>(n);
        } else if (arg == "--seed") {
            if (!parse_int(value(), n) || n < 0)
                return usage_error("--seed needs a whole number >= 0");
            options.seed = static_cast<std::uint64_t>(n);
        } else if (arg == "--display-hz") {
            if (!parse_double(value(), options.display.rate_hz))
                return usage_error("--display-hz needs a number of Hz");
        } else if (arg == "--frame-jitter-ms") {
            if (!parse_double(value(), options.display.jitter_ms))
                return usage_error("--frame-jitter-ms needs a number of milliseconds");
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
    try {
        physhand::check_display_timing(options.display);
    } catch (const std::invalid_argument& e) {
        return usage_error(e.what());
    }

    try {
        const physhand::Scene scene = physhand::load_scene(scene_path);
        const physhand::RunResult result = physhand::run_scene(scene, options);
        if (json) {
            std::cout << physhand::to_json(result).dump() << "\n";
        } else {
            std::cout << physhand::summary_line(result) << "\n";
        }
    } catch (const physhand::FormatError& e) {
        std::cerr << "physhand-scene: " << e.what() << "\n";
        return 2;
    } catch (const std::invalid_argument& e) {
        return usage_error(e.what());
    } catch (const std::exception& e) {
        std::cerr << "physhand-scene: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
