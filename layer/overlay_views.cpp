#include "overlay_views.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numbers>

#include "overlay_renderer.h"

namespace physhand::layer {

namespace {

bool drawable(const XrCompositionLayerProjectionView& view,
              const XrSystemGraphicsProperties& limits) {
    const XrExtent2Di& size = view.subImage.imageRect.extent;
    const XrPosef& pose = view.pose;
    const XrFovf& fov = view.fov;
    const float values[] = {pose.position.x,    pose.position.y,    pose.position.z,
                            pose.orientation.x, pose.orientation.y, pose.orientation.z,
                            pose.orientation.w, fov.angleLeft,      fov.angleRight,
                            fov.angleUp,        fov.angleDown};
    // Each side of the view within a right angle of its axis: the projection divides by
    // the tangents of the angles.
    constexpr float kRightAngle = std::numbers::pi_v<float> / 2;
    return size.width > 0 && size.height > 0 &&
           static_cast<uint32_t>(size.width) <= limits.maxSwapchainImageWidth &&
           static_cast<uint32_t>(size.height) <= limits.maxSwapchainImageHeight &&
           std::all_of(std::begin(values), std::end(values),
                       [](float v) { return std::isfinite(v); }) &&
           -kRightAngle < fov.angleLeft && fov.angleLeft < fov.angleRight &&
           fov.angleRight < kRightAngle && -kRightAngle < fov.angleDown &&
           fov.angleDown < fov.angleUp && fov.angleUp < kRightAngle;
}

}  // namespace

std::optional<std::vector<VkExtent2D>> overlay_extents(
    const XrCompositionLayerProjection& app_layer, const XrSystemGraphicsProperties& limits) {
    std::vector<VkExtent2D> extents;
    for (uint32_t i = 0; i < app_layer.viewCount; ++i) {
        const XrCompositionLayerProjectionView& view = app_layer.views[i];
        if (!drawable(view, limits)) return std::nullopt;
        const XrExtent2Di& size = view.subImage.imageRect.extent;
        extents.push_back(overlay::drawn_extent(
            {static_cast<uint32_t>(size.width), static_cast<uint32_t>(size.height)}));
    }
    return extents;
}

}  // namespace physhand::layer
