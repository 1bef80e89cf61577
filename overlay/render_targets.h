#pragma once

#include <vulkan/vulkan.h>

#include <span>
#include <utility>
#include <vector>

#include "gpu_memory.h"
#include "overlay_renderer.h"
#include "vk_dispatch.h"

namespace physhand::overlay {

// Throws std::runtime_error (VK_ERROR_FORMAT_NOT_SUPPORTED) unless `format` can be a 4x
// multisampled colour and input attachment.
void require_color_format(const DeviceContext& context, VkFormat format);

// `requested` if it can be a 4x multisampled depth attachment (else throws); for
// VK_FORMAT_UNDEFINED the most precise one that can.
VkFormat choose_depth_format(const DeviceContext& context, VkFormat requested);

// The multisampled attachments, shared by all views and grown to the largest view seen,
// the descriptor set through which the resolve reads them, and a view and framebuffer
// per target image layer.
class RenderTargets {
  public:
    RenderTargets(const DeviceContext& context, VkFormat color_format, VkFormat depth_format,
                  VkRenderPass render_pass, VkDescriptorSetLayout resolve_set_layout);
    ~RenderTargets();
    RenderTargets(const RenderTargets&) = delete;
    RenderTargets& operator=(const RenderTargets&) = delete;

    // True when every view already has its framebuffer, so prepare() would change nothing.
    bool ready_for(std::span<const View> views) const;
    // Creates what the views lack, destroying what they replace: the caller makes sure no
    // pending GPU work still uses those.
    void prepare(std::span<const View> views);
    // The framebuffer of a view passed to prepare().
    VkFramebuffer framebuffer(const View& view) const;
    // The multisampled colour as the resolve's input attachment (valid after prepare()).
    VkDescriptorSet resolve_input() const { return resolve_input_; }
    // Destroys what belongs to `image` (no pending GPU work may use it).
    void forget(VkImage image);
    // Device memory of the multisampled attachments, bytes.
    VkDeviceSize memory_bytes() const { return color_.memory_size + depth_.memory_size; }

  private:
    struct Target {
        VkImage image = VK_NULL_HANDLE;
        uint32_t array_layer = 0;
        VkExtent2D extent{};
        VkImageView view = VK_NULL_HANDLE;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
    };

    const Target* find(const View& view) const;
    Target* find(const View& view) { return const_cast<Target*>(std::as_const(*this).find(view)); }
    bool fits(const View& view) const;
    void destroy_target(Target& target);

    const DeviceContext& context_;
    VkFormat color_format_;
    VkFormat depth_format_;
    VkRenderPass render_pass_;
    VkExtent2D attachment_extent_{};
    TransientAttachment color_;
    TransientAttachment depth_;
    VkDescriptorPool descriptor_pool_ = VK_NULL_HANDLE;
    VkDescriptorSet resolve_input_ = VK_NULL_HANDLE;
    std::vector<Target> targets_;
};

}  // namespace physhand::overlay
