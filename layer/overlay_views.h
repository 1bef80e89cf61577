#pragma once

#include <openxr/openxr.h>
#include <vulkan/vulkan.h>

#include <optional>
#include <vector>

// What the overlay draws for the app's projection views: it has to trust them less than
// the runtime does, since a bad value would wrap through its unsigned image sizes.
namespace physhand::layer {

// The overlay's image size for each of the app's views: the view's own rect, so the
// overlay is as sharp as the app, up to overlay::kMaxDrawnPixels (overlay::drawn_extent).
// Nullopt when a view cannot be drawn for: an empty or
// negative rect, one larger than the system's largest swapchain (`limits`), a non-finite
// pose, or a field of view that is not finite, is empty or inverted, or reaches ±90° (no
// projection takes it); the overlay then skips the frame. `app_layer.views` holds
// `app_layer.viewCount` views.
std::optional<std::vector<VkExtent2D>> overlay_extents(
    const XrCompositionLayerProjection& app_layer, const XrSystemGraphicsProperties& limits);

}  // namespace physhand::layer
