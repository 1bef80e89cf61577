#include "runtime_clock.h"

#include <vulkan/vulkan.h>
// After vulkan.h: the build defines XR_USE_GRAPHICS_API_VULKAN, and XR_USE_TIMESPEC for
// the function used here.
#include <openxr/openxr_platform.h>

#include <ctime>

namespace physhand::sample {

RuntimeClock::RuntimeClock(XrInstance instance, bool enabled) : instance_(instance) {
    if (enabled &&
        XR_FAILED(xrGetInstanceProcAddr(instance, "xrConvertTimespecTimeToTimeKHR", &convert_))) {
        convert_ = nullptr;
    }
}

std::optional<XrTime> RuntimeClock::now() const {
    if (convert_ == nullptr) return std::nullopt;
    timespec monotonic{};
    if (clock_gettime(CLOCK_MONOTONIC, &monotonic) != 0) return std::nullopt;
    XrTime time = 0;
    const auto convert = reinterpret_cast<PFN_xrConvertTimespecTimeToTimeKHR>(convert_);
    if (XR_FAILED(convert(instance_, &monotonic, &time)) || time <= 0) return std::nullopt;
    return time;
}

}  // namespace physhand::sample
