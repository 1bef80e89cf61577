#include "headless_vulkan.h"

#include <algorithm>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace physhand::overlay::testing {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) {
        throw std::runtime_error(std::string(what) + " failed: VkResult " + std::to_string(result));
    }
}

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT type,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data,
                                          void* user) {
    const std::string message = data->pMessage != nullptr ? data->pMessage : "";
    // Drivers and the loader remark through the messenger too, as GENERAL warnings
    // (lavapipe warns about the Invariant decoration glslang puts on gl_Position, which
    // spirv-val accepts): shown, not counted.
    if (type == VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT &&
        severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        std::cerr << "note: " << message << "\n";
    } else {
        static_cast<ValidationMessages*>(user)->add(message);
    }
    return VK_FALSE;  // never abort the call: the test reports the message instead
}

bool has_layer(std::string_view name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& layer) { return name == layer.layerName; });
}

uint32_t memory_type(VkPhysicalDevice physical_device, uint32_t allowed,
                     VkMemoryPropertyFlags wanted) {
    VkPhysicalDeviceMemoryProperties properties;
    vkGetPhysicalDeviceMemoryProperties(physical_device, &properties);
    for (uint32_t i = 0; i < properties.memoryTypeCount; ++i) {
        if ((allowed & (1u << i)) != 0 &&
            (properties.memoryTypes[i].propertyFlags & wanted) == wanted) {
            return i;
        }
    }
    throw std::runtime_error("no suitable memory type");
}

VkDeviceMemory allocate(VkDevice device, VkPhysicalDevice physical_device,
                        const VkMemoryRequirements& requirements, VkMemoryPropertyFlags wanted) {
    VkMemoryAllocateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = memory_type(physical_device, requirements.memoryTypeBits, wanted);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(device, &info, nullptr, &memory), "vkAllocateMemory");
    return memory;
}

VkImageMemoryBarrier layout_barrier(VkImage image, VkImageLayout from, VkImageLayout to,
                                    VkAccessFlags src_access, VkAccessFlags dst_access,
                                    uint32_t first_layer, uint32_t layers) {
    VkImageMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    barrier.srcAccessMask = src_access;
    barrier.dstAccessMask = dst_access;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, first_layer, layers};
    return barrier;
}

// Whatever the layout's last user was (the renderer's resolve, a clear, a copy).
constexpr VkPipelineStageFlags kAnyWriteStage =
    VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
constexpr VkAccessFlags kAnyWrite =
    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;

// The loader unloads the driver and layers with the last instance, and they keep
// allocations in globals (lavapipe and the validation layer do), which LeakSanitizer then
// reports once the libraries are unmapped. One instance with the same layers, living as
// long as the process, keeps them mapped.
void keep_loaded(const VkInstanceCreateInfo& like) {
    static const VkInstance keeper = [&] {
        VkInstanceCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
        info.enabledLayerCount = like.enabledLayerCount;
        info.ppEnabledLayerNames = like.ppEnabledLayerNames;
        VkInstance instance = VK_NULL_HANDLE;
        vkCreateInstance(&info, nullptr, &instance);
        return instance;
    }();
    (void)keeper;
}

}  // namespace

void ValidationMessages::add(std::string message) {
    const std::lock_guard lock(mutex_);
    messages_.push_back(std::move(message));
}

std::vector<std::string> ValidationMessages::take() {
    const std::lock_guard lock(mutex_);
    return std::exchange(messages_, {});
}

Rgba Pixels::at(uint32_t x, uint32_t y) const {
    const uint8_t* p = &bytes[(static_cast<size_t>(y) * width + x) * 4];
    return {p[0], p[1], p[2], p[3]};
}

std::unique_ptr<HeadlessVulkan> HeadlessVulkan::create(bool validation,
                                                       ValidationMessages* messages,
                                                       std::string& reason) {
    std::unique_ptr<HeadlessVulkan> vulkan(new HeadlessVulkan);
    const bool validate = validation && messages != nullptr && has_layer(kValidationLayer);

    VkDebugUtilsMessengerCreateInfoEXT messenger_info{};
    messenger_info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                     VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messenger_info.pfnUserCallback = on_message;
    messenger_info.pUserData = messages;

    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "physhand overlay tests";
    app.apiVersion = VK_API_VERSION_1_0;  // the renderer needs nothing newer
    const char* layers[] = {kValidationLayer};
    // Both extensions come with the validation layer.
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME,
                                VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME};
    // Synchronisation validation as well: the renderer's subpass dependencies and frame
    // ring are what it checks.
    const VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{};
    features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    VkInstanceCreateInfo instance_info{};
    instance_info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    instance_info.pApplicationInfo = &app;
    if (validate) {
        // The messenger is chained too, so instance creation and destruction are checked.
        features.pNext = &messenger_info;
        instance_info.pNext = &features;
        instance_info.enabledLayerCount = 1;
        instance_info.ppEnabledLayerNames = layers;
        instance_info.enabledExtensionCount = 2;
        instance_info.ppEnabledExtensionNames = extensions;
    }
    keep_loaded(instance_info);
    if (const VkResult result = vkCreateInstance(&instance_info, nullptr, &vulkan->instance_);
        result != VK_SUCCESS) {
        reason = "vkCreateInstance: VkResult " + std::to_string(result);
        return nullptr;
    }
    if (validate) {
        const auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(vulkan->instance_, "vkCreateDebugUtilsMessengerEXT"));
        check(create_messenger(vulkan->instance_, &messenger_info, nullptr, &vulkan->messenger_),
              "vkCreateDebugUtilsMessengerEXT");
    }

    uint32_t device_count = 0;
    vkEnumeratePhysicalDevices(vulkan->instance_, &device_count, nullptr);
    std::vector<VkPhysicalDevice> devices(device_count);
    vkEnumeratePhysicalDevices(vulkan->instance_, &device_count, devices.data());
    for (const VkPhysicalDevice candidate : devices) {
        uint32_t family_count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, nullptr);
        std::vector<VkQueueFamilyProperties> families(family_count);
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &family_count, families.data());
        for (uint32_t i = 0; i < family_count; ++i) {
            if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0) {
                vulkan->physical_device_ = candidate;
                vulkan->queue_family_ = i;
                break;
            }
        }
        if (vulkan->physical_device_ != VK_NULL_HANDLE) {
            break;
        }
    }
    if (vulkan->physical_device_ == VK_NULL_HANDLE) {
        reason = "no Vulkan device with a graphics queue";
        return nullptr;
    }

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{};
    queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue_info.queueFamilyIndex = vulkan->queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo device_info{};
    device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    if (const VkResult result =
            vkCreateDevice(vulkan->physical_device_, &device_info, nullptr, &vulkan->device_);
        result != VK_SUCCESS) {
        reason = "vkCreateDevice: VkResult " + std::to_string(result);
        return nullptr;
    }
    vkGetDeviceQueue(vulkan->device_, vulkan->queue_family_, 0, &vulkan->queue_);

    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pool_info.queueFamilyIndex = vulkan->queue_family_;
    check(vkCreateCommandPool(vulkan->device_, &pool_info, nullptr, &vulkan->command_pool_),
          "vkCreateCommandPool");
    return vulkan;
}

HeadlessVulkan::~HeadlessVulkan() {
    if (device_ != VK_NULL_HANDLE) {
        vkDestroyCommandPool(device_, command_pool_, nullptr);
        // The validation layer reports objects still alive here: the renderer's leaks.
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_ != VK_NULL_HANDLE) {
        const auto destroy_messenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        destroy_messenger(instance_, messenger_, nullptr);
    }
    if (instance_ != VK_NULL_HANDLE) {
        vkDestroyInstance(instance_, nullptr);
    }
}

std::string HeadlessVulkan::device_name() const {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physical_device_, &properties);
    return properties.deviceName;
}

OffscreenImage HeadlessVulkan::create_image(VkFormat format, VkExtent2D extent, uint32_t layers) {
    OffscreenImage result{.format = format, .extent = extent, .layers = layers};
    VkImageCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {extent.width, extent.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = layers;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                 VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(device_, &info, nullptr, &result.image), "vkCreateImage");
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device_, result.image, &requirements);
    result.memory =
        allocate(device_, physical_device_, requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    check(vkBindImageMemory(device_, result.image, result.memory, 0), "vkBindImageMemory");
    return result;
}

void HeadlessVulkan::destroy_image(OffscreenImage& image) {
    vkDestroyImage(device_, image.image, nullptr);
    vkFreeMemory(device_, image.memory, nullptr);
    image = {};
}

template <typename Record>
void HeadlessVulkan::run_once(Record record) {
    VkCommandBufferAllocateInfo allocate_info{};
    allocate_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    allocate_info.commandPool = command_pool_;
    allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate_info.commandBufferCount = 1;
    VkCommandBuffer commands = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(device_, &allocate_info, &commands), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
    record(commands);
    check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    check(vkQueueSubmit(queue_, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
    check(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
    vkFreeCommandBuffers(device_, command_pool_, 1, &commands);
}

void HeadlessVulkan::fill(const OffscreenImage& image, std::array<float, 4> color,
                          VkImageLayout layout) {
    run_once([&](VkCommandBuffer commands) {
        const VkImageMemoryBarrier to_transfer = layout_barrier(
            image.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kAnyWrite,
            VK_ACCESS_TRANSFER_WRITE_BIT, 0, image.layers);
        vkCmdPipelineBarrier(commands, kAnyWriteStage, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                             nullptr, 0, nullptr, 1, &to_transfer);
        VkClearColorValue clear{};
        std::copy(color.begin(), color.end(), clear.float32);
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, image.layers};
        vkCmdClearColorImage(commands, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1,
                             &range);
        const VkImageMemoryBarrier to_layout = layout_barrier(
            image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layout, VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT, 0, image.layers);
        vkCmdPipelineBarrier(
            commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
            nullptr, 0, nullptr, 1, &to_layout);
    });
}

Pixels HeadlessVulkan::read(const OffscreenImage& image, uint32_t layer, VkImageLayout layout) {
    const VkDeviceSize size = VkDeviceSize{image.extent.width} * image.extent.height * 4;
    VkBufferCreateInfo buffer_info{};
    buffer_info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    buffer_info.size = size;
    buffer_info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(device_, &buffer_info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device_, buffer, &requirements);
    VkDeviceMemory memory =
        allocate(device_, physical_device_, requirements,
                 VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    check(vkBindBufferMemory(device_, buffer, memory, 0), "vkBindBufferMemory");

    run_once([&](VkCommandBuffer commands) {
        const VkImageMemoryBarrier to_transfer =
            layout_barrier(image.image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kAnyWrite,
                           VK_ACCESS_TRANSFER_READ_BIT, layer, 1);
        vkCmdPipelineBarrier(commands, kAnyWriteStage, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                             nullptr, 0, nullptr, 1, &to_transfer);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, layer, 1};
        region.imageExtent = {image.extent.width, image.extent.height, 1};
        vkCmdCopyImageToBuffer(commands, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer,
                               1, &region);
        const VkImageMemoryBarrier back = layout_barrier(
            image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout, 0, 0, layer, 1);
        VkBufferMemoryBarrier to_host{};
        to_host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        to_host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        to_host.buffer = buffer;
        to_host.size = VK_WHOLE_SIZE;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
                             nullptr, 1, &to_host, 1, &back);
    });

    Pixels pixels{image.extent.width, image.extent.height, std::vector<uint8_t>(size)};
    void* mapped = nullptr;
    check(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    std::memcpy(pixels.bytes.data(), mapped, size);
    vkDestroyBuffer(device_, buffer, nullptr);
    vkFreeMemory(device_, memory, nullptr);
    return pixels;
}

}  // namespace physhand::overlay::testing
