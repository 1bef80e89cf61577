#pragma once

#include <filesystem>
#include <optional>

namespace physhand::bench {

// The options every physics benchmark tool takes: where to write, how many runs to take
// the median of, and where the scene files are.
struct Options {
    std::filesystem::path out = "bench-out";
    std::filesystem::path scenes_dir;
    int repeat = 3;
};

// nullopt (after printing the usage of `tool`) on a bad command line.
std::optional<Options> parse_options(int argc, char** argv, const char* tool,
                                     const std::filesystem::path& default_scenes);

}  // namespace physhand::bench
