#include "vulkan_binding.h"

#include <stdexcept>

namespace physhand::layer {

std::optional<VulkanBinding> capture_vulkan_binding(const XrSessionCreateInfo& info) {
    const XrGraphicsBindingVulkanKHR* found = nullptr;
    for (auto* s = static_cast<const XrBaseInStructure*>(info.next); s != nullptr; s = s->next) {
        if (s->type == XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR) {
            found = reinterpret_cast<const XrGraphicsBindingVulkanKHR*>(s);
            break;
        }
    }
    if (found == nullptr) return std::nullopt;
    VulkanBinding binding;
    binding.instance = found->instance;
    // The linked Vulkan loader's: the app created its instance through the same loader.
    binding.get_instance_proc_addr = &vkGetInstanceProcAddr;
    binding.physical_device = found->physicalDevice;
    binding.device = found->device;
    binding.queue_family_index = found->queueFamilyIndex;
    const auto get_device_proc_addr = reinterpret_cast<PFN_vkGetDeviceProcAddr>(
        vkGetInstanceProcAddr(found->instance, "vkGetDeviceProcAddr"));
    if (get_device_proc_addr == nullptr) throw std::runtime_error("no vkGetDeviceProcAddr");
    const auto get_device_queue = reinterpret_cast<PFN_vkGetDeviceQueue>(
        get_device_proc_addr(found->device, "vkGetDeviceQueue"));
    if (get_device_queue == nullptr) throw std::runtime_error("no vkGetDeviceQueue");
    get_device_queue(found->device, found->queueFamilyIndex, found->queueIndex, &binding.queue);
    return binding;
}

}  // namespace physhand::layer
