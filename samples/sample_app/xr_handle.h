#pragma once

#include <openxr/openxr.h>

#include <utility>

namespace physhand::sample {

// Owns one OpenXR handle and destroys it when it goes, so that every way out of the app,
// errors included, cleans up children before their parents.
template <typename Handle>
class XrHandle {
  public:
    using Destroy = XrResult(XRAPI_PTR*)(Handle);

    XrHandle() = default;
    XrHandle(Handle handle, Destroy destroy) : handle_(handle), destroy_(destroy) {}
    XrHandle(XrHandle&& other) noexcept
        : handle_(std::exchange(other.handle_, XR_NULL_HANDLE)), destroy_(other.destroy_) {}
    XrHandle& operator=(XrHandle&& other) noexcept {
        if (this != &other) {
            reset();
            handle_ = std::exchange(other.handle_, XR_NULL_HANDLE);
            destroy_ = other.destroy_;
        }
        return *this;
    }
    XrHandle(const XrHandle&) = delete;
    XrHandle& operator=(const XrHandle&) = delete;
    ~XrHandle() { reset(); }

    Handle get() const { return handle_; }

  private:
    // A failed destroy leaves nothing to do on the way out.
    void reset() {
        if (handle_ != XR_NULL_HANDLE) destroy_(handle_);
        handle_ = XR_NULL_HANDLE;
    }

    Handle handle_ = XR_NULL_HANDLE;
    Destroy destroy_ = nullptr;
};

}  // namespace physhand::sample
