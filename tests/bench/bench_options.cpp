#include "bench_options.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

namespace physhand::bench {

namespace {

// "1,2,4" -> {1, 2, 4}; nullopt unless every item is a whole number >= 1.
std::optional<std::vector<int>> parse_counts(const std::string& text) {
    std::vector<int> counts;
    std::istringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        char* end = nullptr;
        const long n = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || n < 1 || n > 1000) return std::nullopt;
        counts.push_back(static_cast<int>(n));
    }
    if (counts.empty()) return std::nullopt;
    return counts;
}

}  // namespace

std::optional<Options> parse_options(int argc, char** argv, const char* tool,
                                     const std::filesystem::path& default_scenes, bool with_filters,
                                     bool with_shifts) {
    Options o;
    o.scenes_dir = default_scenes;
    bool ok = true;
    for (int i = 1; i < argc && ok; ++i) {
        const std::string a = argv[i];
        const bool has_value = i + 1 < argc;
        if (a == "--out" && has_value) {
            o.out = argv[++i];
        } else if (a == "--repeat" && has_value) {
            o.repeat = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--scenes" && has_value) {
            o.scenes_dir = argv[++i];
        } else if (with_filters && a == "--scene" && has_value) {
            o.only_scenes.emplace_back(argv[++i]);
        } else if (with_filters && a == "--drive" && has_value) {
            o.only_drives.emplace_back(argv[++i]);
        } else if (with_shifts && a == "--shifts" && has_value) {
            o.shifts = std::max(1, std::atoi(argv[++i]));
        } else if (with_filters && a == "--substeps" && has_value) {
            const auto counts = parse_counts(argv[++i]);
            ok = counts.has_value();
            if (ok) o.only_substeps.insert(o.only_substeps.end(), counts->begin(), counts->end());
        } else {
            ok = false;
        }
    }
    if (!ok) {
        std::cerr << "usage: " << tool << " [--out DIR] [--repeat N] [--scenes DIR]"
                  << (with_filters ? " [--scene NAME]... [--drive NAME]... [--substeps N,N...]"
                                   : "")
                  << (with_shifts ? " [--shifts N]" : "") << "\n";
        return std::nullopt;
    }
    std::filesystem::create_directories(o.out);
    return o;
}

}  // namespace physhand::bench
