#pragma once

#include <vulkan/vulkan.h>
// After vulkan.h; the build defines XR_USE_GRAPHICS_API_VULKAN.
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <cstdint>

namespace physhand::sample {

// Throws std::runtime_error naming the call and its VkResult unless it succeeded.
void vk_check(VkResult result, const char* call);

// The Vulkan instance, device and graphics queue an XR_KHR_vulkan_enable2 runtime asks for,
// made through the runtime (xrCreateVulkanInstanceKHR, xrCreateVulkanDeviceKHR) so that it
// can add what it needs; the physical device is the one it names.
class VulkanDevice {
  public:
    // Throws XrCallError or std::runtime_error for a failed call.
    VulkanDevice(XrInstance instance, XrSystemId system);
    ~VulkanDevice();
    VulkanDevice(const VulkanDevice&) = delete;
    VulkanDevice& operator=(const VulkanDevice&) = delete;

    // What xrCreateSession chains to bind the session to this device.
    XrGraphicsBindingVulkan2KHR binding() const;

    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    std::uint32_t queue_family() const { return queue_family_; }
    // The depth format the device renders to, the most precise of those tried.
    VkFormat depth_format() const { return depth_format_; }
    // Memory for `requirements` of a type with `flags`; throws when there is none.
    VkDeviceMemory allocate(const VkMemoryRequirements& requirements,
                            VkMemoryPropertyFlags flags) const;

  private:
    VkInstance instance_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queue_family_ = 0;
    VkPhysicalDeviceMemoryProperties memory_{};
    VkFormat depth_format_ = VK_FORMAT_UNDEFINED;
};

}  // namespace physhand::sample
