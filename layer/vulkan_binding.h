#pragma once

#include <vulkan/vulkan.h>
// openxr_platform.h declares the Vulkan binding structs only after vulkan.h, with this.
#ifndef XR_USE_GRAPHICS_API_VULKAN
#define XR_USE_GRAPHICS_API_VULKAN
#endif
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <optional>

// The app's Vulkan objects, captured at xrCreateSession: the overlay renders with them.
namespace physhand::layer {

struct VulkanBinding {
    VkInstance instance = VK_NULL_HANDLE;
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queue_family_index = 0;
    VkQueue queue = VK_NULL_HANDLE;
};

// The XrGraphicsBindingVulkanKHR (the same struct for XR_KHR_vulkan_enable and enable2) in
// the create info's chain, with its queue; nullopt for other graphics APIs and headless
// sessions. Throws std::runtime_error when the Vulkan loader cannot provide the queue.
std::optional<VulkanBinding> capture_vulkan_binding(const XrSessionCreateInfo& info);

}  // namespace physhand::layer
