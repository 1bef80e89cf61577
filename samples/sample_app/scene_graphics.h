#pragma once

#include <vulkan/vulkan.h>
// After vulkan.h; the build defines XR_USE_GRAPHICS_API_VULKAN.
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>
#include <openxr/physhand_physical_hands.h>

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "hand_trackers.h"
#include "scene.h"
#include "scene_drawing.h"
#include "shape_renderer.h"
#include "view_swapchains.h"
#include "vulkan_device.h"

namespace physhand::sample {

// The rendered mode's graphics: a swapchain per view, and each frame the scene drawn from the eyes
// the runtime reports, submitted as one opaque projection layer.
class SceneGraphics {
  public:
    // Creates the swapchains of a session bound to `device`, which must outlive this.
    SceneGraphics(XrInstance instance, XrSystemId system, XrSession session,
                  const VulkanDevice& device, std::optional<std::uint32_t> view_width);

    // The scene to draw from now on.
    void show(const Scene& scene);

    // Draws the shown scene as located at `time` into the next swapchain images, each
    // collider lit by its `flashes` (scene order, 0..1). Returns the layer to submit, or null
    // when the runtime has no valid eye poses to draw from. The pointer is valid until the
    // next call.
    const XrCompositionLayerBaseHeader* render(
        XrSpace stage, XrTime time,
        const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders,
        const std::array<LocatedHand, 2>& hands, const DrawSettings& drawing,
        const std::vector<float>& flashes);

    // Where a point of the scene appears in view 0 of the last frame rendered, as a fraction
    // of the image's width and height from its top left; nullopt behind the eye.
    std::optional<std::array<double, 2>> view0_position(const Vec3& point) const;
    // Wall time of each render(), in milliseconds: building the draws, recording, submitting
    // and finishing both views on the GPU (lavapipe: the rasterising itself).
    const std::vector<double>& frame_ms() const { return frame_ms_; }

  private:
    XrInstance instance_;
    XrSession session_;
    const VulkanDevice& device_;
    ViewSwapchains swapchains_;
    std::optional<SceneDrawing> drawing_;
    std::optional<ShapeRenderer> renderer_;
    std::vector<XrCompositionLayerProjectionView> layer_views_;
    XrCompositionLayerProjection layer_{};
    std::optional<Eigen::Matrix4f> view0_projection_;
    std::vector<double> frame_ms_;
};

}  // namespace physhand::sample
