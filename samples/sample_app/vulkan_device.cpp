#include "vulkan_device.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "xr_check.h"

namespace physhand::sample {

namespace {

// D32_SFLOAT first, for depth precision with the near plane at 2 cm, but it is optional;
// Vulkan guarantees only D16_UNORM.
VkFormat pick_depth_format(VkPhysicalDevice device) {
    for (const VkFormat format : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D32_SFLOAT_S8_UINT,
                                  VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D16_UNORM}) {
        VkFormatProperties properties{};
        vkGetPhysicalDeviceFormatProperties(device, format, &properties);
        if ((properties.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) !=
            0) {
            return format;
        }
    }
    throw std::runtime_error(
        "the Vulkan device renders to none of the depth formats D32_SFLOAT, "
        "D32_SFLOAT_S8_UINT, X8_D24_UNORM_PACK32, D16_UNORM");
}

}  // namespace

void vk_check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) {
        throw std::runtime_error(std::string(call) + " failed with VkResult " +
                                 std::to_string(result));
    }
}

VulkanDevice::VulkanDevice(XrInstance instance, XrSystemId system) {
    // Required before any other XR_KHR_vulkan_enable2 call; Vulkan 1.1 meets every runtime
    // that asks for 1.0 or 1.1.
    XrGraphicsRequirementsVulkan2KHR requirements{};
    requirements.type = XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR;
    xr_check(instance,
             load_function<PFN_xrGetVulkanGraphicsRequirements2KHR>(
                 instance, "xrGetVulkanGraphicsRequirements2KHR")(instance, system, &requirements),
             "xrGetVulkanGraphicsRequirements2KHR");
    if (requirements.minApiVersionSupported > XR_MAKE_VERSION(1, 1, 0)) {
        throw std::runtime_error("the runtime needs a Vulkan newer than 1.1");
    }

    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "physhand-sample";
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo instance_info{};
    instance_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    instance_info.pApplicationInfo = &app;
    XrVulkanInstanceCreateInfoKHR xr_instance_info{};
    xr_instance_info.type = XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR;
    xr_instance_info.systemId = system;
    xr_instance_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr_instance_info.vulkanCreateInfo = &instance_info;
    VkResult result = VK_SUCCESS;
    xr_check(instance,
             load_function<PFN_xrCreateVulkanInstanceKHR>(instance, "xrCreateVulkanInstanceKHR")(
                 instance, &xr_instance_info, &instance_, &result),
             "xrCreateVulkanInstanceKHR");
    vk_check(result, "vkCreateInstance");

    try {
        XrVulkanGraphicsDeviceGetInfoKHR device_get_info{};
        device_get_info.type = XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR;
        device_get_info.systemId = system;
        device_get_info.vulkanInstance = instance_;
        xr_check(instance,
                 load_function<PFN_xrGetVulkanGraphicsDevice2KHR>(
                     instance, "xrGetVulkanGraphicsDevice2KHR")(instance, &device_get_info,
                                                                &physical_device_),
                 "xrGetVulkanGraphicsDevice2KHR");
        vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_);
        depth_format_ = pick_depth_format(physical_device_);

        std::uint32_t count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, nullptr);
        std::vector<VkQueueFamilyProperties> families(count);
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, families.data());
        while (queue_family_ < count &&
               (families[queue_family_].queueFlags & VK_QUEUE_GRAPHICS_BIT) == 0) {
            ++queue_family_;
        }
        if (queue_family_ == count) throw std::runtime_error("the Vulkan device has no graphics");
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo queue_info{};
        queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
        queue_info.queueFamilyIndex = queue_family_;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        VkDeviceCreateInfo device_info{};
        device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        XrVulkanDeviceCreateInfoKHR xr_device_info{};
        xr_device_info.type = XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR;
        xr_device_info.systemId = system;
        xr_device_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        xr_device_info.vulkanPhysicalDevice = physical_device_;
        xr_device_info.vulkanCreateInfo = &device_info;
        xr_check(instance,
                 load_function<PFN_xrCreateVulkanDeviceKHR>(instance, "xrCreateVulkanDeviceKHR")(
                     instance, &xr_device_info, &device_, &result),
                 "xrCreateVulkanDeviceKHR");
        vk_check(result, "vkCreateDevice");
        vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
    } catch (...) {
        vkDestroyInstance(instance_, nullptr);
        throw;
    }
}

VulkanDevice::~VulkanDevice() {
    vkDestroyDevice(device_, nullptr);
    vkDestroyInstance(instance_, nullptr);
}

XrGraphicsBindingVulkan2KHR VulkanDevice::binding() const {
    XrGraphicsBindingVulkan2KHR binding{};
    binding.type = XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR;
    binding.instance = instance_;
    binding.physicalDevice = physical_device_;
    binding.device = device_;
    binding.queueFamilyIndex = queue_family_;
    binding.queueIndex = 0;
    return binding;
}

VkDeviceMemory VulkanDevice::allocate(const VkMemoryRequirements& requirements,
                                      VkMemoryPropertyFlags flags) const {
    for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
        if ((requirements.memoryTypeBits & (1u << i)) == 0 ||
            (memory_.memoryTypes[i].propertyFlags & flags) != flags) {
            continue;
        }
        VkMemoryAllocateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
        info.allocationSize = requirements.size;
        info.memoryTypeIndex = i;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        vk_check(vkAllocateMemory(device_, &info, nullptr, &memory), "vkAllocateMemory");
        return memory;
    }
    throw std::runtime_error("no Vulkan memory type fits");
}

}  // namespace physhand::sample
