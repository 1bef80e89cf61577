#pragma once

#include <vulkan/vulkan.h>

#include "vk_dispatch.h"

namespace physhand::overlay {

// A buffer in host-visible, coherent memory, mapped for its whole life: everything the
// renderer uploads is small (a mesh once, about 10 KB of instances per frame).
struct HostBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize memory_size = 0;  // bytes allocated
    void* mapped = nullptr;
};

HostBuffer create_host_buffer(const DeviceContext& context, VkDeviceSize size,
                              VkBufferUsageFlags usage);
void destroy(const DeviceContext& context, HostBuffer& buffer);

// A multisampled attachment that lives only inside a render pass (cleared at its start,
// discarded at its end), so lazily allocated memory is preferred (tile-based GPUs).
struct TransientAttachment {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize memory_size = 0;  // bytes allocated
    VkImageView view = VK_NULL_HANDLE;
};

TransientAttachment create_transient_attachment(const DeviceContext& context, VkFormat format,
                                                VkExtent2D extent, VkSampleCountFlagBits samples,
                                                VkImageUsageFlags usage, VkImageAspectFlags aspect);
void destroy(const DeviceContext& context, TransientAttachment& attachment);

}  // namespace physhand::overlay
