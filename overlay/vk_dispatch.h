#pragma once

#include <vulkan/vulkan.h>

namespace physhand::overlay {

// Physical-device queries, made once at creation.
#define PHYSHAND_VK_INSTANCE_FUNCTIONS(X)       \
    X(vkGetPhysicalDeviceProperties)            \
    X(vkGetPhysicalDeviceMemoryProperties)      \
    X(vkGetPhysicalDeviceFormatProperties)      \
    X(vkGetPhysicalDeviceImageFormatProperties) \
    X(vkGetPhysicalDeviceQueueFamilyProperties) \
    X(vkGetDeviceProcAddr)

#define PHYSHAND_VK_DEVICE_FUNCTIONS(X) \
    X(vkAllocateCommandBuffers)         \
    X(vkAllocateDescriptorSets)         \
    X(vkAllocateMemory)                 \
    X(vkBeginCommandBuffer)             \
    X(vkBindBufferMemory)               \
    X(vkBindImageMemory)                \
    X(vkCmdBeginRenderPass)             \
    X(vkCmdBindDescriptorSets)          \
    X(vkCmdBindIndexBuffer)             \
    X(vkCmdBindPipeline)                \
    X(vkCmdBindVertexBuffers)           \
    X(vkCmdDraw)                        \
    X(vkCmdDrawIndexed)                 \
    X(vkCmdEndRenderPass)               \
    X(vkCmdNextSubpass)                 \
    X(vkCmdPushConstants)               \
    X(vkCmdResetQueryPool)              \
    X(vkCmdSetScissor)                  \
    X(vkCmdSetViewport)                 \
    X(vkCmdWriteTimestamp)              \
    X(vkCreateBuffer)                   \
    X(vkCreateCommandPool)              \
    X(vkCreateDescriptorPool)           \
    X(vkCreateDescriptorSetLayout)      \
    X(vkCreateFence)                    \
    X(vkCreateFramebuffer)              \
    X(vkCreateGraphicsPipelines)        \
    X(vkCreateImage)                    \
    X(vkCreateImageView)                \
    X(vkCreatePipelineLayout)           \
    X(vkCreateQueryPool)                \
    X(vkCreateRenderPass)               \
    X(vkCreateShaderModule)             \
    X(vkDestroyBuffer)                  \
    X(vkDestroyCommandPool)             \
    X(vkDestroyDescriptorPool)          \
    X(vkDestroyDescriptorSetLayout)     \
    X(vkDestroyFence)                   \
    X(vkDestroyFramebuffer)             \
    X(vkDestroyImage)                   \
    X(vkDestroyImageView)               \
    X(vkDestroyPipeline)                \
    X(vkDestroyPipelineLayout)          \
    X(vkDestroyQueryPool)               \
    X(vkDestroyRenderPass)              \
    X(vkDestroyShaderModule)            \
    X(vkEndCommandBuffer)               \
    X(vkFreeMemory)                     \
    X(vkGetBufferMemoryRequirements)    \
    X(vkGetImageMemoryRequirements)     \
    X(vkGetQueryPoolResults)            \
    X(vkMapMemory)                      \
    X(vkQueueSubmit)                    \
    X(vkResetFences)                    \
    X(vkUpdateDescriptorSets)           \
    X(vkWaitForFences)

// The functions the renderer calls, loaded from the app's instance and device so the
// renderer works whichever loader (or layer chain) the app's Vulkan objects came from.
struct VulkanFunctions {
#define PHYSHAND_VK_DECLARE(name) PFN_##name name = nullptr;
    PHYSHAND_VK_INSTANCE_FUNCTIONS(PHYSHAND_VK_DECLARE)
    PHYSHAND_VK_DEVICE_FUNCTIONS(PHYSHAND_VK_DECLARE)
#undef PHYSHAND_VK_DECLARE
};

// With no instance, the physical-device queries go through the linked loader's exported
// entry points (they dispatch on the physical device alone). Throws std::runtime_error
// naming a function that cannot be loaded.
VulkanFunctions load_vulkan_functions(VkInstance instance,
                                      PFN_vkGetInstanceProcAddr get_instance_proc_addr,
                                      VkDevice device);

// What every part of the renderer needs to create and destroy objects.
struct DeviceContext {
    VulkanFunctions vk;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory_properties{};
};

}  // namespace physhand::overlay
