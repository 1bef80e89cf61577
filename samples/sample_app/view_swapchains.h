#pragma once

#include <vulkan/vulkan.h>
// After vulkan.h; the build defines XR_USE_GRAPHICS_API_VULKAN.
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "xr_handle.h"

namespace physhand::sample {

// A colour swapchain per view of the stereo view configuration, in an sRGB format.
class ViewSwapchains {
  public:
    // Each view `width` pixels wide (its recommended width without one), as high as its
    // recommended aspect ratio makes it. Throws XrCallError, or std::runtime_error when the
    // runtime offers no sRGB format.
    ViewSwapchains(XrInstance instance, XrSystemId system, XrSession session,
                   std::optional<std::uint32_t> width);

    VkFormat format() const { return format_; }
    std::size_t count() const { return views_.size(); }
    VkExtent2D extent(std::size_t view) const { return views_[view].extent; }
    XrSwapchain swapchain(std::size_t view) const { return views_[view].swapchain.get(); }

    // Acquires the view's next image and waits until it may be drawn into.
    VkImage acquire(std::size_t view);
    void release(std::size_t view);

  private:
    struct View {
        XrHandle<XrSwapchain> swapchain;
        VkExtent2D extent{};
        std::vector<VkImage> images;
    };

    XrInstance instance_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    std::vector<View> views_;
};

}  // namespace physhand::sample
