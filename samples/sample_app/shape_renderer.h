#pragma once

#include <vulkan/vulkan.h>

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "shape_meshes.h"
#include "vulkan_device.h"

namespace physhand::sample {

// One mesh to draw: where it is (model: scene frame from mesh frame) and its colour
// (linear rgb and alpha; alpha < 1 draws it translucent).
struct Draw {
    MeshRange mesh;
    Eigen::Matrix4f model;
    std::array<float, 4> color;
};

// One view to render: a target image (colour attachment, left in
// COLOR_ATTACHMENT_OPTIMAL as OpenXR wants swapchain images back) and how it sees the scene.
struct ViewTarget {
    VkImage image = VK_NULL_HANDLE;
    VkExtent2D extent{};
    Eigen::Matrix4f view_projection;  // scene frame to Vulkan clip space
    Eigen::Vector3f eye;              // in the scene frame, to sort translucent draws
};

// Draws lit meshes into views: the opaque ones first, then the translucent ones from far to
// near, blended over them without writing depth.
class ShapeRenderer {
  public:
    // `meshes` is uploaded once; every Draw's range must come from it.
    ShapeRenderer(const VulkanDevice& device, VkFormat color_format, const MeshSet& meshes);
    ~ShapeRenderer();
    ShapeRenderer(const ShapeRenderer&) = delete;
    ShapeRenderer& operator=(const ShapeRenderer&) = delete;

    // Records, submits and waits for one frame of every view (one render pass each).
    void render(std::span<const ViewTarget> views, std::span<const Draw> draws);

  private:
    struct Target {
        VkImage image = VK_NULL_HANDLE;
        VkExtent2D extent{};
        VkImageView color_view = VK_NULL_HANDLE;
        VkImage depth = VK_NULL_HANDLE;
        VkDeviceMemory depth_memory = VK_NULL_HANDLE;
        VkImageView depth_view = VK_NULL_HANDLE;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
    };
    struct Buffer {
        VkBuffer buffer = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
    };

    const Target& target(const ViewTarget& view);
    Buffer upload(const void* data, VkDeviceSize size, VkBufferUsageFlags usage);
    VkImageView image_view(VkImage image, VkFormat format, VkImageAspectFlags aspect);
    void record(VkCommandBuffer commands, const ViewTarget& view, std::span<const Draw> draws);

    const VulkanDevice& device_;
    VkFormat color_format_;
    VkRenderPass render_pass_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline opaque_ = VK_NULL_HANDLE;
    VkPipeline translucent_ = VK_NULL_HANDLE;
    Buffer vertices_;
    Buffer indices_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    std::vector<Target> targets_;  // one per swapchain image seen
};

}  // namespace physhand::sample
