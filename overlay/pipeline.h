#pragma once

#include <vulkan/vulkan.h>

#include <array>

#include "vk_dispatch.h"

namespace physhand::overlay {

// 4x MSAA rather than analytic edge antialiasing in impostor shaders: it also smooths
// where primitives of different colours intersect (a tinted joint in its bones, the
// ghost cutting the physical hand), needs no back-to-front sorting, and lets the
// translucent ghost be drawn as one layer with a depth pre-pass. Every implementation
// supports 4 samples for colour and depth attachments.
inline constexpr VkSampleCountFlagBits kSamples = VK_SAMPLE_COUNT_4_BIT;

// Attachments: 0 multisampled colour, 1 multisampled depth (both cleared, then
// discarded), 2 the target image layer, written whole and left in `final_layout`.
// Subpass 0 draws the hands; subpass 1 resolves 0 into 2 with a shader rather than a
// resolve attachment: the mean is then always taken in linear space for sRGB formats,
// and the resolve attachment of Mesa 22 (lavapipe, Debian 12) ignores the view's base
// array layer, which would put every eye of an array swapchain into layer 0.
// Render passes differing only in final layout are compatible, so one set of pipelines
// and framebuffers serves all of them.
VkRenderPass create_render_pass(const DeviceContext& context, VkFormat color_format,
                                VkFormat depth_format, VkImageLayout final_layout);

// Matches the push-constant block of primitive.vert.
struct PushConstants {
    std::array<float, 16> view_projection;
    std::array<float, 4> eye_position;
};

struct Pipelines {
    VkPipelineLayout draw_layout = VK_NULL_HANDLE;  // push constants
    // Opaque physical hands: depth tested and written.
    VkPipeline physical = VK_NULL_HANDLE;
    // Translucent ghost, as one layer: its nearest surface is written to depth first,
    // then coloured where depth is EQUAL, so overlapping ghost parts blend once. Both
    // passes carry a depth bias away from the eye so that where the ghost coincides with
    // the physical hand (no contact: the usual case) the physical hand wins, untinted by
    // the ghost.
    VkPipeline ghost_depth = VK_NULL_HANDLE;
    VkPipeline ghost_color = VK_NULL_HANDLE;

    VkDescriptorSetLayout resolve_set_layout = VK_NULL_HANDLE;  // the input attachment
    VkPipelineLayout resolve_layout = VK_NULL_HANDLE;
    VkPipeline resolve = VK_NULL_HANDLE;  // subpass 1: a full-viewport triangle
};

Pipelines create_pipelines(const DeviceContext& context, VkRenderPass render_pass);
void destroy(const DeviceContext& context, Pipelines& pipelines);

}  // namespace physhand::overlay
