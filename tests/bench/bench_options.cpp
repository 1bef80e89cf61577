#include "bench_options.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

namespace physhand::bench {

std::optional<Options> parse_options(int argc, char** argv, const char* tool,
                                     const std::filesystem::path& default_scenes) {
    Options o;
    o.scenes_dir = default_scenes;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--out" && i + 1 < argc) {
            o.out = argv[++i];
        } else if (a == "--repeat" && i + 1 < argc) {
            o.repeat = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--scenes" && i + 1 < argc) {
            o.scenes_dir = argv[++i];
        } else {
            std::cerr << "usage: " << tool << " [--out DIR] [--repeat N] [--scenes DIR]\n";
            return std::nullopt;
        }
    }
    std::filesystem::create_directories(o.out);
    return o;
}

}  // namespace physhand::bench
