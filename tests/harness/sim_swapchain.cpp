// Swapchains of Vulkan sessions: images made on the application's device, and the
// acquire, wait, release cycle with its call-order rules. Headless sessions offer no format.

#include <array>
#include <chrono>
#include <thread>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

// In order of preference: sRGB first, so the colours an application writes are those shown.
constexpr auto kFormats = std::to_array<VkFormat>({
    VK_FORMAT_R8G8B8A8_SRGB,
    VK_FORMAT_B8G8R8A8_SRGB,
    VK_FORMAT_R8G8B8A8_UNORM,
    VK_FORMAT_B8G8R8A8_UNORM,
    VK_FORMAT_D32_SFLOAT,
});

// Three, so an application may render one image while the compositor shows another.
constexpr std::uint32_t kImageCount = 3;

constexpr XrSwapchainCreateFlags kKnownCreateFlags =
    XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT | XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT;

bool is_supported_format(std::int64_t format) {
    return std::find(kFormats.begin(), kFormats.end(), format) != kFormats.end();
}

VkImageUsageFlags vulkan_usage(XrSwapchainUsageFlags usage) {
    constexpr std::array<std::pair<XrSwapchainUsageFlags, VkImageUsageFlags>, 6> kUsage{{
        {XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT},
        {XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT},
        {XR_SWAPCHAIN_USAGE_UNORDERED_ACCESS_BIT, VK_IMAGE_USAGE_STORAGE_BIT},
        {XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_USAGE_TRANSFER_SRC_BIT},
        {XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT, VK_IMAGE_USAGE_TRANSFER_DST_BIT},
        {XR_SWAPCHAIN_USAGE_SAMPLED_BIT, VK_IMAGE_USAGE_SAMPLED_BIT},
    }};
    VkImageUsageFlags flags = 0;
    for (const auto& [xr, vk] : kUsage) {
        if ((usage & xr) != 0) flags |= vk;
    }
    return flags;
}

// Images leave UNDEFINED for the layout XR_KHR_vulkan_enable promises after
// xrWaitSwapchainImage. Done at the first acquire, a call during which the runtime may use
// the application's queue.
void set_initial_layouts(VulkanSession& vulkan, const SwapchainData& swapchain) {
    std::vector<VkImageMemoryBarrier> barriers;
    for (VkImage image : swapchain.images->images()) {
        barriers.push_back(layout_barrier(
            image, {swapchain.aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS},
            VK_IMAGE_LAYOUT_UNDEFINED, swapchain.layout));
    }
    vulkan.submit([&](VkCommandBuffer commands) {
        vulkan.fn().vkCmdPipelineBarrier(
            commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0,
            nullptr, 0, nullptr, static_cast<std::uint32_t>(barriers.size()), barriers.data());
    });
}

}  // namespace

XrResult xrEnumerateSwapchainFormats(XrSession session, uint32_t formatCapacityInput,
                                     uint32_t* formatCountOutput, int64_t* formats) {
    return guarded([&](Runtime& rt) {
        const SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        auto count = static_cast<uint32_t>(data->vulkan ? kFormats.size() : 0);
        return fill_array(formatCapacityInput, formatCountOutput, formats, count,
                          [](int64_t& out, uint32_t i) {
                              out = kFormats[i];
                              return XR_SUCCESS;
                          });
    });
}

XrResult xrCreateSwapchain(XrSession session, const XrSwapchainCreateInfo* createInfo,
                           XrSwapchain* swapchain) {
    return guarded([&](Runtime& rt) {
        SessionData* data = rt.sessions.find(session);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_SWAPCHAIN_CREATE_INFO) || swapchain == nullptr ||
            (createInfo->createFlags & ~kKnownCreateFlags) != 0 || createInfo->width == 0 ||
            createInfo->height == 0 || createInfo->arraySize == 0 || createInfo->mipCount == 0 ||
            createInfo->faceCount == 0 || createInfo->sampleCount == 0) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!data->vulkan || !is_supported_format(createInfo->format)) {
            return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
        }
        // No protected memory, cube maps or multisampling (maxSwapchainSampleCount is 1).
        if ((createInfo->createFlags & XR_SWAPCHAIN_CREATE_PROTECTED_CONTENT_BIT) != 0 ||
            createInfo->faceCount != 1 || createInfo->sampleCount != 1) {
            return XR_ERROR_FEATURE_UNSUPPORTED;
        }
        auto format = static_cast<VkFormat>(createInfo->format);
        bool depth = format == VK_FORMAT_D32_SFLOAT;
        // The attachment usage of its aspect makes the promised layout valid for every image;
        // the compositor copies images out.
        auto image = vk_struct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
        if ((createInfo->usageFlags & XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT) != 0) {
            image.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
        }
        image.imageType = VK_IMAGE_TYPE_2D;
        image.format = format;
        image.extent = {createInfo->width, createInfo->height, 1};
        image.mipLevels = createInfo->mipCount;
        image.arrayLayers = createInfo->arraySize;
        image.samples = VK_SAMPLE_COUNT_1_BIT;
        image.tiling = VK_IMAGE_TILING_OPTIMAL;
        image.usage = vulkan_usage(createInfo->usageFlags) | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                      (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                             : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT);
        image.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        image.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        if (!data->vulkan->supports(image)) return XR_ERROR_FEATURE_UNSUPPORTED;
        bool is_static = (createInfo->createFlags & XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT) != 0;
        *swapchain = rt.swapchains.add({
            .session = session,
            .format = format,
            .width = createInfo->width,
            .height = createInfo->height,
            .array_size = createInfo->arraySize,
            .is_static = is_static,
            .layout = depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL
                            : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            .aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT,
            .images = std::make_unique<SwapchainImages>(*data->vulkan, image,
                                                        is_static ? 1 : kImageCount),
        });
        return XR_SUCCESS;
    });
}

XrResult xrDestroySwapchain(XrSwapchain swapchain) {
    return guarded([&](Runtime& rt) {
        if (rt.swapchains.find(swapchain) == nullptr) return XR_ERROR_HANDLE_INVALID;
        rt.swapchains.erase(swapchain);
        return XR_SUCCESS;
    });
}

XrResult xrEnumerateSwapchainImages(XrSwapchain swapchain, uint32_t imageCapacityInput,
                                    uint32_t* imageCountOutput,
                                    XrSwapchainImageBaseHeader* images) {
    return guarded([&](Runtime& rt) {
        const SwapchainData* data = rt.swapchains.find(swapchain);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        // The array is of the graphics API's struct, not of the header.
        auto* vulkan_images = reinterpret_cast<XrSwapchainImageVulkanKHR*>(images);
        const std::vector<VkImage>& created = data->images->images();
        return fill_array(imageCapacityInput, imageCountOutput, vulkan_images,
                          static_cast<uint32_t>(created.size()),
                          [&](XrSwapchainImageVulkanKHR& out, uint32_t i) {
                              if (out.type != XR_TYPE_SWAPCHAIN_IMAGE_VULKAN_KHR) {
                                  return XR_ERROR_VALIDATION_FAILURE;
                              }
                              out.image = created[i];
                              return XR_SUCCESS;
                          });
    });
}

XrResult xrAcquireSwapchainImage(XrSwapchain swapchain,
                                 const XrSwapchainImageAcquireInfo* acquireInfo, uint32_t* index) {
    return guarded([&](Runtime& rt) {
        SwapchainData* data = rt.swapchains.find(swapchain);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if ((acquireInfo != nullptr && acquireInfo->type != XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO) ||
            index == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const auto count = static_cast<std::uint32_t>(data->images->images().size());
        bool exhausted = data->is_static ? data->released || !data->acquired.empty()
                                         : data->acquired.size() == count;
        if (exhausted) return XR_ERROR_CALL_ORDER_INVALID;
        if (!data->layouts_set) {
            set_initial_layouts(*rt.sessions.find(data->session)->vulkan, *data);
            data->layouts_set = true;
        }
        *index = data->next;
        data->acquired.push_back(data->next);
        data->next = (data->next + 1) % count;
        return XR_SUCCESS;
    });
}

// Images are ready as soon as they are acquired: the application's own work on them is
// all the work there is, so the timeout never matters. PHYSHAND_SIM_SWAPCHAIN_WAIT_MS=N
// makes every wait take N ms, as a compositor still reading the image would; slept outside
// the runtime's lock, so other threads' calls go on meanwhile.
XrResult xrWaitSwapchainImage(XrSwapchain swapchain, const XrSwapchainImageWaitInfo* waitInfo) {
    const std::optional<std::int64_t> wait_ms =
        whole_number_env("PHYSHAND_SIM_SWAPCHAIN_WAIT_MS", 0);
    if (wait_ms) std::this_thread::sleep_for(std::chrono::milliseconds(*wait_ms));
    return guarded([&](Runtime& rt) {
        SwapchainData* data = rt.swapchains.find(swapchain);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(waitInfo, XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (data->acquired.empty() || data->waited) return XR_ERROR_CALL_ORDER_INVALID;
        data->waited = true;
        return XR_SUCCESS;
    });
}

XrResult xrReleaseSwapchainImage(XrSwapchain swapchain,
                                 const XrSwapchainImageReleaseInfo* releaseInfo) {
    return guarded([&](Runtime& rt) {
        SwapchainData* data = rt.swapchains.find(swapchain);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (releaseInfo != nullptr && releaseInfo->type != XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        // Only the oldest acquired image is released, and only once it has been waited for.
        if (!data->waited) return XR_ERROR_CALL_ORDER_INVALID;
        data->released = data->acquired.front();
        data->acquired.pop_front();
        data->waited = false;
        return XR_SUCCESS;
    });
}

}  // namespace physhand::sim
