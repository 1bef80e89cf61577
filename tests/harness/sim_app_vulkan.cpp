#include "sim_app_vulkan.h"

#include <stdexcept>
#include <string>

#include "sim_app.h"

namespace physhand::test {

namespace {

constexpr std::int32_t kViewSize = 256;  // pixels; the overlay draws at the app's size

template <typename T>
T vk(VkStructureType type) {
    T s{};
    s.sType = type;
    return s;
}

void check_vk(VkResult result, const char* call) {
    if (result != VK_SUCCESS) {
        throw std::runtime_error(std::string(call) + " failed with VkResult " +
                                 std::to_string(result));
    }
}

template <typename Pfn>
Pfn xr_function(XrInstance instance, const char* name) {
    PFN_xrVoidFunction function = nullptr;
    check(xrGetInstanceProcAddr(instance, name, &function), name);
    return reinterpret_cast<Pfn>(function);
}

std::uint32_t graphics_family(VkPhysicalDevice device) {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (std::uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0) return i;
    }
    throw std::runtime_error("the runtime's Vulkan device has no graphics queue");
}

}  // namespace

AppVulkan::AppVulkan(XrInstance instance, XrSystemId system) {
    auto requirements =
        xr<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
    check(xr_function<PFN_xrGetVulkanGraphicsRequirements2KHR>(
              instance, "xrGetVulkanGraphicsRequirements2KHR")(instance, system, &requirements),
          "xrGetVulkanGraphicsRequirements2KHR");

    auto app = vk<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "physhand sim app";
    app.apiVersion = VK_API_VERSION_1_1;
    auto instance_info = vk<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    instance_info.pApplicationInfo = &app;
    auto xr_instance_info =
        xr<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
    xr_instance_info.systemId = system;
    xr_instance_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr_instance_info.vulkanCreateInfo = &instance_info;
    VkResult result = VK_ERROR_UNKNOWN;
    check(xr_function<PFN_xrCreateVulkanInstanceKHR>(instance, "xrCreateVulkanInstanceKHR")(
              instance, &xr_instance_info, &instance_, &result),
          "xrCreateVulkanInstanceKHR");
    check_vk(result, "vkCreateInstance");

    auto device_get_info =
        xr<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
    device_get_info.systemId = system;
    device_get_info.vulkanInstance = instance_;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    check(xr_function<PFN_xrGetVulkanGraphicsDevice2KHR>(instance, "xrGetVulkanGraphicsDevice2KHR")(
              instance, &device_get_info, &physical_device),
          "xrGetVulkanGraphicsDevice2KHR");

    const std::uint32_t family = graphics_family(physical_device);
    const float priority = 1.0f;
    auto queue_info = vk<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    auto device_info = vk<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    auto xr_device_info = xr<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
    xr_device_info.systemId = system;
    xr_device_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr_device_info.vulkanPhysicalDevice = physical_device;
    xr_device_info.vulkanCreateInfo = &device_info;
    check(xr_function<PFN_xrCreateVulkanDeviceKHR>(instance, "xrCreateVulkanDeviceKHR")(
              instance, &xr_device_info, &device_, &result),
          "xrCreateVulkanDeviceKHR");
    check_vk(result, "vkCreateDevice");

    binding_ = xr<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
    binding_.instance = instance_;
    binding_.physicalDevice = physical_device;
    binding_.device = device_;
    binding_.queueFamilyIndex = family;
}

AppVulkan::~AppVulkan() {
    if (device_ != VK_NULL_HANDLE) vkDestroyDevice(device_, nullptr);
    if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

void AppVulkan::start(XrSession session, XrSpace space, XrTime time) {
    auto swapchain_info = xr<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
    swapchain_info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
    swapchain_info.format = VK_FORMAT_R8G8B8A8_SRGB;
    swapchain_info.width = swapchain_info.height = kViewSize;
    swapchain_info.sampleCount = swapchain_info.faceCount = swapchain_info.arraySize =
        swapchain_info.mipCount = 1;
    check(xrCreateSwapchain(session, &swapchain_info, &swapchain_), "xrCreateSwapchain");

    auto locate = xr<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
    locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    locate.displayTime = time;
    locate.space = space;
    auto view_state = xr<XrViewState>(XR_TYPE_VIEW_STATE);
    std::array<XrView, 2> views;
    views.fill(xr<XrView>(XR_TYPE_VIEW));
    std::uint32_t count = 0;
    check(xrLocateViews(session, &locate, &view_state, 2, &count, views.data()), "xrLocateViews");
    for (std::size_t i = 0; i < views_.size(); ++i) {
        views_[i] = xr<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
        views_[i].pose = views[i].pose;
        views_[i].fov = views[i].fov;
        views_[i].subImage = {swapchain_, {{0, 0}, {kViewSize, kViewSize}}, 0};
    }
    layer_ = xr<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
    layer_.space = space;
    layer_.viewCount = static_cast<std::uint32_t>(views_.size());
    layer_.views = views_.data();
}

const XrCompositionLayerProjection* AppVulkan::render() {
    if (swapchain_ == XR_NULL_HANDLE) return nullptr;
    std::uint32_t index = 0;
    check(xrAcquireSwapchainImage(swapchain_, nullptr, &index), "xrAcquireSwapchainImage");
    auto wait = xr<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
    wait.timeout = XR_INFINITE_DURATION;
    check(xrWaitSwapchainImage(swapchain_, &wait), "xrWaitSwapchainImage");
    check(xrReleaseSwapchainImage(swapchain_, nullptr), "xrReleaseSwapchainImage");
    return &layer_;
}

}  // namespace physhand::test
