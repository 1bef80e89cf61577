#pragma once

#include <openxr/openxr.h>

#include <array>
#include <chrono>
#include <cstdint>
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
    // `limits`: the system's, the largest swapchain among them; `recommended`: the
    // runtime's recommended view sizes, the least the swapchain is made for.
    OverlaySession(const NextDispatch& next, XrSession session, const VulkanBinding& binding,
                   const XrSystemGraphicsProperties& limits, std::vector<VkExtent2D> recommended,
                   const overlay::Settings& drawing);
    // Waits for the GPU, then destroys the swapchain (the session must still exist); logs
    // the medians when PHYSHAND_OVERLAY_STATS=1.
    ~OverlaySession();
    OverlaySession(const OverlaySession&) = delete;
    OverlaySession& operator=(const OverlaySession&) = delete;

    // Draws `hands` (in the space of `app_layer`) for the views of the app's projection
    // layer, at their size. Returns the layer to composite over the app's, or null when
    // nothing was drawn, or when the app's views cannot be drawn for (overlay_extents): that
    // frame only. Throws on any failure.
    const XrCompositionLayerProjection* draw(const XrCompositionLayerProjection& app_layer,
                                             const std::array<overlay::Hand, 2>& hands);

    // With PHYSHAND_OVERLAY_STATS=1, keeps the figures of a frame draw() drew: the CPU time
    // of the layer's overlay work in xrEndFrame (`elapsed`, less the runtime's swapchain
    // calls in draw()) and the renderer's newest GPU time.
    void record_drawn_frame(std::chrono::steady_clock::duration elapsed);

  private:
    void ensure_swapchain(std::vector<VkExtent2D> extents);
    void destroy_swapchain() noexcept;

    const NextDispatch& next_;
    const XrSession session_;
    const XrSystemGraphicsProperties limits_;
    const std::vector<VkExtent2D> recommended_;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    std::unique_ptr<overlay::Renderer> renderer_;
    overlay::Settings settings_;

    XrSwapchain swapchain_ = XR_NULL_HANDLE;  // one array layer per view
    VkExtent2D swapchain_size_{};
    int swapchains_made_ = 0;
    std::vector<VkImage> images_;
    std::vector<VkExtent2D> extents_;  // per view: the app's view size, drawn at the top left

    std::vector<overlay::View> views_;
    std::vector<XrCompositionLayerProjectionView> layer_views_;
    XrCompositionLayerProjection layer_{};

    bool collect_stats_ = false;  // PHYSHAND_OVERLAY_STATS=1; the rest is empty without it
    std::chrono::steady_clock::duration runtime_time_{};  // in the runtime, this draw()
    std::vector<double> cpu_us_;
    std::vector<double> gpu_us_;
    uint64_t gpu_frames_seen_ = 0;  // overlay::Timings::gpu_frames at the last sample
};

}  // namespace physhand::layer
