#include "render_targets.h"

#include <algorithm>
#include <vector>

#include "pipeline.h"
#include "vk_check.h"

namespace physhand::overlay {

namespace {

constexpr VkImageUsageFlags kColorUsage =
    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT;

bool supports_multisampled(const DeviceContext& context, VkFormat format, VkImageUsageFlags usage) {
    VkImageFormatProperties properties{};
    const VkResult result = context.vk.vkGetPhysicalDeviceImageFormatProperties(
        context.physical_device, format, VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
        usage | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT, 0, &properties);
    return result == VK_SUCCESS && (properties.sampleCounts & kSamples) != 0;
}

}  // namespace

void require_color_format(const DeviceContext& context, VkFormat format) {
    if (!supports_multisampled(context, format, kColorUsage)) {
        throw_vulkan_error("multisampled colour attachment format", VK_ERROR_FORMAT_NOT_SUPPORTED);
    }
}

VkFormat choose_depth_format(const DeviceContext& context, VkFormat requested) {
    constexpr VkImageUsageFlags kUsage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    if (requested != VK_FORMAT_UNDEFINED) {
        if (!supports_multisampled(context, requested, kUsage)) {
            throw_vulkan_error("multisampled depth attachment format",
                               VK_ERROR_FORMAT_NOT_SUPPORTED);
        }
        return requested;
    }
    // Vulkan guarantees D16 and one of the other two.
    for (const VkFormat format :
         {VK_FORMAT_D32_SFLOAT, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D16_UNORM}) {
        if (supports_multisampled(context, format, kUsage)) {
            return format;
        }
    }
    throw_vulkan_error("multisampled depth attachment format", VK_ERROR_FORMAT_NOT_SUPPORTED);
}

RenderTargets::RenderTargets(const DeviceContext& context, VkFormat color_format,
                             VkFormat depth_format, VkRenderPass render_pass,
                             VkDescriptorSetLayout resolve_set_layout)
    : context_(context),
      color_format_(color_format),
      depth_format_(depth_format),
      render_pass_(render_pass) {
    const auto& vk = context_.vk;
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1};
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &size;
    PHYSHAND_VK_CHECK(
        vk.vkCreateDescriptorPool(context_.device, &pool_info, nullptr, &descriptor_pool_));
    VkDescriptorSetAllocateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    set_info.descriptorPool = descriptor_pool_;
    set_info.descriptorSetCount = 1;
    set_info.pSetLayouts = &resolve_set_layout;
    if (const VkResult result =
            vk.vkAllocateDescriptorSets(context_.device, &set_info, &resolve_input_);
        result != VK_SUCCESS) {
        vk.vkDestroyDescriptorPool(context_.device, descriptor_pool_, nullptr);
        throw_vulkan_error("vkAllocateDescriptorSets", result);
    }
}

RenderTargets::~RenderTargets() {
    for (Target& target : targets_) {
        destroy_target(target);
    }
    destroy(context_, color_);
    destroy(context_, depth_);
    context_.vk.vkDestroyDescriptorPool(context_.device, descriptor_pool_,
                                        nullptr);  // frees the set
}

const RenderTargets::Target* RenderTargets::find(const View& view) const {
    const auto it = std::find_if(targets_.begin(), targets_.end(), [&](const Target& target) {
        return target.image == view.image && target.array_layer == view.array_layer;
    });
    return it == targets_.end() ? nullptr : &*it;
}

bool RenderTargets::fits(const View& view) const {
    return view.extent.width <= attachment_extent_.width &&
           view.extent.height <= attachment_extent_.height;
}

bool RenderTargets::ready_for(std::span<const View> views) const {
    return std::all_of(views.begin(), views.end(), [&](const View& view) {
        const Target* target = find(view);
        return target != nullptr && target->framebuffer != VK_NULL_HANDLE &&
               target->extent.width == view.extent.width &&
               target->extent.height == view.extent.height && fits(view);
    });
}

void RenderTargets::prepare(std::span<const View> views) {
    const auto& vk = context_.vk;
    if (!std::all_of(views.begin(), views.end(), [&](const View& view) { return fits(view); })) {
        // Every framebuffer refers to the old attachments; they are remade on next use.
        for (Target& target : targets_) {
            vk.vkDestroyFramebuffer(context_.device, target.framebuffer, nullptr);
            target.framebuffer = VK_NULL_HANDLE;
        }
        destroy(context_, color_);
        destroy(context_, depth_);
        VkExtent2D extent = attachment_extent_;
        for (const View& view : views) {
            extent.width = std::max(extent.width, view.extent.width);
            extent.height = std::max(extent.height, view.extent.height);
        }
        color_ = create_transient_attachment(context_, color_format_, extent, kSamples, kColorUsage,
                                             VK_IMAGE_ASPECT_COLOR_BIT);
        depth_ = create_transient_attachment(context_, depth_format_, extent, kSamples,
                                             VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                             VK_IMAGE_ASPECT_DEPTH_BIT);
        const VkDescriptorImageInfo image{VK_NULL_HANDLE, color_.view,
                                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkWriteDescriptorSet write{};
        write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        write.dstSet = resolve_input_;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
        write.pImageInfo = &image;
        vk.vkUpdateDescriptorSets(context_.device, 1, &write, 0, nullptr);
        // Only now: after a failure the next prepare() starts over.
        attachment_extent_ = extent;
    }
    for (const View& view : views) {
        Target* target = find(view);
        if (target == nullptr) {
            target = &targets_.emplace_back(Target{view.image, view.array_layer});
            VkImageViewCreateInfo info{};
            info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
            info.image = view.image;
            info.viewType = VK_IMAGE_VIEW_TYPE_2D;
            info.format = color_format_;
            info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, view.array_layer, 1};
            PHYSHAND_VK_CHECK(vk.vkCreateImageView(context_.device, &info, nullptr, &target->view));
        }
        if (target->framebuffer != VK_NULL_HANDLE &&
            (target->extent.width != view.extent.width ||
             target->extent.height != view.extent.height)) {
            vk.vkDestroyFramebuffer(context_.device, target->framebuffer, nullptr);
            target->framebuffer = VK_NULL_HANDLE;
        }
        if (target->framebuffer == VK_NULL_HANDLE) {
            const VkImageView attachments[] = {color_.view, depth_.view, target->view};
            VkFramebufferCreateInfo info{};
            info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
            info.renderPass = render_pass_;
            info.attachmentCount = 3;
            info.pAttachments = attachments;
            info.width = view.extent.width;
            info.height = view.extent.height;
            info.layers = 1;
            PHYSHAND_VK_CHECK(
                vk.vkCreateFramebuffer(context_.device, &info, nullptr, &target->framebuffer));
            target->extent = view.extent;
        }
    }
}

VkFramebuffer RenderTargets::framebuffer(const View& view) const {
    return find(view)->framebuffer;
}

void RenderTargets::forget(VkImage image) {
    std::erase_if(targets_, [&](Target& target) {
        if (target.image != image) {
            return false;
        }
        destroy_target(target);
        return true;
    });
}

void RenderTargets::destroy_target(Target& target) {
    context_.vk.vkDestroyFramebuffer(context_.device, target.framebuffer, nullptr);
    context_.vk.vkDestroyImageView(context_.device, target.view, nullptr);
    target = {};
}

}  // namespace physhand::overlay
