// The overlay end to end: a minimal Vulkan OpenXR app (XR_KHR_vulkan_enable2) clears its
// swapchain to one opaque colour each frame and shows it as a projection layer; the layer
// draws the simulated hands over it; the runtime's PNG capture shows the result.

#include <vulkan/vulkan.h>
// After vulkan.h; the build defines XR_USE_GRAPHICS_API_VULKAN.
#include <gtest/gtest.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "png_file.h"

namespace {

namespace fs = std::filesystem;
using physhand::test::PngImage;

template <typename T, typename Type>
T zeroed(Type type) {
    T s{};
    if constexpr (requires { s.sType; }) {
        s.sType = type;
    } else {
        s.type = type;
    }
    return s;
}

#define XR_OK(call) ASSERT_EQ((call), XR_SUCCESS) << #call
#define VK_OK(call) ASSERT_EQ((call), VK_SUCCESS) << #call

// The app's colour, linear; sRGB-encoded 8-bit it is kClearSrgb.
constexpr VkClearColorValue kClear{{0.2f, 0.2f, 0.2f, 1.0f}};
constexpr int kClearSrgb = 124;  // 1.055 * 0.2^(1/2.4) - 0.055 = 0.4845
constexpr int32_t kSize = 256;   // the app's views, pixels

// The app's colour, where nothing is drawn over it.
bool is_clear(const PngImage& png, std::uint32_t x, std::uint32_t y) {
    const std::uint8_t* p = png.at(x, y);
    return std::abs(p[0] - kClearSrgb) <= 1 && std::abs(p[1] - kClearSrgb) <= 1 &&
           std::abs(p[2] - kClearSrgb) <= 1 && p[3] == 255;
}

// Where a point of the app's space lands in a view's image, in [0, 1] from the top left.
std::array<double, 2> project(const XrView& view, const XrVector3f& point) {
    const XrQuaternionf& q = view.pose.orientation;
    // The point in view coordinates: the inverse rotation of (point - eye).
    const double v[3] = {point.x - view.pose.position.x, point.y - view.pose.position.y,
                         point.z - view.pose.position.z};
    const double qx = -q.x, qy = -q.y, qz = -q.z, qw = q.w;
    const double tx = 2 * (qy * v[2] - qz * v[1]), ty = 2 * (qz * v[0] - qx * v[2]),
                 tz = 2 * (qx * v[1] - qy * v[0]);
    const double x = v[0] + qw * tx + (qy * tz - qz * ty);
    const double y = v[1] + qw * ty + (qz * tx - qx * tz);
    const double z = v[2] + qw * tz + (qx * ty - qy * tx);
    const double l = std::tan(view.fov.angleLeft), r = std::tan(view.fov.angleRight);
    const double u = std::tan(view.fov.angleUp), d = std::tan(view.fov.angleDown);
    return {(x / -z - l) / (r - l), (u - y / -z) / (u - d)};
}

class OverlayLayerTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        // One directory, also for a parameterised test's "Name/Param", so TearDown removes it.
        std::replace(name.begin(), name.end(), '/', '_');
        dir_ = fs::temp_directory_path() / ("physhand_OverlayLayerTest_" + name);
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "capture");
        setenv("PHYSHAND_SIM_CAPTURE", (dir_ / "capture").c_str(), 1);
        setenv("PHYSHAND_SIM_CAPTURE_EVERY", "1", 1);
    }

    void TearDown() override {
        for (const char* name : {"PHYSHAND_SIM_REJECT_LAYERS_OVER", "PHYSHAND_SIM_HEAD_POSITION",
                                 "PHYSHAND_SIM_HEAD_PITCH_DEG"}) {
            unsetenv(name);
        }
        unsetenv("PHYSHAND_SIM_SWAPCHAIN_WAIT_MS");
        if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
        if (device_ != VK_NULL_HANDLE) {
            vkDestroyCommandPool(device_, pool_, nullptr);
            vkDestroyDevice(device_, nullptr);
        }
        if (vk_instance_ != VK_NULL_HANDLE) vkDestroyInstance(vk_instance_, nullptr);
        if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
        fs::remove_all(dir_);
    }

    void write_config(const std::string& json) {
        const fs::path path = dir_ / "config.json";
        std::ofstream(path) << json;
        setenv("PHYSHAND_CONFIG", path.c_str(), 1);
    }

    template <typename PFN>
    PFN function(const char* name) {
        PFN_xrVoidFunction f = nullptr;
        EXPECT_EQ(xrGetInstanceProcAddr(instance_, name, &f), XR_SUCCESS) << name;
        return reinterpret_cast<PFN>(f);
    }

    // Instance, Vulkan through XR_KHR_vulkan_enable2, running session, spaces, hand
    // trackers and the app's swapchain, as an application sets them up.
    void start() {
        const char* extensions[] = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME,
                                    XR_EXT_HAND_TRACKING_EXTENSION_NAME};
        auto create = zeroed<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
        std::snprintf(create.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE,
                      "overlay_layer_test");
        create.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
        create.enabledExtensionCount = 2;
        create.enabledExtensionNames = extensions;
        XR_OK(xrCreateInstance(&create, &instance_));
        auto system_info = zeroed<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
        system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
        XR_OK(xrGetSystem(instance_, &system_info, &system_));
        auto requirements =
            zeroed<XrGraphicsRequirementsVulkan2KHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR);
        XR_OK(function<PFN_xrGetVulkanGraphicsRequirements2KHR>(
            "xrGetVulkanGraphicsRequirements2KHR")(instance_, system_, &requirements));
        ASSERT_NO_FATAL_FAILURE(create_vulkan());

        auto binding = zeroed<XrGraphicsBindingVulkan2KHR>(XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR);
        binding.instance = vk_instance_;
        binding.physicalDevice = physical_device_;
        binding.device = device_;
        binding.queueFamilyIndex = family_;
        auto session_info = zeroed<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
        session_info.next = &binding;
        session_info.systemId = system_;
        XR_OK(xrCreateSession(instance_, &session_info, &session_));
        ASSERT_NO_FATAL_FAILURE(wait_for_state(XR_SESSION_STATE_READY));
        auto begin = zeroed<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
        begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
        XR_OK(xrBeginSession(session_, &begin));

        auto space_info = zeroed<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
        space_info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
        space_info.poseInReferenceSpace.orientation.w = 1.0f;
        XR_OK(xrCreateReferenceSpace(session_, &space_info, &space_));
        for (XrHandEXT hand : {XR_HAND_LEFT_EXT, XR_HAND_RIGHT_EXT}) {
            auto tracker_info =
                zeroed<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
            tracker_info.hand = hand;
            tracker_info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
            XR_OK(function<PFN_xrCreateHandTrackerEXT>("xrCreateHandTrackerEXT")(
                session_, &tracker_info, &trackers_[hand == XR_HAND_RIGHT_EXT]));
        }

        auto swapchain_info = zeroed<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
        swapchain_info.usageFlags =
            XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT;
        swapchain_info.format = VK_FORMAT_R8G8B8A8_SRGB;
        swapchain_info.width = swapchain_info.height = kSize;
        swapchain_info.sampleCount = swapchain_info.faceCount = swapchain_info.arraySize =
            swapchain_info.mipCount = 1;
        XR_OK(xrCreateSwapchain(session_, &swapchain_info, &swapchain_));
        uint32_t count = 0;
        XR_OK(xrEnumerateSwapchainImages(swapchain_, 0, &count, nullptr));
        std::vector<XrSwapchainImageVulkan2KHR> images(
            count, zeroed<XrSwapchainImageVulkan2KHR>(XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR));
        XR_OK(xrEnumerateSwapchainImages(
            swapchain_, count, &count,
            reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())));
        for (const auto& image : images) images_.push_back(image.image);
    }

    void create_vulkan() {
        auto app = zeroed<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
        app.pApplicationName = "overlay_layer_test";
        app.apiVersion = VK_API_VERSION_1_1;
        auto instance_info = zeroed<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
        instance_info.pApplicationInfo = &app;
        auto xr_instance_info =
            zeroed<XrVulkanInstanceCreateInfoKHR>(XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR);
        xr_instance_info.systemId = system_;
        xr_instance_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        xr_instance_info.vulkanCreateInfo = &instance_info;
        VkResult vk_result = VK_ERROR_UNKNOWN;
        XR_OK(function<PFN_xrCreateVulkanInstanceKHR>("xrCreateVulkanInstanceKHR")(
            instance_, &xr_instance_info, &vk_instance_, &vk_result));
        VK_OK(vk_result);
        auto device_get_info =
            zeroed<XrVulkanGraphicsDeviceGetInfoKHR>(XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR);
        device_get_info.systemId = system_;
        device_get_info.vulkanInstance = vk_instance_;
        XR_OK(function<PFN_xrGetVulkanGraphicsDevice2KHR>("xrGetVulkanGraphicsDevice2KHR")(
            instance_, &device_get_info, &physical_device_));

        uint32_t count = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, nullptr);
        std::vector<VkQueueFamilyProperties> families(count);
        vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &count, families.data());
        while (family_ < count && (families[family_].queueFlags & VK_QUEUE_GRAPHICS_BIT) == 0) {
            ++family_;
        }
        ASSERT_LT(family_, count);
        const float priority = 1.0f;
        auto queue_info =
            zeroed<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
        queue_info.queueFamilyIndex = family_;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        auto device_info = zeroed<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        auto xr_device_info =
            zeroed<XrVulkanDeviceCreateInfoKHR>(XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR);
        xr_device_info.systemId = system_;
        xr_device_info.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
        xr_device_info.vulkanPhysicalDevice = physical_device_;
        xr_device_info.vulkanCreateInfo = &device_info;
        XR_OK(function<PFN_xrCreateVulkanDeviceKHR>("xrCreateVulkanDeviceKHR")(
            instance_, &xr_device_info, &device_, &vk_result));
        VK_OK(vk_result);
        vkGetDeviceQueue(device_, family_, 0, &queue_);
        auto pool_info =
            zeroed<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool_info.queueFamilyIndex = family_;
        VK_OK(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_));
    }

    void wait_for_state(XrSessionState wanted) {
        for (int polls = 0; polls < 100; ++polls) {
            auto event = zeroed<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
            const XrResult result = xrPollEvent(instance_, &event);
            ASSERT_TRUE(XR_SUCCEEDED(result));
            if (result == XR_EVENT_UNAVAILABLE) continue;
            if (event.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) continue;
            if (reinterpret_cast<const XrEventDataSessionStateChanged&>(event).state == wanted) {
                return;
            }
        }
        FAIL() << "session state " << wanted << " never came";
    }

    // Clears the next swapchain image to kClear, leaving it in the layout it came in.
    void clear_image() {
        uint32_t index = 0;
        XR_OK(xrAcquireSwapchainImage(swapchain_, nullptr, &index));
        auto wait = zeroed<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
        wait.timeout = XR_INFINITE_DURATION;
        XR_OK(xrWaitSwapchainImage(swapchain_, &wait));
        auto allocate =
            zeroed<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        allocate.commandPool = pool_;
        allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        allocate.commandBufferCount = 1;
        VkCommandBuffer commands = VK_NULL_HANDLE;
        VK_OK(vkAllocateCommandBuffers(device_, &allocate, &commands));
        auto begin = zeroed<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        VK_OK(vkBeginCommandBuffer(commands, &begin));
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        auto barrier = zeroed<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        barrier.srcAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        barrier.image = images_.at(index);
        barrier.subresourceRange = range;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &barrier);
        vkCmdClearColorImage(commands, barrier.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &kClear,
                             1, &range);
        std::swap(barrier.oldLayout, barrier.newLayout);
        barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr, 1,
                             &barrier);
        VK_OK(vkEndCommandBuffer(commands));
        auto submit = zeroed<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &commands;
        VK_OK(vkQueueSubmit(queue_, 1, &submit, VK_NULL_HANDLE));
        VK_OK(vkQueueWaitIdle(queue_));
        vkFreeCommandBuffers(device_, pool_, 1, &commands);
        XR_OK(xrReleaseSwapchainImage(swapchain_, nullptr));
    }

    // One frame as an application renders it; remembers the views and the right wrist.
    // `spoil`, when given, changes view 1 before xrEndFrame, which must answer `expected`;
    // a frame the runtime refused is ended again unspoilt, as by an app that fixes it.
    void frame(const std::function<void(XrCompositionLayerProjectionView&)>& spoil = {},
               XrResult expected = XR_SUCCESS) {
        auto state = zeroed<XrFrameState>(XR_TYPE_FRAME_STATE);
        XR_OK(xrWaitFrame(session_, nullptr, &state));
        display_time_ = state.predictedDisplayTime;
        XR_OK(xrBeginFrame(session_, nullptr));
        auto locate = zeroed<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
        locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
        locate.displayTime = state.predictedDisplayTime;
        locate.space = space_;
        auto view_state = zeroed<XrViewState>(XR_TYPE_VIEW_STATE);
        views_.fill(zeroed<XrView>(XR_TYPE_VIEW));
        uint32_t count = 0;
        XR_OK(xrLocateViews(session_, &locate, &view_state, 2, &count, views_.data()));
        ASSERT_EQ(count, 2u);

        auto joints_info = zeroed<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
        joints_info.baseSpace = space_;
        joints_info.time = state.predictedDisplayTime;
        auto locations = zeroed<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
        std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT> joints{};
        locations.jointCount = XR_HAND_JOINT_COUNT_EXT;
        locations.jointLocations = joints.data();
        XR_OK(function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")(
            trackers_[1], &joints_info, &locations));
        ASSERT_TRUE(locations.isActive);
        wrist_ = joints[XR_HAND_JOINT_WRIST_EXT].pose.position;
        right_joints_ = joints;

        ASSERT_NO_FATAL_FAILURE(clear_image());
        std::array<XrCompositionLayerProjectionView, 2> projection_views{};
        for (std::size_t i = 0; i < 2; ++i) {
            projection_views[i] =
                zeroed<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
            projection_views[i].pose = views_[i].pose;
            projection_views[i].fov = views_[i].fov;
            projection_views[i].subImage = {swapchain_, {{0, 0}, {view_size_, view_size_}}, 0};
        }
        auto layer = zeroed<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
        layer.space = space_;
        layer.viewCount = 2;
        layer.views = projection_views.data();
        const auto* layers = reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer);
        auto end = zeroed<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
        end.displayTime = state.predictedDisplayTime;
        end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
        end.layerCount = 1;
        end.layers = &layers;
        if (spoil) {
            const XrCompositionLayerProjectionView unspoilt = projection_views[1];
            spoil(projection_views[1]);
            ASSERT_EQ(xrEndFrame(session_, &end), expected);
            if (XR_SUCCEEDED(expected)) return;
            projection_views[1] = unspoilt;
        }
        const auto start = std::chrono::steady_clock::now();
        XR_OK(xrEndFrame(session_, &end));
        end_frame_took_ = std::chrono::steady_clock::now() - start;
    }

    // The newest captured image of view 0.
    PngImage press_table_seen_from(const char* head, const char* pitch_deg);

    PngImage last_capture() const {
        fs::path newest;
        for (const auto& entry : fs::directory_iterator(dir_ / "capture")) {
            const fs::path& path = entry.path();
            if (path.filename().string().ends_with("_view0.png") && path > newest) newest = path;
        }
        EXPECT_FALSE(newest.empty()) << "nothing captured";
        if (newest.empty()) return {};
        try {
            return physhand::test::read_png(newest);
        } catch (const std::runtime_error& e) {
            ADD_FAILURE() << e.what();
            return {};
        }
    }

    fs::path dir_;
    XrInstance instance_ = XR_NULL_HANDLE;
    XrSystemId system_ = XR_NULL_SYSTEM_ID;
    XrSession session_ = XR_NULL_HANDLE;
    XrSpace space_ = XR_NULL_HANDLE;
    std::array<XrHandTrackerEXT, 2> trackers_{};
    XrSwapchain swapchain_ = XR_NULL_HANDLE;
    std::vector<VkImage> images_;
    std::array<XrView, 2> views_{};
    XrVector3f wrist_{};
    std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT> right_joints_{};  // physical
    std::int32_t view_size_ = kSize;        // of the app's views, at the swapchain's top left
    std::atomic<XrTime> display_time_ = 0;  // of the latest frame
    std::chrono::steady_clock::duration end_frame_took_{};  // its xrEndFrame
    VkInstance vk_instance_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    uint32_t family_ = 0;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool pool_ = VK_NULL_HANDLE;
};

constexpr int kFrames = 20;

// The scene's box (touch_scene.json) as a collider of the layer's simulation: the physical
// hand comes to rest on it, the joints touching it tinted, the ghost sinking in below.
std::string box_config(const char* extra = "") {
    return std::string(R"({"colliders": [{"id": "box", "shape": "box",
        "half_extents": [0.1, 0.03, 0.1], "motion": "static",
        "pose": {"position": [0.05, 1.40, -0.5]}}])") +
           extra + "}";
}

// The contact tint (light blue) over the app's grey; the hands are red and green.
bool is_tint(const std::uint8_t* p) {
    return p[2] > 200 && p[2] > p[0] + 60;
}

// Pixels around where the wrist projects in view 0 that satisfy `test`.
template <typename Test>
int count_near_wrist(const PngImage& png, const XrView& view, const XrVector3f& wrist, Test test) {
    const auto [u, v] = project(view, wrist);
    EXPECT_TRUE(u > 0.0 && u < 1.0 && v > 0.0 && v < 1.0) << u << ", " << v;
    const auto cx = static_cast<int>(u * png.width), cy = static_cast<int>(v * png.height);
    const int reach = static_cast<int>(png.width / 16);
    int count = 0;
    for (int y = std::max(0, cy - reach); y < std::min<int>(png.height, cy + reach); ++y) {
        for (int x = std::max(0, cx - reach); x < std::min<int>(png.width, cx + reach); ++x) {
            if (test(x, y)) ++count;
        }
    }
    return count;
}

TEST_F(OverlayLayerTest, HandsAreDrawnOverTheAppsLayer) {
    write_config(box_config());
    ASSERT_NO_FATAL_FAILURE(start());
    for (int i = 0; i < kFrames; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    const PngImage png = last_capture();
    ASSERT_GT(png.width, 0u);
    // Away from the hand (the top corners: the hand is below the eyes): the app's colour.
    EXPECT_TRUE(is_clear(png, 2, 2));
    EXPECT_TRUE(is_clear(png, png.width - 3, 2));
    // Around the wrist: the overlay's colours blended over the app's, the tint among them.
    const int reach = static_cast<int>(png.width / 16);
    EXPECT_GT(count_near_wrist(png, views_[0], wrist_,
                               [&](int x, int y) { return !is_clear(png, x, y); }),
              reach * reach / 4);
    EXPECT_GT(count_near_wrist(png, views_[0], wrist_,
                               [&](int x, int y) { return is_tint(png.at(x, y)); }),
              0);
}

TEST_F(OverlayLayerTest, TintOffInTheConfigDrawsTheHandsUntinted) {
    write_config(box_config(R"(, "tint": false)"));
    ASSERT_NO_FATAL_FAILURE(start());
    for (int i = 0; i < kFrames; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    const PngImage png = last_capture();
    ASSERT_GT(png.width, 0u);
    EXPECT_GT(count_near_wrist(png, views_[0], wrist_,
                               [&](int x, int y) { return !is_clear(png, x, y); }),
              0);
    EXPECT_EQ(count_near_wrist(png, views_[0], wrist_,
                               [&](int x, int y) { return is_tint(png.at(x, y)); }),
              0);
}

// Drawing the overlay waits for swapchain images (here made slow, as a busy compositor
// makes them) and for the GPU, but not under the lock that locating hands takes: another
// thread's locates go on while xrEndFrame draws.
TEST_F(OverlayLayerTest, LocatesFromAnotherThreadDoNotWaitForTheOverlaysDrawing) {
    constexpr auto kWait = std::chrono::milliseconds(40);
    write_config(box_config());
    // The simulated runtime composes and writes captures under its own lock, which its
    // locates take too: no capture here.
    unsetenv("PHYSHAND_SIM_CAPTURE");
    ASSERT_NO_FATAL_FAILURE(start());
    ASSERT_NO_FATAL_FAILURE(frame());
    setenv("PHYSHAND_SIM_SWAPCHAIN_WAIT_MS", std::to_string(kWait.count()).c_str(), 1);
    const auto locate_joints = function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT");
    std::atomic<bool> done = false;
    std::atomic<int> failures = 0;
    std::chrono::steady_clock::duration longest{};
    int locates = 0;
    std::thread locator([&] {
        while (!done) {
            auto info = zeroed<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
            info.baseSpace = space_;
            info.time = display_time_;
            auto locations = zeroed<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
            std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT> joints{};
            locations.jointCount = XR_HAND_JOINT_COUNT_EXT;
            locations.jointLocations = joints.data();
            const auto start = std::chrono::steady_clock::now();
            if (XR_FAILED(locate_joints(trackers_[0], &info, &locations))) ++failures;
            longest = std::max(longest, std::chrono::steady_clock::now() - start);
            ++locates;
        }
    });
    for (int i = 0; i < 5; ++i) {
        ASSERT_NO_FATAL_FAILURE(frame());
        // The overlay was drawn, waiting for its swapchain image within xrEndFrame.
        EXPECT_GE(end_frame_took_, kWait);
    }
    done = true;
    locator.join();
    EXPECT_EQ(failures, 0);
    EXPECT_GT(locates, 0);
    // Far less than a swapchain wait: a locate held up by the drawing would wait it out.
    EXPECT_LT(longest, kWait / 2);
    RecordProperty(
        "longest_locate_us",
        std::to_string(std::chrono::duration_cast<std::chrono::microseconds>(longest).count()));
}

// An app whose views change size every few frames (dynamic resolution) gets the hands drawn
// at every size, from the one swapchain the overlay made for the runtime's recommended size.
TEST_F(OverlayLayerTest, ViewsThatChangeSizeReuseTheOverlaysSwapchain) {
    write_config(box_config());
    setenv("PHYSHAND_OVERLAY_STATS", "1", 1);
    ASSERT_NO_FATAL_FAILURE(start());
    testing::internal::CaptureStderr();
    // The hand comes to rest on the box, tinted where it touches.
    for (int i = 0; i < kFrames; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    for (const std::int32_t size : {kSize / 2, kSize * 3 / 4, kSize / 4, kSize}) {
        view_size_ = size;
        for (int i = 0; i < 3; ++i) ASSERT_NO_FATAL_FAILURE(frame());
        const PngImage png = last_capture();
        ASSERT_GT(png.width, 0u);
        EXPECT_GT(count_near_wrist(png, views_[0], wrist_,
                                   [&](int x, int y) { return is_tint(png.at(x, y)); }),
                  0)
            << "views of " << size << " pixels";
    }
    // The overlay's figures, said when the session ends.
    xrDestroySession(session_);
    session_ = XR_NULL_HANDLE;
    const std::string log = testing::internal::GetCapturedStderr();
    unsetenv("PHYSHAND_OVERLAY_STATS");
    EXPECT_NE(log.find("swapchains made 1\n"), std::string::npos) << log;
}

// Pixels that are not the app's colour.
int count_not_clear(const PngImage& png) {
    int count = 0;
    for (std::uint32_t y = 0; y < png.height; ++y) {
        for (std::uint32_t x = 0; x < png.width; ++x) {
            const std::uint8_t* p = png.at(x, y);
            if (p[0] != kClearSrgb || p[1] != kClearSrgb || p[2] != kClearSrgb || p[3] != 255) {
                ++count;
            }
        }
    }
    return count;
}

TEST_F(OverlayLayerTest, OverlayOffInTheConfigLeavesTheAppsFrameAlone) {
    write_config(R"({"overlay": false})");
    ASSERT_NO_FATAL_FAILURE(start());
    for (int i = 0; i < kFrames; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    const PngImage png = last_capture();
    ASSERT_GT(png.width, 0u);
    EXPECT_EQ(count_not_clear(png), 0);
}

// The configured drawing (no colour of it one of the defaults' red, green or light blue)
// reaches the renderer: the right hand's physical joints, all on the box, in the contact
// colour, yellow; its ghost below them in the hand's colour, magenta, at its most opaque as
// configured (at the default opacity it would be blended into the app's grey).
TEST_F(OverlayLayerTest, ConfiguredColorsAndGhostOpacityAreDrawn) {
    write_config(box_config(
        R"(, "colors": {"right": [1, 0, 1], "contact": [1, 1, 0]}, "ghost_opacity": 1)"));
    ASSERT_NO_FATAL_FAILURE(start());
    for (int i = 0; i < kFrames; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    const PngImage png = last_capture();
    ASSERT_GT(png.width, 0u);
    const auto magenta = [&](int x, int y) {
        const std::uint8_t* p = png.at(x, y);
        // The ghost is see-through where it faces the eye, so the app's grey shows in it.
        return p[0] > 150 && p[2] > 150 && p[1] + 50 < p[0];
    };
    const auto yellow = [&](int x, int y) {
        const std::uint8_t* p = png.at(x, y);
        return p[0] > 150 && p[1] > 150 && p[2] < 60;
    };
    EXPECT_GT(count_near_wrist(png, views_[0], wrist_, magenta), 0);
    EXPECT_GT(count_near_wrist(png, views_[0], wrist_, yellow), 0);
    EXPECT_EQ(count_near_wrist(png, views_[0], wrist_,
                               [&](int x, int y) { return is_tint(png.at(x, y)); }),
              0);
}

// A runtime that refuses the frame with the overlay's layer gets the app's own frame
// instead: the app sees XR_SUCCESS and its frames composited, and the overlay stays off for
// the session even once the runtime would take its layer again.
TEST_F(OverlayLayerTest, RefusedOverlayLayerLeavesTheAppsFramesAndTurnsTheOverlayOff) {
    write_config(box_config());
    setenv("PHYSHAND_SIM_REJECT_LAYERS_OVER", "1", 1);
    ASSERT_NO_FATAL_FAILURE(start());
    for (int i = 0; i < kFrames / 2; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    PngImage png = last_capture();
    ASSERT_GT(png.width, 0u);
    EXPECT_EQ(count_not_clear(png), 0);
    unsetenv("PHYSHAND_SIM_REJECT_LAYERS_OVER");
    for (int i = 0; i < kFrames / 2; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    png = last_capture();
    ASSERT_GT(png.width, 0u);
    EXPECT_EQ(count_not_clear(png), 0);
}

struct BadView {
    const char* name;
    std::function<void(XrCompositionLayerProjectionView&)> spoil;
    XrResult result;  // the runtime's answer to the app's frame
};

// Test names and failures show the case's name, not its bytes.
void PrintTo(const BadView& bad, std::ostream* out) {
    *out << bad.name;
}

class OverlayBadViewTest : public OverlayLayerTest,
                           public ::testing::WithParamInterface<BadView> {};

// A view the overlay cannot draw for skips the overlay for that frame only: the app's
// frame goes through as it is (the runtime judges it), and the next frames have the hands.
TEST_P(OverlayBadViewTest, SkipsTheOverlayForThatFrameOnly) {
    write_config(box_config());
    ASSERT_NO_FATAL_FAILURE(start());
    for (int i = 0; i < kFrames / 2; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    ASSERT_NO_FATAL_FAILURE(frame(GetParam().spoil, GetParam().result));
    if (XR_SUCCEEDED(GetParam().result)) {
        // Only view 1 is bad, yet view 0 has no overlay either.
        const PngImage png = last_capture();
        ASSERT_GT(png.width, 0u);
        EXPECT_EQ(count_not_clear(png), 0);
    }
    for (int i = 0; i < 2; ++i) ASSERT_NO_FATAL_FAILURE(frame());
    const PngImage png = last_capture();
    ASSERT_GT(png.width, 0u);
    EXPECT_GT(count_near_wrist(png, views_[0], wrist_,
                               [&](int x, int y) { return !is_clear(png, x, y); }),
              0);
}

using View = XrCompositionLayerProjectionView;
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

const BadView kBadViews[] = {
    {"NegativeWidth", [](View& v) { v.subImage.imageRect.extent.width = -kSize; },
     XR_ERROR_SWAPCHAIN_RECT_INVALID},
    {"ZeroHeight", [](View& v) { v.subImage.imageRect.extent.height = 0; },
     XR_ERROR_SWAPCHAIN_RECT_INVALID},
    {"NanFov", [](View& v) { v.fov.angleLeft = kNan; }, XR_SUCCESS},
    {"InfiniteFov", [](View& v) { v.fov.angleDown = -kInf; }, XR_SUCCESS},
    {"InfinitePosition", [](View& v) { v.pose.position.x = kInf; }, XR_ERROR_POSE_INVALID},
};

INSTANTIATE_TEST_SUITE_P(OverlayLayerTest, OverlayBadViewTest, ::testing::ValuesIn(kBadViews),
                         [](const ::testing::TestParamInfo<BadView>& info) {
                             return std::string(info.param.name);
                         });

}  // namespace

namespace physhand_press_table {

// The right hand green and its contact tint blue, both opaque; its ghost green too, at its
// most opaque, which leaves it see-through where it faces the eye.
constexpr const char* kConfig = R"({"colliders": [{"id": "table", "shape": "box",
    "half_extents": [0.4, 0.025, 0.3], "motion": "static",
    "pose": {"position": [0, 0.725, -0.4]}}],
    "colors": {"right": [0, 1, 0], "contact": [0, 0, 1]}, "ghost_opacity": 1})";
constexpr int kPressedFrame = 270;  // 3 s in: the ghost has been 5 cm deep for a second

bool physical(const std::uint8_t* p) {
    return p[0] < 40 && (p[1] > 80 || p[2] > 80);
}
bool ghost(const std::uint8_t* p) {
    return p[0] > 60 && p[1] > p[0] + 25;
}
// A physical pixel within `reach` of (x, y): the hand's own green edges, blended with the grey
// background, are as pale as the ghost.
bool near_physical(const PngImage& png, int x, int y, int reach) {
    for (int j = std::max(0, y - reach); j <= std::min<int>(png.height - 1, y + reach); ++j) {
        for (int i = std::max(0, x - reach); i <= std::min<int>(png.width - 1, x + reach); ++i) {
            if (physical(png.at(i, j))) return true;
        }
    }
    return false;
}

}  // namespace physhand_press_table

// press_table played to kPressedFrame with the head at `head` (X,Y,Z) pitched `pitch_deg`:
// view 0 of that frame.
PngImage OverlayLayerTest::press_table_seen_from(const char* head, const char* pitch_deg) {
    using namespace physhand_press_table;
    setenv("PHYSHAND_SIM_SCENE", PHYSHAND_SCENES_DIR "/press_table.json", 1);
    setenv("PHYSHAND_SIM_HEAD_POSITION", head, 1);
    setenv("PHYSHAND_SIM_HEAD_PITCH_DEG", pitch_deg, 1);
    setenv("PHYSHAND_SIM_CAPTURE_EVERY", std::to_string(kPressedFrame).c_str(), 1);
    write_config(kConfig);
    start();
    for (int i = 0; i < kPressedFrame && !HasFatalFailure(); ++i) frame();
    return HasFatalFailure() ? PngImage{} : last_capture();
}

// press_table seen from the side with the eyes at the height of the table's top, which is
// then a line across the image: the physical hand rests on the table, so it is drawn above
// that line, and its ghost, pressed 5 cm into the table, below it. The palm box, held 3 mm up
// by the ball of the thumb and touching nothing, is drawn in the hand's own green: its edges
// are not counted as ghost.
TEST_F(OverlayLayerTest, PressedIntoATableTheGhostIsDrawnBelowTheTopAndThePhysicalHandAbove) {
    using namespace physhand_press_table;
    const PngImage png = press_table_seen_from("0.1,0.75,0.1", "0");
    ASSERT_GT(png.width, 0u);
    // LOCAL starts at the head: the table's top is at its height.
    const auto [u, v] = project(views_[0], {0.0f, 0.0f, -0.4f});
    const int line = static_cast<int>(v * png.height);
    const int band = static_cast<int>(png.height / 100) + 1;  // a depth of 2-3 mm
    int physical_above = 0, physical_below = 0, ghost_above = 0, ghost_below = 0;
    for (int y = 0; y < static_cast<int>(png.height); ++y) {
        for (int x = 0; x < static_cast<int>(png.width); ++x) {
            const std::uint8_t* p = png.at(x, y);
            if (y < line - band) {
                physical_above += physical(p);
                ghost_above += ghost(p) && !near_physical(png, x, y, 4);
            } else if (y > line + band) {
                physical_below += physical(p);
                ghost_below += ghost(p);
            }
        }
    }
    EXPECT_GT(physical_above, 200);
    EXPECT_GT(ghost_below, 200);
    EXPECT_LT(physical_below, physical_above / 50)
        << physical_below << " physical pixels below the table's top";
    EXPECT_LT(ghost_above, ghost_below / 10)
        << ghost_above << " ghost pixels above the table's top";
}

// The default drive's palm is a box: seen from above, the hand resting on the table covers
// the whole of its palm between the wrist and the knuckles, where joint spheres and bones
// leave gaps between the metacarpals.
TEST_F(OverlayLayerTest, ThePalmIsDrawnAsTheBoxItCollidesAs) {
    using namespace physhand_press_table;
    const PngImage png = press_table_seen_from("0.1,1.1,-0.35", "-90");
    ASSERT_GT(png.width, 0u);
    const auto at = [&](XrHandJointEXT joint) { return right_joints_[joint].pose.position; };
    const XrVector3f wrist = at(XR_HAND_JOINT_WRIST_EXT);
    const XrVector3f index = at(XR_HAND_JOINT_INDEX_PROXIMAL_EXT);
    const XrVector3f little = at(XR_HAND_JOINT_LITTLE_PROXIMAL_EXT);
    int points = 0, covered = 0;
    std::string uncovered;
    for (int i = 2; i <= 8; ++i) {
        for (int j = 1; j <= 9; ++j) {
            const float s = 0.1f * i, t = 0.1f * j;
            const auto lerp = [&](float a, float b, float c) {
                return a + s * ((1 - t) * b + t * c - a);
            };
            const XrVector3f point{lerp(wrist.x, index.x, little.x),
                                   lerp(wrist.y, index.y, little.y),
                                   lerp(wrist.z, index.z, little.z)};
            const auto [u, v] = project(views_[0], point);
            const int x = static_cast<int>(u * png.width), y = static_cast<int>(v * png.height);
            ASSERT_TRUE(x >= 0 && y >= 0 && x < static_cast<int>(png.width) &&
                        y < static_cast<int>(png.height));
            ++points;
            if (physical(png.at(x, y))) {
                ++covered;
            } else {
                uncovered += " (" + std::to_string(i) + ", " + std::to_string(j) + ")";
            }
        }
    }
    EXPECT_EQ(covered, points) << "uncovered:" << uncovered;
}
