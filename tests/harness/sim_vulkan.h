#pragma once

// The Vulkan side of the simulated runtime: the system's Vulkan loader, opened at first
// use, and the application's device as a session's graphics binding names it.

// Vulkan types only (the build defines VK_NO_PROTOTYPES): the runtime loads Vulkan itself.
#include <vulkan/vulkan.h>
// After vulkan.h; the build defines XR_USE_GRAPHICS_API_VULKAN.
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

namespace physhand::sim {

// A failed Vulkan call inside an entry point; guarded() turns it into
// XR_ERROR_RUNTIME_FAILURE and prints it.
class VulkanError : public std::runtime_error {
  public:
    VulkanError(const char* call, VkResult result);
};

inline void check_vk(VkResult result, const char* call) {
    if (result != VK_SUCCESS) throw VulkanError(call, result);
}

// A zeroed Vulkan struct carrying its sType (`VkFoo x{VK_STRUCTURE_TYPE_FOO}` trips
// -Wmissing-field-initializers).
template <typename T>
T vk_struct(VkStructureType type) {
    T s{};
    s.sType = type;
    return s;
}

// vkGetInstanceProcAddr of the system's Vulkan loader (libvulkan.so.1), or nullptr when
// there is none: headless sessions must keep working on machines without Vulkan.
PFN_vkGetInstanceProcAddr vulkan_loader();

// The device-level functions the runtime calls on the application's device.
#define PHYSHAND_SIM_DEVICE_FUNCTIONS(X) \
    X(vkGetDeviceQueue)                  \
    X(vkCreateImage)                     \
    X(vkDestroyImage)                    \
    X(vkGetImageMemoryRequirements)      \
    X(vkCreateBuffer)                    \
    X(vkDestroyBuffer)                   \
    X(vkGetBufferMemoryRequirements)     \
    X(vkAllocateMemory)                  \
    X(vkFreeMemory)                      \
    X(vkBindImageMemory)                 \
    X(vkBindBufferMemory)                \
    X(vkMapMemory)                       \
    X(vkCreateCommandPool)               \
    X(vkDestroyCommandPool)              \
    X(vkAllocateCommandBuffers)          \
    X(vkResetCommandBuffer)              \
    X(vkBeginCommandBuffer)              \
    X(vkEndCommandBuffer)                \
    X(vkCmdPipelineBarrier)              \
    X(vkCmdCopyImageToBuffer)            \
    X(vkQueueSubmit)                     \
    X(vkCreateFence)                     \
    X(vkDestroyFence)                    \
    X(vkWaitForFences)                   \
    X(vkResetFences)

struct DeviceFunctions {
#define PHYSHAND_SIM_DECLARE(name) PFN_##name name = nullptr;
    PHYSHAND_SIM_DEVICE_FUNCTIONS(PHYSHAND_SIM_DECLARE)
#undef PHYSHAND_SIM_DECLARE
};

// The application's device and queue from XrGraphicsBindingVulkanKHR, with what the
// runtime keeps on them: one command buffer and fence for its own short submissions, and
// a host-visible buffer that composited images are read back into.
class VulkanSession {
  public:
    // Throws VulkanError when the device cannot be used.
    explicit VulkanSession(const XrGraphicsBindingVulkanKHR& binding);
    ~VulkanSession();
    VulkanSession(const VulkanSession&) = delete;
    VulkanSession& operator=(const VulkanSession&) = delete;

    const DeviceFunctions& fn() const { return fn_; }
    VkDevice device() const { return device_; }

    // Whether the device can create an image like this one.
    bool supports(const VkImageCreateInfo& info) const;
    // The first memory type among allowed_types that has all the wanted flags.
    std::optional<std::uint32_t> memory_type(std::uint32_t allowed_types,
                                             VkMemoryPropertyFlags wanted) const;

    // Records commands with record(VkCommandBuffer), submits them to the application's
    // queue and waits for them: the application synchronises that queue around the frame
    // and swapchain calls that use it.
    template <typename Record>
    void submit(Record&& record) {
        begin_commands();
        record(commands_);
        submit_and_wait();
    }

    // A mapped host-visible buffer of at least `size` bytes, grown as needed.
    VkBuffer readback_buffer(VkDeviceSize size);
    const std::uint8_t* readback_data() const { return readback_data_; }

  private:
    void begin_commands();
    void submit_and_wait();
    void free_readback();
    void destroy();

    VkPhysicalDevice physical_device_;
    VkDevice device_;
    PFN_vkGetPhysicalDeviceMemoryProperties get_memory_properties_ = nullptr;
    PFN_vkGetPhysicalDeviceImageFormatProperties get_image_format_properties_ = nullptr;
    DeviceFunctions fn_;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    VkBuffer readback_ = VK_NULL_HANDLE;
    VkDeviceMemory readback_memory_ = VK_NULL_HANDLE;
    VkDeviceSize readback_size_ = 0;
    const std::uint8_t* readback_data_ = nullptr;
};

// A barrier taking a range of an image from one layout to another, after all earlier work
// and before all later work: the runtime's few transitions gain nothing from finer masks.
VkImageMemoryBarrier layout_barrier(VkImage image, const VkImageSubresourceRange& range,
                                    VkImageLayout from, VkImageLayout to);

// The images of one swapchain, each with its own device memory, freed with the object.
class SwapchainImages {
  public:
    // Throws VulkanError; creates nothing then.
    SwapchainImages(const VulkanSession& vulkan, const VkImageCreateInfo& info,
                    std::uint32_t count);
    ~SwapchainImages();
    SwapchainImages(const SwapchainImages&) = delete;
    SwapchainImages& operator=(const SwapchainImages&) = delete;

    const std::vector<VkImage>& images() const { return images_; }

  private:
    void destroy();

    const VulkanSession& vulkan_;
    std::vector<VkImage> images_;
    std::vector<VkDeviceMemory> memory_;
};

}  // namespace physhand::sim
