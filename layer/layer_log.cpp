#include "layer_log.h"

#include <cstdio>
#include <mutex>
#include <string>
#include <unordered_set>

namespace physhand::layer {

namespace {
// Distinct messages remembered; beyond this, messages are dropped rather than letting a
// message with a changing number grow memory without bound.
constexpr std::size_t kMaxMessages = 1000;
}  // namespace

void log_once(const std::string& message) noexcept {
    static std::mutex mutex;
    static std::unordered_set<std::string> seen;
    try {
        std::lock_guard lock(mutex);
        if (seen.size() >= kMaxMessages || !seen.insert(message).second) return;
        std::fprintf(stderr, "physhand: %s\n", message.c_str());
    } catch (...) {
        // Out of memory while logging: losing the message is the only safe option.
    }
}

void log_failure(const char* function, const char* what) noexcept {
    try {
        log_once(std::string(function) + ": " + what);
    } catch (...) {
        // As above.
    }
}

}  // namespace physhand::layer
