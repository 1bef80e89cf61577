// physhand::parse_scene on arbitrary bytes: every input either parses or throws FormatError.
// Any other exception ends in std::terminate, which the fuzzer reports as a crash.

#include <cstddef>
#include <cstdint>
#include <string>

#include "scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        // Recorded tracks resolve against the corpus folder, which holds one valid track.
        physhand::parse_scene(text, PHYSHAND_FUZZ_CORPUS_DIR);
    } catch (const physhand::FormatError&) {
        // The documented answer to a scene file that does not conform.
    }
    return 0;
}
