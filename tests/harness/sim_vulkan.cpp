// XR_KHR_vulkan_enable2 and XR_KHR_vulkan_enable: the application's Vulkan instance and
// device, and the session's hold on them. The runtime needs nothing beyond core Vulkan 1.0
// (it only copies images to a buffer), so it adds no Vulkan extension anywhere.

#include <dlfcn.h>

#include <string>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

// The Vulkan versions the runtime has been tried with (it needs only 1.0).
constexpr XrVersion kMinVulkanVersion = XR_MAKE_VERSION(1, 0, 0);
constexpr XrVersion kMaxVulkanVersion = XR_MAKE_VERSION(1, 3, 0);

PFN_vkGetInstanceProcAddr loader_or_throw() {
    PFN_vkGetInstanceProcAddr get = vulkan_loader();
    if (get == nullptr) throw std::runtime_error("cannot load libvulkan.so.1");
    return get;
}

template <typename Pfn>
Pfn instance_function(VkInstance instance, const char* name) {
    auto fn = reinterpret_cast<Pfn>(loader_or_throw()(instance, name));
    if (fn == nullptr) throw std::runtime_error(std::string("Vulkan has no ") + name);
    return fn;
}

XrResult check_system(Runtime& rt, XrInstance instance, XrSystemId systemId, InstanceData** data) {
    *data = rt.instances.find(instance);
    if (*data == nullptr) return XR_ERROR_HANDLE_INVALID;
    return systemId == kSystemId ? XR_SUCCESS : XR_ERROR_SYSTEM_INVALID;
}

XrResult graphics_requirements(XrInstance instance, XrSystemId systemId,
                               XrGraphicsRequirementsVulkanKHR* graphicsRequirements) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = nullptr;
        if (XrResult result = check_system(rt, instance, systemId, &data); XR_FAILED(result)) {
            return result;
        }
        if (!has_type(graphicsRequirements, XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN_KHR)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        graphicsRequirements->minApiVersionSupported = kMinVulkanVersion;
        graphicsRequirements->maxApiVersionSupported = kMaxVulkanVersion;
        data->vulkan.requirements_queried = true;
        return XR_SUCCESS;
    });
}

// The first physical device of the application's instance: lavapipe where
// VK_ICD_FILENAMES names only it, as in the tests. Remembered for xrCreateSession.
XrResult graphics_device(XrInstance instance, XrSystemId systemId, VkInstance vulkanInstance,
                         VkPhysicalDevice* vulkanPhysicalDevice) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = nullptr;
        if (XrResult result = check_system(rt, instance, systemId, &data); XR_FAILED(result)) {
            return result;
        }
        if (vulkanInstance == VK_NULL_HANDLE || vulkanPhysicalDevice == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        auto enumerate = instance_function<PFN_vkEnumeratePhysicalDevices>(
            vulkanInstance, "vkEnumeratePhysicalDevices");
        std::uint32_t count = 1;
        VkPhysicalDevice first = VK_NULL_HANDLE;
        VkResult result = enumerate(vulkanInstance, &count, &first);
        if (result != VK_INCOMPLETE) check_vk(result, "vkEnumeratePhysicalDevices");
        if (count == 0) throw std::runtime_error("Vulkan has no physical device");
        data->vulkan.instance = vulkanInstance;
        data->vulkan.physical_device = first;
        *vulkanPhysicalDevice = first;
        return XR_SUCCESS;
    });
}

// XR_KHR_vulkan_enable's space-separated lists of the Vulkan extensions the runtime needs:
// none.
XrResult no_extensions(XrInstance instance, XrSystemId systemId, uint32_t bufferCapacityInput,
                       uint32_t* bufferCountOutput, char* buffer) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = nullptr;
        if (XrResult result = check_system(rt, instance, systemId, &data); XR_FAILED(result)) {
            return result;
        }
        return fill_array(bufferCapacityInput, bufferCountOutput, buffer, 1,
                          [](char& out, uint32_t) {
                              out = '\0';
                              return XR_SUCCESS;
                          });
    });
}

}  // namespace

VulkanError::VulkanError(const char* call, VkResult result)
    : std::runtime_error(std::string(call) + " failed with VkResult " + std::to_string(result)) {}

PFN_vkGetInstanceProcAddr vulkan_loader() {
    // Opened once and never closed: the application's Vulkan objects live in this loader.
    static const PFN_vkGetInstanceProcAddr get = [] {
        void* library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
        return library == nullptr ? nullptr
                                  : reinterpret_cast<PFN_vkGetInstanceProcAddr>(
                                        dlsym(library, "vkGetInstanceProcAddr"));
    }();
    return get;
}

// ---- VulkanSession ----------------------------------------------------------------------

VulkanSession::VulkanSession(const XrGraphicsBindingVulkanKHR& binding)
    : physical_device_(binding.physicalDevice), device_(binding.device) {
    get_memory_properties_ = instance_function<PFN_vkGetPhysicalDeviceMemoryProperties>(
        binding.instance, "vkGetPhysicalDeviceMemoryProperties");
    get_image_format_properties_ = instance_function<PFN_vkGetPhysicalDeviceImageFormatProperties>(
        binding.instance, "vkGetPhysicalDeviceImageFormatProperties");
    auto get_device_function =
        instance_function<PFN_vkGetDeviceProcAddr>(binding.instance, "vkGetDeviceProcAddr");
#define PHYSHAND_SIM_LOAD(name)                                                   \
    fn_.name = reinterpret_cast<PFN_##name>(get_device_function(device_, #name)); \
    if (fn_.name == nullptr) throw std::runtime_error("the Vulkan device has no " #name);
    PHYSHAND_SIM_DEVICE_FUNCTIONS(PHYSHAND_SIM_LOAD)
#undef PHYSHAND_SIM_LOAD

    fn_.vkGetDeviceQueue(device_, binding.queueFamilyIndex, binding.queueIndex, &queue_);
    try {
        auto pool_info =
            vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = binding.queueFamilyIndex;
        check_vk(fn_.vkCreateCommandPool(device_, &pool_info, nullptr, &pool_),
                 "vkCreateCommandPool");
        auto allocate_info =
            vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        allocate_info.commandPool = pool_;
        allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate_info.commandBufferCount = 1;
        check_vk(fn_.vkAllocateCommandBuffers(device_, &allocate_info, &commands_),
                 "vkAllocateCommandBuffers");
        auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        check_vk(fn_.vkCreateFence(device_, &fence_info, nullptr, &fence_), "vkCreateFence");
    } catch (...) {
        destroy();
        throw;
    }
}

VulkanSession::~VulkanSession() {
    destroy();
}

void VulkanSession::destroy() {
    free_readback();
    if (fence_ != VK_NULL_HANDLE) fn_.vkDestroyFence(device_, fence_, nullptr);
    if (pool_ != VK_NULL_HANDLE) fn_.vkDestroyCommandPool(device_, pool_, nullptr);
    fence_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
}

bool VulkanSession::supports(const VkImageCreateInfo& info) const {
    VkImageFormatProperties properties;
    if (get_image_format_properties_(physical_device_, info.format, info.imageType, info.tiling,
                                     info.usage, info.flags, &properties) != VK_SUCCESS) {
        return false;
    }
    return info.extent.width <= properties.maxExtent.width &&
           info.extent.height <= properties.maxExtent.height &&
           info.mipLevels <= properties.maxMipLevels &&
           info.arrayLayers <= properties.maxArrayLayers &&
           (info.samples & properties.sampleCounts) != 0;
}

std::optional<std::uint32_t> VulkanSession::memory_type(std::uint32_t allowed_types,
                                                        VkMemoryPropertyFlags wanted) const {
    VkPhysicalDeviceMemoryProperties properties;
    get_memory_properties_(physical_device_, &properties);
    for (std::uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
        if ((allowed_types & (1u << i)) != 0 &&
            (properties.memoryTypes[i].propertyFlags & wanted) == wanted) {
            return i;
        }
    }
    return std::nullopt;
}

void VulkanSession::begin_commands() {
    check_vk(fn_.vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check_vk(fn_.vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
}

void VulkanSession::submit_and_wait() {
    check_vk(fn_.vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
    auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands_;
    check_vk(fn_.vkQueueSubmit(queue_, 1, &submit, fence_), "vkQueueSubmit");
    check_vk(fn_.vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check_vk(fn_.vkResetFences(device_, 1, &fence_), "vkResetFences");
}

VkBuffer VulkanSession::readback_buffer(VkDeviceSize size) {
    if (size <= readback_size_) return readback_;
    free_readback();
    auto buffer_info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    buffer_info.size = size;
    buffer_info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    buffer_info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check_vk(fn_.vkCreateBuffer(device_, &buffer_info, nullptr, &readback_), "vkCreateBuffer");
    VkMemoryRequirements requirements;
    fn_.vkGetBufferMemoryRequirements(device_, readback_, &requirements);
    // Coherent, so the host reads what the copy wrote without invalidating ranges; Vulkan
    // guarantees such a memory type for buffers.
    auto allocate = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    allocate.allocationSize = requirements.size;
    allocate.memoryTypeIndex =
        memory_type(requirements.memoryTypeBits,
                    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT)
            .value();
    check_vk(fn_.vkAllocateMemory(device_, &allocate, nullptr, &readback_memory_),
             "vkAllocateMemory");
    check_vk(fn_.vkBindBufferMemory(device_, readback_, readback_memory_, 0), "vkBindBufferMemory");
    void* mapped = nullptr;
    check_vk(fn_.vkMapMemory(device_, readback_memory_, 0, VK_WHOLE_SIZE, 0, &mapped),
             "vkMapMemory");
    readback_data_ = static_cast<const std::uint8_t*>(mapped);
    readback_size_ = size;
    return readback_;
}

void VulkanSession::free_readback() {
    // Freeing the memory unmaps it.
    if (readback_ != VK_NULL_HANDLE) fn_.vkDestroyBuffer(device_, readback_, nullptr);
    if (readback_memory_ != VK_NULL_HANDLE) fn_.vkFreeMemory(device_, readback_memory_, nullptr);
    readback_ = VK_NULL_HANDLE;
    readback_memory_ = VK_NULL_HANDLE;
    readback_size_ = 0;
    readback_data_ = nullptr;
}

VkImageMemoryBarrier layout_barrier(VkImage image, const VkImageSubresourceRange& range,
                                    VkImageLayout from, VkImageLayout to) {
    auto barrier = vk_struct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = range;
    return barrier;
}

// ---- SwapchainImages --------------------------------------------------------------------

SwapchainImages::SwapchainImages(const VulkanSession& vulkan, const VkImageCreateInfo& info,
                                 std::uint32_t count)
    : vulkan_(vulkan) {
    const DeviceFunctions& fn = vulkan.fn();
    try {
        for (std::uint32_t i = 0; i < count; ++i) {
            VkImage image = VK_NULL_HANDLE;
            check_vk(fn.vkCreateImage(vulkan.device(), &info, nullptr, &image), "vkCreateImage");
            images_.push_back(image);
            VkMemoryRequirements requirements;
            fn.vkGetImageMemoryRequirements(vulkan.device(), image, &requirements);
            auto allocate = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
            allocate.allocationSize = requirements.size;
            allocate.memoryTypeIndex =
                vulkan.memory_type(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)
                    .value_or(vulkan.memory_type(requirements.memoryTypeBits, 0).value());
            VkDeviceMemory memory = VK_NULL_HANDLE;
            check_vk(fn.vkAllocateMemory(vulkan.device(), &allocate, nullptr, &memory),
                     "vkAllocateMemory");
            memory_.push_back(memory);
            check_vk(fn.vkBindImageMemory(vulkan.device(), image, memory, 0), "vkBindImageMemory");
        }
    } catch (...) {
        destroy();
        throw;
    }
}

SwapchainImages::~SwapchainImages() {
    destroy();
}

void SwapchainImages::destroy() {
    for (VkImage image : images_) vulkan_.fn().vkDestroyImage(vulkan_.device(), image, nullptr);
    for (VkDeviceMemory memory : memory_) {
        vulkan_.fn().vkFreeMemory(vulkan_.device(), memory, nullptr);
    }
    images_.clear();
    memory_.clear();
}

// ---- sessions ---------------------------------------------------------------------------

XrResult open_vulkan_session(const InstanceData& instance,
                             const XrGraphicsBindingVulkanKHR& binding,
                             std::unique_ptr<VulkanSession>* vulkan) {
    if (!instance.vulkan_enable && !instance.vulkan_enable2) {
        return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    }
    if (!instance.vulkan.requirements_queried) return XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING;
    if (binding.instance == VK_NULL_HANDLE || binding.device == VK_NULL_HANDLE ||
        binding.physicalDevice != instance.vulkan.physical_device) {
        return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    }
    auto get_families = instance_function<PFN_vkGetPhysicalDeviceQueueFamilyProperties>(
        binding.instance, "vkGetPhysicalDeviceQueueFamilyProperties");
    std::uint32_t count = 0;
    get_families(binding.physicalDevice, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    get_families(binding.physicalDevice, &count, families.data());
    if (binding.queueFamilyIndex >= count ||
        binding.queueIndex >= families[binding.queueFamilyIndex].queueCount) {
        return XR_ERROR_VALIDATION_FAILURE;
    }
    *vulkan = std::make_unique<VulkanSession>(binding);
    return XR_SUCCESS;
}

// ---- XR_KHR_vulkan_enable2 --------------------------------------------------------------

XrResult xrGetVulkanGraphicsRequirements2KHR(
    XrInstance instance, XrSystemId systemId,
    XrGraphicsRequirementsVulkanKHR* graphicsRequirements) {
    return graphics_requirements(instance, systemId, graphicsRequirements);
}

// The VkResult of vkCreateInstance comes back in vulkanResult; the call itself succeeded
// when it got as far as making it.
XrResult xrCreateVulkanInstanceKHR(XrInstance instance,
                                   const XrVulkanInstanceCreateInfoKHR* createInfo,
                                   VkInstance* vulkanInstance, VkResult* vulkanResult) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR) ||
            createInfo->createFlags != 0 || createInfo->pfnGetInstanceProcAddr == nullptr ||
            createInfo->vulkanCreateInfo == nullptr || vulkanInstance == nullptr ||
            vulkanResult == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (createInfo->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
        auto create = reinterpret_cast<PFN_vkCreateInstance>(
            createInfo->pfnGetInstanceProcAddr(VK_NULL_HANDLE, "vkCreateInstance"));
        if (create == nullptr) return XR_ERROR_RUNTIME_FAILURE;
        *vulkanResult =
            create(createInfo->vulkanCreateInfo, createInfo->vulkanAllocator, vulkanInstance);
        return XR_SUCCESS;
    });
}

XrResult xrGetVulkanGraphicsDevice2KHR(XrInstance instance,
                                       const XrVulkanGraphicsDeviceGetInfoKHR* getInfo,
                                       VkPhysicalDevice* vulkanPhysicalDevice) {
    if (!has_type(getInfo, XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR)) {
        return XR_ERROR_VALIDATION_FAILURE;
    }
    return graphics_device(instance, getInfo->systemId, getInfo->vulkanInstance,
                           vulkanPhysicalDevice);
}

XrResult xrCreateVulkanDeviceKHR(XrInstance instance, const XrVulkanDeviceCreateInfoKHR* createInfo,
                                 VkDevice* vulkanDevice, VkResult* vulkanResult) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR) ||
            createInfo->createFlags != 0 || createInfo->pfnGetInstanceProcAddr == nullptr ||
            createInfo->vulkanCreateInfo == nullptr || vulkanDevice == nullptr ||
            vulkanResult == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (createInfo->systemId != kSystemId) return XR_ERROR_SYSTEM_INVALID;
        // The specification's answer for a device other than xrGetVulkanGraphicsDevice2KHR's.
        if (createInfo->vulkanPhysicalDevice == VK_NULL_HANDLE ||
            createInfo->vulkanPhysicalDevice != data->vulkan.physical_device) {
            return XR_ERROR_HANDLE_INVALID;
        }
        auto create = reinterpret_cast<PFN_vkCreateDevice>(
            createInfo->pfnGetInstanceProcAddr(data->vulkan.instance, "vkCreateDevice"));
        if (create == nullptr) return XR_ERROR_RUNTIME_FAILURE;
        *vulkanResult = create(createInfo->vulkanPhysicalDevice, createInfo->vulkanCreateInfo,
                               createInfo->vulkanAllocator, vulkanDevice);
        return XR_SUCCESS;
    });
}

// ---- XR_KHR_vulkan_enable ---------------------------------------------------------------

XrResult xrGetVulkanInstanceExtensionsKHR(XrInstance instance, XrSystemId systemId,
                                          uint32_t bufferCapacityInput, uint32_t* bufferCountOutput,
                                          char* buffer) {
    return no_extensions(instance, systemId, bufferCapacityInput, bufferCountOutput, buffer);
}

XrResult xrGetVulkanDeviceExtensionsKHR(XrInstance instance, XrSystemId systemId,
                                        uint32_t bufferCapacityInput, uint32_t* bufferCountOutput,
                                        char* buffer) {
    return no_extensions(instance, systemId, bufferCapacityInput, bufferCountOutput, buffer);
}

XrResult xrGetVulkanGraphicsDeviceKHR(XrInstance instance, XrSystemId systemId,
                                      VkInstance vkInstance, VkPhysicalDevice* vkPhysicalDevice) {
    return graphics_device(instance, systemId, vkInstance, vkPhysicalDevice);
}

XrResult xrGetVulkanGraphicsRequirementsKHR(XrInstance instance, XrSystemId systemId,
                                            XrGraphicsRequirementsVulkanKHR* graphicsRequirements) {
    return graphics_requirements(instance, systemId, graphicsRequirements);
}

}  // namespace physhand::sim
