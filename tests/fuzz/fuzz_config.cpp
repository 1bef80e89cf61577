// The layer's config parser (physhand::layer::parse_config) on arbitrary bytes: every input
// either parses or throws std::runtime_error, as config.h documents. Any other exception
// ends in std::terminate, which the fuzzer reports as a crash.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        physhand::layer::parse_config(text);
    } catch (const std::runtime_error&) {
        // The documented answer to a config file that does not parse.
    }
    return 0;
}
