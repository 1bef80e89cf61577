#include "gpu_memory.h"

#include <cstdint>
#include <optional>

#include "vk_check.h"

namespace physhand::overlay {

namespace {

std::optional<uint32_t> find_memory_type(const VkPhysicalDeviceMemoryProperties& properties,
                                         uint32_t allowed_types, VkMemoryPropertyFlags wanted) {
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
        if ((allowed_types & (1u << i)) != 0 &&
            (properties.memoryTypes[i].propertyFlags & wanted) == wanted) {
            return i;
        }
    }
    return std::nullopt;
}

// The first type with `preferred`, else the first with `required`.
VkDeviceMemory allocate(const DeviceContext& context, const VkMemoryRequirements& requirements,
                        VkMemoryPropertyFlags preferred, VkMemoryPropertyFlags required) {
    std::optional<uint32_t> type =
        find_memory_type(context.memory_properties, requirements.memoryTypeBits, preferred);
    if (!type) {
        type = find_memory_type(context.memory_properties, requirements.memoryTypeBits, required);
    }
    if (!type) {
        throw_vulkan_error("find_memory_type", VK_ERROR_OUT_OF_DEVICE_MEMORY);
    }
    VkMemoryAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = *type;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    PHYSHAND_VK_CHECK(context.vk.vkAllocateMemory(context.device, &info, nullptr, &memory));
    return memory;
}

}  // namespace

HostBuffer create_host_buffer(const DeviceContext& context, VkDeviceSize size,
                              VkBufferUsageFlags usage) {
    const auto& vk = context.vk;
    HostBuffer result;
    try {
        VkBufferCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
        info.size = size;
        info.usage = usage;
        info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        PHYSHAND_VK_CHECK(vk.vkCreateBuffer(context.device, &info, nullptr, &result.buffer));
        VkMemoryRequirements requirements;
        vk.vkGetBufferMemoryRequirements(context.device, result.buffer, &requirements);
        constexpr VkMemoryPropertyFlags kHost =
            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        // Device-local host-visible memory (integrated GPUs, resizable BAR) spares the
        // GPU a read over the bus; plain host memory works everywhere.
        result.memory =
            allocate(context, requirements, kHost | VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, kHost);
        result.memory_size = requirements.size;
        PHYSHAND_VK_CHECK(vk.vkBindBufferMemory(context.device, result.buffer, result.memory, 0));
        PHYSHAND_VK_CHECK(
            vk.vkMapMemory(context.device, result.memory, 0, VK_WHOLE_SIZE, 0, &result.mapped));
    } catch (...) {
        destroy(context, result);
        throw;
    }
    return result;
}

void destroy(const DeviceContext& context, HostBuffer& buffer) {
    // Freeing mapped memory unmaps it.
    context.vk.vkDestroyBuffer(context.device, buffer.buffer, nullptr);
    context.vk.vkFreeMemory(context.device, buffer.memory, nullptr);
    buffer = {};
}

TransientAttachment create_transient_attachment(const DeviceContext& context, VkFormat format,
                                                VkExtent2D extent, VkSampleCountFlagBits samples,
                                                VkImageUsageFlags usage,
                                                VkImageAspectFlags aspect) {
    const auto& vk = context.vk;
    TransientAttachment result;
    try {
        VkImageCreateInfo image_info{};
        image_info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
        image_info.imageType = VK_IMAGE_TYPE_2D;
        image_info.format = format;
        image_info.extent = {extent.width, extent.height, 1};
        image_info.mipLevels = 1;
        image_info.arrayLayers = 1;
        image_info.samples = samples;
        image_info.tiling = VK_IMAGE_TILING_OPTIMAL;
        image_info.usage = usage | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
        image_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        image_info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        PHYSHAND_VK_CHECK(vk.vkCreateImage(context.device, &image_info, nullptr, &result.image));
        VkMemoryRequirements requirements;
        vk.vkGetImageMemoryRequirements(context.device, result.image, &requirements);
        result.memory =
            allocate(context, requirements,
                     VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT,
                     VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        result.memory_size = requirements.size;
        PHYSHAND_VK_CHECK(vk.vkBindImageMemory(context.device, result.image, result.memory, 0));
        VkImageViewCreateInfo view_info{};
        view_info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
        view_info.image = result.image;
        view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view_info.format = format;
        view_info.subresourceRange = {aspect, 0, 1, 0, 1};
        PHYSHAND_VK_CHECK(vk.vkCreateImageView(context.device, &view_info, nullptr, &result.view));
    } catch (...) {
        destroy(context, result);
        throw;
    }
    return result;
}

void destroy(const DeviceContext& context, TransientAttachment& attachment) {
    context.vk.vkDestroyImageView(context.device, attachment.view, nullptr);
    context.vk.vkDestroyImage(context.device, attachment.image, nullptr);
    context.vk.vkFreeMemory(context.device, attachment.memory, nullptr);
    attachment = {};
}

}  // namespace physhand::overlay
