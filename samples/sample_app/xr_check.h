#pragma once

#include <openxr/openxr.h>

#include <stdexcept>
#include <string>
#include <string_view>

namespace physhand::sample {

// An OpenXR call that failed; what() names the function and its result.
class XrCallError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Throws XrCallError when `result` is a failure. `instance` lets the loader name the result;
// before there is one (XR_NULL_HANDLE) the number is given instead.
void xr_check(XrInstance instance, XrResult result, std::string_view function);

// An extension function, which the loader exports no symbol for.
template <typename Pfn>
Pfn load_function(XrInstance instance, const char* name) {
    PFN_xrVoidFunction function = nullptr;
    xr_check(instance, xrGetInstanceProcAddr(instance, name, &function),
             "xrGetInstanceProcAddr(" + std::string(name) + ")");
    return reinterpret_cast<Pfn>(function);
}

}  // namespace physhand::sample
