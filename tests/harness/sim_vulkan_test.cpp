// Vulkan sessions on the simulated runtime, through the real loader, on whatever Vulkan
// device comes first (lavapipe: CTest sets VK_ICD_FILENAMES). Images are cleared to known
// colours and the frames the runtime composes are read back from its PNG capture.

#include <vulkan/vulkan.h>
// After vulkan.h; the build defines XR_USE_GRAPHICS_API_VULKAN.
#include <openxr/openxr_platform.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>

#include "png_file.h"
#include "sim_runtime_fixture.h"

namespace {

using namespace physhand::sim_test;
using Png = physhand::test::PngImage;
using physhand::test::read_png;
using physhand::test::Rgba;

template <typename T>
T vk(VkStructureType type) {
    T s{};
    s.sType = type;
    return s;
}

// The test's own sRGB transfer functions, to predict what the compositor writes.
double srgb_to_linear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
int linear_to_srgb8(double linear) {
    double c = linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255));
}

#define EXPECT_RGBA_NEAR(actual, expected, tolerance)  \
    do {                                               \
        const Rgba a_ = (actual), e_ = (expected);     \
        EXPECT_NEAR(a_.r, e_.r, tolerance) << "red";   \
        EXPECT_NEAR(a_.g, e_.g, tolerance) << "green"; \
        EXPECT_NEAR(a_.b, e_.b, tolerance) << "blue";  \
        EXPECT_EQ(a_.a, e_.a) << "alpha";              \
    } while (false)

class SimVulkanTest : public SimRuntimeFixture {
  protected:
    void SetUp() override {
        SimRuntimeFixture::SetUp();
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        capture_dir_ = std::filesystem::temp_directory_path() /
                       (std::string("physhand_SimVulkanTest_") + info->name());
        std::filesystem::remove_all(capture_dir_);
        unsetenv("PHYSHAND_SIM_CAPTURE");
        unsetenv("PHYSHAND_SIM_CAPTURE_EVERY");
    }

    // The runtime goes first: its swapchain images live on the device.
    void TearDown() override {
        SimRuntimeFixture::TearDown();
        if (device_ != VK_NULL_HANDLE) {
            vkDestroyCommandPool(device_, pool_, nullptr);
            vkDestroyDevice(device_, nullptr);
        }
        if (vk_instance_ != VK_NULL_HANDLE) vkDestroyInstance(vk_instance_, nullptr);
        std::filesystem::remove_all(capture_dir_);
    }

    // Capture is read when the instance is created.
    void capture(const char* every) {
        setenv("PHYSHAND_SIM_CAPTURE", capture_dir_.c_str(), 1);
        if (every != nullptr) setenv("PHYSHAND_SIM_CAPTURE_EVERY", every, 1);
    }

    XrResult graphics_requirements(XrGraphicsRequirementsVulkan2KHR* requirements) {
        *requirements =
            xr<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
        return function<PFN_xrGetVulkanGraphicsRequirements2KHR>(
            "xrGetVulkanGraphicsRequirements2KHR")(instance_, system(), requirements);
    }

    // An XR instance with XR_KHR_vulkan_enable2, and the Vulkan instance and device made
    // through it, as an application does it.
    void create_vulkan(bool query_requirements = true) {
        ASSERT_EQ(create_instance({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME}), XR_SUCCESS);
        if (query_requirements) {
            XrGraphicsRequirementsVulkan2KHR requirements;
            ASSERT_EQ(graphics_requirements(&requirements), XR_SUCCESS);
        }
        auto app = vk<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
        app.pApplicationName = "sim_vulkan_test";
        app.apiVersion = VK_API_VERSION_1_1;
        auto instance_info = vk<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
        instance_info.pApplicationInfo = &app;
        auto create_instance_info =
            xr<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
        create_instance_info.systemId = system();
        create_instance_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        create_instance_info.vulkanCreateInfo = &instance_info;
        VkResult vk_result = VK_ERROR_UNKNOWN;
        ASSERT_EQ(function<PFN_xrCreateVulkanInstanceKHR>("xrCreateVulkanInstanceKHR")(
                      instance_, &create_instance_info, &vk_instance_, &vk_result),
                  XR_SUCCESS);
        ASSERT_EQ(vk_result, VK_SUCCESS);

        auto device_get_info =
            xr<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
        device_get_info.systemId = system();
        device_get_info.vulkanInstance = vk_instance_;
        ASSERT_EQ(function<PFN_xrGetVulkanGraphicsDevice2KHR>("xrGetVulkanGraphicsDevice2KHR")(
                      instance_, &device_get_info, &physical_device_),
                  XR_SUCCESS);
        ASSERT_NE(physical_device_, VK_NULL_HANDLE);

        uint32_t count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, nullptr);
        std::vector<VkQueueFamilyProperties> families(count);
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, families.data());
        while (family_ < count && (families[family_].queueFlags & VK_QUEUE_GRAPHICS_BIT) == 0) {
            ++family_;
        }
        ASSERT_LT(family_, count);
        const float priority = 1.0f;
        auto queue_info = vk<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
        queue_info.queueFamilyIndex = family_;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        auto device_info = vk<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        auto create_device_info =
            xr<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
        create_device_info.systemId = system();
        create_device_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        create_device_info.vulkanPhysicalDevice = physical_device_;
        create_device_info.vulkanCreateInfo = &device_info;
        auto create_device = function<PFN_xrCreateVulkanDeviceKHR>("xrCreateVulkanDeviceKHR");
        create_device_info.vulkanPhysicalDevice = bogus_handle<VkPhysicalDevice>();
        EXPECT_EQ(create_device(instance_, &create_device_info, &device_, &vk_result),
                  XR_ERROR_HANDLE_INVALID);
        create_device_info.vulkanPhysicalDevice = physical_device_;
        ASSERT_EQ(create_device(instance_, &create_device_info, &device_, &vk_result), XR_SUCCESS);
        ASSERT_EQ(vk_result, VK_SUCCESS);
        vkGetDeviceQueue(device_, family_, 0, &queue_);

        auto pool_info = vk<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pool_info.queueFamilyIndex = family_;
        ASSERT_EQ(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_), VK_SUCCESS);

        binding_ = xr<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
        binding_.instance = vk_instance_;
        binding_.physicalDevice = physical_device_;
        binding_.device = device_;
        binding_.queueFamilyIndex = family_;
        binding_.queueIndex = 0;
    }

    XrSession vulkan_session() {
        XrSession created = XR_NULL_HANDLE;
        EXPECT_EQ(create_session(&created, &binding_), XR_SUCCESS);
        expect_states({XR_SESSION_STATE_IDLE, XR_SESSION_STATE_READY});
        EXPECT_EQ(begin_session(created), XR_SUCCESS);
        expect_states(
            {XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_FOCUSED});
        return created;
    }

    static XrSwapchainCreateInfo swapchain_info(VkFormat format, uint32_t size = 64) {
        auto info = xr<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
        info.usageFlags =
            XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT;
        info.format = format;
        info.width = info.height = size;
        info.sampleCount = info.faceCount = info.arraySize = info.mipCount = 1;
        return info;
    }

    static XrSwapchain swapchain(XrSession session, VkFormat format, uint32_t size = 64) {
        XrSwapchainCreateInfo info = swapchain_info(format, size);
        XrSwapchain created = XR_NULL_HANDLE;
        EXPECT_EQ(xrCreateSwapchain(session, &info, &created), XR_SUCCESS);
        return created;
    }

    static std::vector<VkImage> images(XrSwapchain swapchain) {
        uint32_t count = 0;
        EXPECT_EQ(xrEnumerateSwapchainImages(swapchain, 0, &count, nullptr), XR_SUCCESS);
        std::vector<XrSwapchainImageVulkan2KHR> images(
            count, xr<XrSwapchainImageVulkan2KHR>(XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR));
        EXPECT_EQ(xrEnumerateSwapchainImages(
                      swapchain, count, &count,
                      reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())),
                  XR_SUCCESS);
        std::vector<VkImage> handles;
        for (const auto& image : images) handles.push_back(image.image);
        return handles;
    }

    // Renders the next image of the swapchain as an application does: acquire, wait, clear
    // (leaving it in the layout it was handed over in), release.
    void clear(XrSwapchain swapchain, VkClearColorValue colour) {
        uint32_t index = 0;
        ASSERT_EQ(xrAcquireSwapchainImage(swapchain, nullptr, &index), XR_SUCCESS);
        auto wait = xr<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
        wait.timeout = XR_INFINITE_DURATION;
        ASSERT_EQ(xrWaitSwapchainImage(swapchain, &wait), XR_SUCCESS);
        VkImage image = images(swapchain)[index];

        auto allocate =
            vk<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        allocate.commandPool = pool_;
        allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate.commandBufferCount = 1;
        VkCommandBuffer commands = VK_NULL_HANDLE;
        ASSERT_EQ(vkAllocateCommandBuffers(device_, &allocate, &commands), VK_SUCCESS);
        auto begin = vk<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        vkBeginCommandBuffer(commands, &begin);
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        auto barrier = vk<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        barrier.srcAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.image = image;
        barrier.subresourceRange = range;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &barrier);
        vkCmdClearColorImage(commands, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &colour, 1,
                             &range);
        std::swap(barrier.oldLayout, barrier.newLayout);
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &barrier);
        vkEndCommandBuffer(commands);
        auto submit = vk<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &commands;
        ASSERT_EQ(vkQueueSubmit(queue_, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);
        ASSERT_EQ(vkQueueWaitIdle(queue_), VK_SUCCESS);
        vkFreeCommandBuffers(device_, pool_, 1, &commands);
        ASSERT_EQ(xrReleaseSwapchainImage(swapchain, nullptr), XR_SUCCESS);
    }

    // A layer showing the whole of the swapchain's latest image to both eyes.
    struct Projection {
        std::array<XrCompositionLayerProjectionView, 2> views;
        XrCompositionLayerProjection layer;
        Projection(XrSpace space, XrSwapchain swapchain, XrCompositionLayerFlags flags,
                   int32_t size = 64) {
            for (auto& view : views) {
                view =
                    xr<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
                view.pose = identity_pose();
                view.subImage = {swapchain, {{0, 0}, {size, size}}, 0};
            }
            layer = xr<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
            layer.layerFlags = flags;
            layer.space = space;
            layer.viewCount = 2;
            layer.views = views.data();
        }
        Projection(const Projection&) = delete;  // points into itself
        Projection& operator=(const Projection&) = delete;
    };

    // One frame showing the layers; returns xrEndFrame's result and the frame's display time.
    static XrResult show(XrSession session, std::vector<const XrCompositionLayerBaseHeader*> layers,
                         XrTime* time = nullptr) {
        XrFrameState state;
        EXPECT_EQ(wait_frame(session, &state), XR_SUCCESS);
        EXPECT_EQ(xrBeginFrame(session, nullptr), XR_SUCCESS);
        auto info = xr<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
        info.displayTime = state.predictedDisplayTime;
        info.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
        info.layerCount = static_cast<uint32_t>(layers.size());
        info.layers = layers.data();
        if (time != nullptr) *time = state.predictedDisplayTime;
        return xrEndFrame(session, &info);
    }

    template <typename Layer>
    static const XrCompositionLayerBaseHeader* base(const Layer& layer) {
        return reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer);
    }

    // The captured views of the first frame (scene frame 1).
    std::array<Png, 2> first_frame() const {
        return {read_png(capture_dir_ / "frame_00001_view0.png"),
                read_png(capture_dir_ / "frame_00001_view1.png")};
    }

    std::filesystem::path capture_dir_;
    VkInstance vk_instance_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    XrGraphicsBindingVulkan2KHR binding_{};
};

TEST_F(SimVulkanTest, AdvertisesVulkanExtensions) {
    uint32_t count = 0;
    ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr), XR_SUCCESS);
    std::vector<XrExtensionProperties> extensions(
        count, xr<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
    ASSERT_EQ(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, extensions.data()),
              XR_SUCCESS);
    std::set<std::string> names;
    for (const auto& extension : extensions) names.insert(extension.extensionName);
    EXPECT_TRUE(names.contains(XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME));
    EXPECT_TRUE(names.contains(XR_KHR_VULKAN_ENABLE_EXTENSION_NAME));

    // Each extension's functions come with it only.
    ASSERT_EQ(create_instance({XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME}), XR_SUCCESS);
    PFN_xrVoidFunction fn = nullptr;
    EXPECT_EQ(xrGetInstanceProcAddr(instance_, "xrGetVulkanGraphicsDeviceKHR", &fn),
              XR_ERROR_FUNCTION_UNSUPPORTED);
    EXPECT_EQ(xrGetInstanceProcAddr(instance_, "xrCreateVulkanDeviceKHR", &fn), XR_SUCCESS);
}

TEST_F(SimVulkanTest, SessionNeedsTheRequirementsAndTheDeviceItWasGiven) {
    ASSERT_NO_FATAL_FAILURE(create_vulkan(false));
    XrSession created = XR_NULL_HANDLE;
    EXPECT_EQ(create_session(&created, &binding_), XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING);

    XrGraphicsRequirementsVulkan2KHR requirements;
    ASSERT_EQ(graphics_requirements(&requirements), XR_SUCCESS);
    EXPECT_LE(requirements.minApiVersionSupported, XR_MAKE_VERSION(1, 0, 0));
    EXPECT_GE(requirements.maxApiVersionSupported, XR_MAKE_VERSION(1, 1, 0));

    auto bad = binding_;
    bad.physicalDevice = bogus_handle<VkPhysicalDevice>();
    EXPECT_EQ(create_session(&created, &bad), XR_ERROR_GRAPHICS_DEVICE_INVALID);
    bad = binding_;
    bad.device = VK_NULL_HANDLE;
    EXPECT_EQ(create_session(&created, &bad), XR_ERROR_GRAPHICS_DEVICE_INVALID);
    bad = binding_;
    bad.queueIndex = 1000;
    EXPECT_EQ(create_session(&created, &bad), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(create_session(&created, &binding_), XR_SUCCESS);
}

// XR_KHR_vulkan_enable: the application makes its instance and device itself.
TEST_F(SimVulkanTest, VulkanEnableOneWorksToo) {
    ASSERT_EQ(create_instance({XR_KHR_VULKAN_ENABLE_EXTENSION_NAME}), XR_SUCCESS);
    for (const char* name :
         {"xrGetVulkanInstanceExtensionsKHR", "xrGetVulkanDeviceExtensionsKHR"}) {
        auto get = function<PFN_xrGetVulkanInstanceExtensionsKHR>(name);
        uint32_t count = 0;
        ASSERT_EQ(get(instance_, system(), 0, &count, nullptr), XR_SUCCESS);
        std::string list(count, 'x');
        ASSERT_EQ(get(instance_, system(), count, &count, list.data()), XR_SUCCESS);
        EXPECT_STREQ(list.c_str(), "") << name;  // the runtime needs no Vulkan extension
    }
    auto requirements =
        xr<XrGraphicsRequirementsVulkanKHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN_KHR);
    ASSERT_EQ(function<PFN_xrGetVulkanGraphicsRequirementsKHR>(
                  "xrGetVulkanGraphicsRequirementsKHR")(instance_, system(), &requirements),
              XR_SUCCESS);

    auto instance_info = vk<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    ASSERT_EQ(vkCreateInstance(&instance_info, nullptr, &vk_instance_), VK_SUCCESS);
    ASSERT_EQ(function<PFN_xrGetVulkanGraphicsDeviceKHR>("xrGetVulkanGraphicsDeviceKHR")(
                  instance_, system(), vk_instance_, &physical_device_),
              XR_SUCCESS);
    const float priority = 1.0f;
    auto queue_info = vk<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    auto device_info = vk<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    ASSERT_EQ(vkCreateDevice(physical_device_, &device_info, nullptr, &device_), VK_SUCCESS);
    auto pool_info = vk<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    ASSERT_EQ(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_), VK_SUCCESS);

    auto binding = xr<XrGraphicsBindingVulkanKHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN_KHR);
    binding.instance = vk_instance_;
    binding.physicalDevice = physical_device_;
    binding.device = device_;
    XrSession created = XR_NULL_HANDLE;
    ASSERT_EQ(create_session(&created, &binding), XR_SUCCESS);
    uint32_t count = 0;
    EXPECT_EQ(xrEnumerateSwapchainFormats(created, 0, &count, nullptr), XR_SUCCESS);
    EXPECT_EQ(count, 5u);
}

TEST_F(SimVulkanTest, SwapchainsFollowTheCallOrder) {
    ASSERT_NO_FATAL_FAILURE(create_vulkan());
    XrSession running = vulkan_session();

    uint32_t count = 0;
    ASSERT_EQ(xrEnumerateSwapchainFormats(running, 0, &count, nullptr), XR_SUCCESS);
    std::vector<int64_t> formats(count);
    ASSERT_EQ(xrEnumerateSwapchainFormats(running, count, &count, formats.data()), XR_SUCCESS);
    EXPECT_EQ(formats, (std::vector<int64_t>{VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB,
                                             VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM,
                                             VK_FORMAT_D32_SFLOAT}));

    XrSwapchain colour = swapchain(running, VK_FORMAT_R8G8B8A8_SRGB);
    std::vector<VkImage> colour_images = images(colour);
    EXPECT_EQ(colour_images.size(), 3u);
    EXPECT_EQ(std::set<VkImage>(colour_images.begin(), colour_images.end()).size(), 3u);

    auto wait = xr<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
    wait.timeout = XR_INFINITE_DURATION;
    EXPECT_EQ(xrReleaseSwapchainImage(colour, nullptr), XR_ERROR_CALL_ORDER_INVALID);
    EXPECT_EQ(xrWaitSwapchainImage(colour, &wait), XR_ERROR_CALL_ORDER_INVALID);
    uint32_t index = 99;
    for (uint32_t expected : {0u, 1u, 2u}) {
        ASSERT_EQ(xrAcquireSwapchainImage(colour, nullptr, &index), XR_SUCCESS);
        EXPECT_EQ(index, expected);
    }
    EXPECT_EQ(xrAcquireSwapchainImage(colour, nullptr, &index), XR_ERROR_CALL_ORDER_INVALID);
    EXPECT_EQ(xrReleaseSwapchainImage(colour, nullptr), XR_ERROR_CALL_ORDER_INVALID);  // unwaited
    ASSERT_EQ(xrWaitSwapchainImage(colour, &wait), XR_SUCCESS);
    EXPECT_EQ(xrWaitSwapchainImage(colour, &wait), XR_ERROR_CALL_ORDER_INVALID);  // not released
    ASSERT_EQ(xrReleaseSwapchainImage(colour, nullptr), XR_SUCCESS);
    ASSERT_EQ(xrAcquireSwapchainImage(colour, nullptr, &index), XR_SUCCESS);
    EXPECT_EQ(index, 0u);

    // A static image is acquired once.
    XrSwapchainCreateInfo info = swapchain_info(VK_FORMAT_B8G8R8A8_UNORM);
    info.createFlags = XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT;
    XrSwapchain still = XR_NULL_HANDLE;
    ASSERT_EQ(xrCreateSwapchain(running, &info, &still), XR_SUCCESS);
    EXPECT_EQ(images(still).size(), 1u);
    ASSERT_EQ(xrAcquireSwapchainImage(still, nullptr, &index), XR_SUCCESS);
    ASSERT_EQ(xrWaitSwapchainImage(still, &wait), XR_SUCCESS);
    ASSERT_EQ(xrReleaseSwapchainImage(still, nullptr), XR_SUCCESS);
    EXPECT_EQ(xrAcquireSwapchainImage(still, nullptr, &index), XR_ERROR_CALL_ORDER_INVALID);

    // Depth swapchains exist, for the application's own use.
    XrSwapchainCreateInfo depth_info = swapchain_info(VK_FORMAT_D32_SFLOAT);
    depth_info.usageFlags = XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    XrSwapchain depth = XR_NULL_HANDLE;
    ASSERT_EQ(xrCreateSwapchain(running, &depth_info, &depth), XR_SUCCESS);
    ASSERT_EQ(xrAcquireSwapchainImage(depth, nullptr, &index), XR_SUCCESS);
    ASSERT_EQ(xrWaitSwapchainImage(depth, &wait), XR_SUCCESS);
    ASSERT_EQ(xrReleaseSwapchainImage(depth, nullptr), XR_SUCCESS);

    info = swapchain_info(VK_FORMAT_R16G16B16A16_SFLOAT);
    XrSwapchain rejected = XR_NULL_HANDLE;
    EXPECT_EQ(xrCreateSwapchain(running, &info, &rejected), XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);
    info = swapchain_info(VK_FORMAT_R8G8B8A8_SRGB);
    info.sampleCount = 4;
    EXPECT_EQ(xrCreateSwapchain(running, &info, &rejected), XR_ERROR_FEATURE_UNSUPPORTED);
    info.sampleCount = 1;
    info.width = 0;
    EXPECT_EQ(xrCreateSwapchain(running, &info, &rejected), XR_ERROR_VALIDATION_FAILURE);

    // Layers show released colour images only, within their bounds.
    XrSpace local = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL);
    XrSwapchain unreleased = swapchain(running, VK_FORMAT_R8G8B8A8_SRGB);
    Projection never_released(local, unreleased, 0);
    XrTime time = 0;
    EXPECT_EQ(show(running, {base(never_released.layer)}, &time), XR_ERROR_LAYER_INVALID);
    ASSERT_EQ(end_frame(running, time), XR_SUCCESS);  // the failed call left the frame open
    Projection too_big(local, colour, 0, 65);
    EXPECT_EQ(show(running, {base(too_big.layer)}, &time), XR_ERROR_SWAPCHAIN_RECT_INVALID);
    ASSERT_EQ(end_frame(running, time), XR_SUCCESS);
    Projection depth_shown(local, depth, 0);
    EXPECT_EQ(show(running, {base(depth_shown.layer)}, &time), XR_ERROR_LAYER_INVALID);
    ASSERT_EQ(end_frame(running, time), XR_SUCCESS);

    ASSERT_EQ(xrDestroySwapchain(colour), XR_SUCCESS);
    EXPECT_EQ(xrDestroySwapchain(colour), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(xrAcquireSwapchainImage(colour, nullptr, &index), XR_ERROR_HANDLE_INVALID);
    // The others go with their session.
    ASSERT_EQ(xrDestroySession(running), XR_SUCCESS);
    EXPECT_EQ(xrDestroySwapchain(still), XR_ERROR_HANDLE_INVALID);
}

// Every colour format shows what was written to it; sRGB images exactly.
TEST_F(SimVulkanTest, ClearedImageIsCaptured) {
    capture("1");
    ASSERT_NO_FATAL_FAILURE(create_vulkan());
    XrSession running = vulkan_session();
    XrSpace local = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL);
    const double code_188 = srgb_to_linear(188 / 255.0);
    const VkClearColorValue colour{{1.0f, 0.0f, static_cast<float>(code_188), 1.0f}};

    XrSwapchain srgb = swapchain(running, VK_FORMAT_R8G8B8A8_SRGB);
    clear(srgb, colour);
    Projection layer(local, srgb, 0);
    ASSERT_EQ(show(running, {base(layer.layer)}), XR_SUCCESS);
    for (const Png& view : first_frame()) {
        ASSERT_EQ(view.width, 1024u);
        ASSERT_EQ(view.height, 1024u);
        for (auto [x, y] : {std::pair{0u, 0u}, {512u, 512u}, {1023u, 1023u}}) {
            EXPECT_RGBA_NEAR(view.rgba(x, y), (Rgba{255, 0, 188, 255}), 0);
        }
    }

    // Frames are numbered by the scene frame they are displayed at: 2, 3, 4 here.
    int frame = 1;
    for (VkFormat format :
         {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM}) {
        SCOPED_TRACE(format);
        const VkClearColorValue linear{{0.8f, 0.2f, 0.05f, 1.0f}};
        XrSwapchain image = swapchain(running, format);
        clear(image, linear);
        Projection shown(local, image, 0);
        ASSERT_EQ(show(running, {base(shown.layer)}), XR_SUCCESS);
        char name[64];
        std::snprintf(name, sizeof(name), "frame_%05d_view1.png", ++frame);
        Png view = read_png(capture_dir_ / name);
        ASSERT_EQ(view.width, 1024u);
        // UNORM holds linear values, quantised on write.
        bool unorm = format != VK_FORMAT_B8G8R8A8_SRGB;
        auto expected = [&](float c) {
            return linear_to_srgb8(unorm ? std::lround(c * 255) / 255.0 : c);
        };
        EXPECT_RGBA_NEAR(view.rgba(700, 300),
                         (Rgba{expected(0.8f), expected(0.2f), expected(0.05f), 255}), 1);
    }
}

// Layers compose in order: source alpha blends, premultiplied or not; without the flag a
// layer replaces what is below whatever its alpha.
TEST_F(SimVulkanTest, LayersBlendInOrder) {
    capture("1");
    ASSERT_NO_FATAL_FAILURE(create_vulkan());
    XrSession running = vulkan_session();
    XrSpace local = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL);
    XrSwapchain blue = swapchain(running, VK_FORMAT_R8G8B8A8_SRGB);
    clear(blue, {{0.0f, 0.0f, 1.0f, 1.0f}});
    // UNORM: the values are the linear ones the compositor blends, up to quantisation.
    const float half = 128 / 255.0f;
    XrSwapchain premultiplied_red = swapchain(running, VK_FORMAT_R8G8B8A8_UNORM);
    clear(premultiplied_red, {{half, 0.0f, 0.0f, half}});
    XrSwapchain straight_red = swapchain(running, VK_FORMAT_R8G8B8A8_UNORM);
    clear(straight_red, {{1.0f, 0.0f, 0.0f, half}});

    Projection below(local, blue, 0);
    Projection premultiplied(local, premultiplied_red,
                             XR_COMPOSITION_LAYER_BLEND_TEXTURE_SOURCE_ALPHA_BIT);
    Projection straight(local, straight_red,
                        XR_COMPOSITION_LAYER_BLEND_TEXTURE_SOURCE_ALPHA_BIT |
                            XR_COMPOSITION_LAYER_UNPREMULTIPLIED_ALPHA_BIT);
    Projection opaque(local, premultiplied_red, 0);
    const Rgba blended{linear_to_srgb8(half), 0, linear_to_srgb8(1 - half), 255};

    ASSERT_EQ(show(running, {base(below.layer), base(premultiplied.layer)}), XR_SUCCESS);
    EXPECT_RGBA_NEAR(first_frame()[0].rgba(100, 900), blended, 1);
    ASSERT_EQ(show(running, {base(below.layer), base(straight.layer)}), XR_SUCCESS);
    EXPECT_RGBA_NEAR(read_png(capture_dir_ / "frame_00002_view0.png").rgba(100, 900), blended, 1);
    ASSERT_EQ(show(running, {base(below.layer), base(opaque.layer)}), XR_SUCCESS);
    EXPECT_RGBA_NEAR(read_png(capture_dir_ / "frame_00003_view1.png").rgba(100, 900),
                     (Rgba{linear_to_srgb8(half), 0, 0, 255}), 1);
}

// A quad 1 m ahead of the head, 0.5 m wide, seen by each eye from its own position.
TEST_F(SimVulkanTest, QuadIsSeenFromEachEye) {
    capture("1");
    ASSERT_NO_FATAL_FAILURE(create_vulkan());
    XrSession running = vulkan_session();
    XrSpace view_space = reference_space(running, XR_REFERENCE_SPACE_TYPE_VIEW);
    XrSwapchain green = swapchain(running, VK_FORMAT_R8G8B8A8_SRGB, 16);
    clear(green, {{0.0f, 1.0f, 0.0f, 1.0f}});
    auto quad = xr<XrCompositionLayerQuad>(XR_TYPE_COMPOSITION_LAYER_QUAD);
    quad.space = view_space;
    quad.eyeVisibility = XR_EYE_VISIBILITY_BOTH;
    quad.subImage = {green, {{0, 0}, {16, 16}}, 0};
    quad.pose = {{0, 0, 0, 1}, {0, 0, -1}};
    quad.size = {0.5f, 0.5f};
    ASSERT_EQ(show(running, {base(quad)}), XR_SUCCESS);

    // 90 degree fields, eyes 64 mm apart: the left eye sees the quad over tangents
    // -0.218..0.282, pixels 400..656; the right one over -0.282..0.218, pixels 367..623.
    const Rgba black{0, 0, 0, 255}, shown{0, 255, 0, 255};
    std::array<Png, 2> views = first_frame();
    EXPECT_RGBA_NEAR(views[0].rgba(512, 512), shown, 0);
    EXPECT_RGBA_NEAR(views[1].rgba(512, 512), shown, 0);
    EXPECT_RGBA_NEAR(views[0].rgba(640, 512), shown, 0);
    EXPECT_RGBA_NEAR(views[1].rgba(640, 512), black, 0);
    EXPECT_RGBA_NEAR(views[0].rgba(380, 512), black, 0);
    EXPECT_RGBA_NEAR(views[1].rgba(380, 512), shown, 0);
    EXPECT_RGBA_NEAR(views[0].rgba(512, 300), black, 0);  // above: tangent 0.41

    quad.eyeVisibility = XR_EYE_VISIBILITY_LEFT;
    ASSERT_EQ(show(running, {base(quad)}), XR_SUCCESS);
    EXPECT_RGBA_NEAR(read_png(capture_dir_ / "frame_00002_view0.png").rgba(512, 512), shown, 0);
    EXPECT_RGBA_NEAR(read_png(capture_dir_ / "frame_00002_view1.png").rgba(512, 512), black, 0);
}

// By default every 30th frame is written, and the last one before the session stops.
TEST_F(SimVulkanTest, CapturesEveryThirtiethAndTheLastFrame) {
    capture(nullptr);
    ASSERT_NO_FATAL_FAILURE(create_vulkan());
    XrSession running = vulkan_session();
    XrSpace local = reference_space(running, XR_REFERENCE_SPACE_TYPE_LOCAL);
    XrSwapchain image = swapchain(running, VK_FORMAT_R8G8B8A8_SRGB);
    clear(image, {{1.0f, 1.0f, 1.0f, 1.0f}});
    Projection layer(local, image, 0);
    bool stopping = false;
    for (int n = 0; n < 100 && !stopping; ++n) {
        ASSERT_EQ(show(running, {base(layer.layer)}), XR_SUCCESS);
        while (auto state = poll_state()) stopping |= *state == XR_SESSION_STATE_STOPPING;
    }
    ASSERT_TRUE(stopping);
    // The scene lasts 0.5 s: frame 46 (0.511 s) is the first past its end.
    std::set<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(capture_dir_)) {
        files.insert(entry.path().filename());
    }
    EXPECT_EQ(files, (std::set<std::string>{"frame_00030_view0.png", "frame_00030_view1.png",
                                            "frame_00046_view0.png", "frame_00046_view1.png"}));
    EXPECT_RGBA_NEAR(read_png(capture_dir_ / "frame_00046_view0.png").rgba(0, 0),
                     (Rgba{255, 255, 255, 255}), 0);
}

}  // namespace
