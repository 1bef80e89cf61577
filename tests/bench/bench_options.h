#pragma once

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace physhand::bench {

// The options every physics benchmark tool takes: where to write, how many runs to take
// the median of, and where the scene files are; tools that sweep configurations also take
// filters (empty: everything), to compare a few variants quickly in one run.
struct Options {
    std::filesystem::path out = "bench-out";
    std::filesystem::path scenes_dir;
    int repeat = 3;
    std::vector<std::string> only_scenes;
    std::vector<std::string> only_drives;
    std::vector<int> only_substeps;
    int shifts = 1;  // physhand-robustness: plays of each variant, each moved a little
};

// nullopt (after printing the usage of `tool`) on a bad command line; the filters are
// accepted only when `with_filters`, --shifts only when `with_shifts`.
std::optional<Options> parse_options(int argc, char** argv, const char* tool,
                                     const std::filesystem::path& default_scenes,
                                     bool with_filters = false, bool with_shifts = false);

// True when `list` is empty (no filter) or holds `value`.
template <typename T>
bool selected(const std::vector<T>& list, const T& value) {
    return list.empty() || std::find(list.begin(), list.end(), value) != list.end();
}

}  // namespace physhand::bench
