#include "view_swapchains.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "xr_check.h"

namespace physhand::sample {

namespace {

// The first of the runtime's formats (its order is its preference) that the sample can use.
VkFormat choose_format(XrInstance instance, XrSession session) {
    std::uint32_t count = 0;
    xr_check(instance, xrEnumerateSwapchainFormats(session, 0, &count, nullptr),
             "xrEnumerateSwapchainFormats");
    std::vector<std::int64_t> formats(count);
    xr_check(instance, xrEnumerateSwapchainFormats(session, count, &count, formats.data()),
             "xrEnumerateSwapchainFormats");
    for (const std::int64_t format : formats) {
        if (format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_B8G8R8A8_SRGB) {
            return static_cast<VkFormat>(format);
        }
    }
    throw std::runtime_error("the runtime offers no sRGB swapchain format");
}

}  // namespace

ViewSwapchains::ViewSwapchains(XrInstance instance, XrSystemId system, XrSession session,
                               std::optional<std::uint32_t> width)
    : instance_(instance), format_(choose_format(instance, session)) {
    std::uint32_t count = 0;
    const XrViewConfigurationType type = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    xr_check(instance,
             xrEnumerateViewConfigurationViews(instance, system, type, 0, &count, nullptr),
             "xrEnumerateViewConfigurationViews");
    XrViewConfigurationView blank{};
    blank.type = XR_TYPE_VIEW_CONFIGURATION_VIEW;
    std::vector<XrViewConfigurationView> configs(count, blank);
    xr_check(
        instance,
        xrEnumerateViewConfigurationViews(instance, system, type, count, &count, configs.data()),
        "xrEnumerateViewConfigurationViews");
    for (const XrViewConfigurationView& config : configs) {
        const std::uint32_t w =
            std::min(width.value_or(config.recommendedImageRectWidth), config.maxImageRectWidth);
        const auto h = static_cast<std::uint32_t>(
            std::lround(static_cast<double>(w) * config.recommendedImageRectHeight /
                        config.recommendedImageRectWidth));
        XrSwapchainCreateInfo info{};
        info.type = XR_TYPE_SWAPCHAIN_CREATE_INFO;
        info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
        info.format = format_;
        info.sampleCount = 1;
        info.width = w;
        info.height = std::clamp<std::uint32_t>(h, 1, config.maxImageRectHeight);
        info.faceCount = info.arraySize = info.mipCount = 1;
        XrSwapchain swapchain = XR_NULL_HANDLE;
        xr_check(instance, xrCreateSwapchain(session, &info, &swapchain), "xrCreateSwapchain");
        View view{
            XrHandle<XrSwapchain>(swapchain, xrDestroySwapchain), {info.width, info.height}, {}};
        std::uint32_t images = 0;
        xr_check(instance, xrEnumerateSwapchainImages(swapchain, 0, &images, nullptr),
                 "xrEnumerateSwapchainImages");
        XrSwapchainImageVulkan2KHR image_blank{};
        image_blank.type = XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR;
        std::vector<XrSwapchainImageVulkan2KHR> listed(images, image_blank);
        xr_check(instance,
                 xrEnumerateSwapchainImages(
                     swapchain, images, &images,
                     reinterpret_cast<XrSwapchainImageBaseHeader*>(listed.data())),
                 "xrEnumerateSwapchainImages");
        for (const auto& image : listed) view.images.push_back(image.image);
        views_.push_back(std::move(view));
    }
}

VkImage ViewSwapchains::acquire(std::size_t view) {
    const XrSwapchain swapchain = views_[view].swapchain.get();
    std::uint32_t index = 0;
    xr_check(instance_, xrAcquireSwapchainImage(swapchain, nullptr, &index),
             "xrAcquireSwapchainImage");
    XrSwapchainImageWaitInfo wait{};
    wait.type = XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO;
    wait.timeout = XR_INFINITE_DURATION;
    xr_check(instance_, xrWaitSwapchainImage(swapchain, &wait), "xrWaitSwapchainImage");
    return views_[view].images.at(index);
}

void ViewSwapchains::release(std::size_t view) {
    xr_check(instance_, xrReleaseSwapchainImage(views_[view].swapchain.get(), nullptr),
             "xrReleaseSwapchainImage");
}

}  // namespace physhand::sample
