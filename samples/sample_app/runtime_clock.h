#pragma once

#include <openxr/openxr.h>

#include <optional>

namespace physhand::sample {

// The runtime's clock read directly (XR_KHR_convert_timespec_time), for runtimes whose
// headless sessions have no frame loop and so give no display times.
class RuntimeClock {
  public:
    // `enabled`: the instance enabled the extension; without it, now() has no answer.
    RuntimeClock(XrInstance instance, bool enabled);

    // The runtime's time now (CLOCK_MONOTONIC converted), or nullopt when it cannot say.
    std::optional<XrTime> now() const;

  private:
    XrInstance instance_;
    PFN_xrVoidFunction convert_ = nullptr;  // xrConvertTimespecTimeToTimeKHR
};

}  // namespace physhand::sample
