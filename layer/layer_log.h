#pragma once

#include <openxr/openxr.h>

#include <exception>
#include <string>

namespace physhand::layer {

// Writes "physhand: <message>" to stderr the first time a message is seen, so a problem
// that repeats every frame does not flood the app's log. Never throws.
void log_once(const std::string& message) noexcept;
// "physhand: <function>: <what>", once.
void log_failure(const char* function, const char* what) noexcept;

// Runs an entry point's body; an exception escaping it is logged once and becomes
// XR_ERROR_RUNTIME_FAILURE, because nothing may unwind into the app.
template <typename Body>
XrResult guarded(const char* function, Body&& body) noexcept {
    try {
        return body();
    } catch (const std::exception& e) {
        log_failure(function, e.what());
    } catch (...) {
        log_failure(function, "unknown exception");
    }
    return XR_ERROR_RUNTIME_FAILURE;
}

}  // namespace physhand::layer
