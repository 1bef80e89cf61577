#include "xr_check.h"

namespace physhand::sample {

void xr_check(XrInstance instance, XrResult result, std::string_view function) {
    if (XR_SUCCEEDED(result)) return;
    char name[XR_MAX_RESULT_STRING_SIZE] = {};
    const bool named =
        instance != XR_NULL_HANDLE && XR_SUCCEEDED(xrResultToString(instance, result, name));
    throw XrCallError(std::string(function) + " failed: " +
                      (named ? std::string(name) : "XrResult " + std::to_string(result)));
}

}  // namespace physhand::sample
