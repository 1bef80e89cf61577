#pragma once

#include <openxr/openxr.h>

#include <array>
#include <memory>
#include <vector>

#include "dispatch.h"
#include "overlay_renderer.h"
#include "vulkan_binding.h"

// The overlay of one Vulkan session: a swapchain the layer creates on the app's session,
// and the renderer that draws the hands into it with the app's device and queue.
namespace physhand::layer {

class OverlaySession {
  public:
    OverlaySession(const NextDispatch& next, XrSession session, const VulkanBinding& binding,
                   bool tint);
    // Waits for the GPU, then destroys the swapchain (the session must still exist).
    ~OverlaySession();
    OverlaySession(const OverlaySession&) = delete;
    OverlaySession& operator=(const OverlaySession&) = delete;

    // Draws `hands` (in the space of `app_layer`) for the views of the app's projection
    // layer. Returns the layer to composite over the app's, or null when nothing was drawn.
    // Throws on any failure.
    const XrCompositionLayerProjection* draw(const XrCompositionLayerProjection& app_layer,
                                             const std::array<overlay::Hand, 2>& hands);

    // CPU time of one frame's overlay work, for the median logged at the end when
    // PHYSHAND_OVERLAY_STATS=1.
    void record_cpu_time(double microseconds);

  private:
    void ensure_swapchain(const XrCompositionLayerProjection& app_layer);
    void destroy_swapchain() noexcept;

    const NextDispatch& next_;
    const XrSession session_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    std::unique_ptr<overlay::Renderer> renderer_;
    overlay::Settings settings_;

    XrSwapchain swapchain_ = XR_NULL_HANDLE;  // one array layer per view
    std::vector<VkImage> images_;
    std::vector<VkExtent2D> extents_;  // per view: the app's view size, capped

    std::vector<overlay::View> views_;
    std::vector<XrCompositionLayerProjectionView> layer_views_;
    XrCompositionLayerProjection layer_{};

    std::vector<double> cpu_us_;  // empty unless PHYSHAND_OVERLAY_STATS=1
    bool collect_stats_ = false;
};

}  // namespace physhand::layer
