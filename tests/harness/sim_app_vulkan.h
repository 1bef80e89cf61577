#pragma once

#include <vulkan/vulkan.h>
// After vulkan.h; the build defines XR_USE_GRAPHICS_API_VULKAN.
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <array>
#include <vector>

// The Vulkan side of a SimApp with a Vulkan session (XR_KHR_vulkan_enable2): the device
// the runtime asks for, one swapchain for both views, and the projection layer an app
// submits each frame. Nothing is drawn into the swapchain: what the tools time or fuzz is
// the frame's path through the layer and the runtime, not the app's rendering.
namespace physhand::test {

class AppVulkan {
  public:
    // Creates the Vulkan instance and device through the runtime. Throws std::runtime_error
    // naming the call that failed.
    AppVulkan(XrInstance instance, XrSystemId system);
    ~AppVulkan();
    AppVulkan(const AppVulkan&) = delete;
    AppVulkan& operator=(const AppVulkan&) = delete;

    // For XrSessionCreateInfo::next.
    const XrGraphicsBindingVulkan2KHR& binding() const { return binding_; }

    // Creates the swapchain and finds where the views are in `space`; after xrBeginSession.
    void start(XrSession session, XrSpace space, XrTime time);
    // Acquires, waits for and releases the next image (the app's rendering, minus drawing),
    // and returns the projection layer that shows it; null before start().
    const XrCompositionLayerProjection* render();

  private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    XrGraphicsBindingVulkan2KHR binding_{};
    XrSwapchain swapchain_ = XR_NULL_HANDLE;  // destroyed with the session
    std::array<XrCompositionLayerProjectionView, 2> views_{};
    XrCompositionLayerProjection layer_{};
};

}  // namespace physhand::test
