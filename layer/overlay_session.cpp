#include "overlay_session.h"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "hand_skeleton.h"
#include "layer_log.h"
#include "overlay_views.h"
#include "quantile.h"

namespace physhand::layer {

namespace {

using Clock = std::chrono::steady_clock;

void check(XrResult result, const char* call) {
    if (XR_FAILED(result)) {
        throw std::runtime_error(std::string(call) + " failed with XrResult " +
                                 std::to_string(result));
    }
}

// 8-bit sRGB formats are the ones every runtime offers; alpha is needed for blending.
VkFormat pick_format(const NextDispatch& next, XrSession session) {
    uint32_t count = 0;
    check(next.EnumerateSwapchainFormats(session, 0, &count, nullptr),
          "xrEnumerateSwapchainFormats");
    std::vector<int64_t> formats(count);
    check(next.EnumerateSwapchainFormats(session, count, &count, formats.data()),
          "xrEnumerateSwapchainFormats");
    for (const VkFormat preferred : {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB}) {
        if (std::find(formats.begin(), formats.end(), preferred) != formats.end()) return preferred;
    }
    throw std::runtime_error("the runtime offers no 8-bit sRGB swapchain format");
}

overlay::Eye to_eye(const XrPosef& pose, const XrFovf& fov) {
    return {{pose.position.x, pose.position.y, pose.position.z},
            {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w},
            fov.angleLeft,
            fov.angleRight,
            fov.angleUp,
            fov.angleDown};
}

std::array<int, overlay::kJointCount> joint_parents() {
    static_assert(overlay::kJointCount == kJointCount);
    std::array<int, overlay::kJointCount> parents{};
    for (int j = 0; j < overlay::kJointCount; ++j) {
        const std::optional<Joint> parent = joint_parent(static_cast<Joint>(j));
        parents[j] = parent ? static_cast<int>(*parent) : -1;
    }
    return parents;
}

}  // namespace

OverlaySession::OverlaySession(const NextDispatch& next, XrSession session,
                               const VulkanBinding& binding,
                               const XrSystemGraphicsProperties& limits,
                               std::vector<VkExtent2D> recommended,
                               const overlay::Settings& drawing)
    : next_(next),
      session_(session),
      limits_(limits),
      recommended_(std::move(recommended)),
      format_(pick_format(next, session)),
      settings_(drawing) {
    const char* stats = std::getenv("PHYSHAND_OVERLAY_STATS");
    collect_stats_ = stats != nullptr && std::string(stats) == "1";
    overlay::CreateInfo info;
    info.instance = binding.instance;
    info.get_instance_proc_addr = binding.get_instance_proc_addr;
    info.physical_device = binding.physical_device;
    info.device = binding.device;
    info.queue_family_index = binding.queue_family_index;
    info.queue = binding.queue;
    info.color_format = format_;
    info.gpu_timestamps = collect_stats_;
    renderer_ = std::make_unique<overlay::Renderer>(info);
}

OverlaySession::~OverlaySession() {
    destroy_swapchain();
    if (!collect_stats_ || cpu_us_.empty()) return;
    const std::string gpu = gpu_us_.empty()
                                ? "not measured (the queue has no timestamps)"
                                : "median " + std::to_string(quantile(gpu_us_, 0.5)) + " us over " +
                                      std::to_string(gpu_us_.size()) + " frames";
    log_once("overlay per drawn frame: CPU time in xrEndFrame median " +
             std::to_string(quantile(cpu_us_, 0.5)) + " us over " + std::to_string(cpu_us_.size()) +
             " frames; GPU time " + gpu + "; GPU memory " +
             std::to_string(renderer_->memory_bytes() / (1024 * 1024)) + " MB; swapchains made " +
             std::to_string(swapchains_made_));
}

void OverlaySession::record_drawn_frame(Clock::duration elapsed) {
    if (!collect_stats_) return;
    cpu_us_.push_back(std::chrono::duration<double, std::micro>(elapsed - runtime_time_).count());
    // The renderer times a frame once its slot comes round again, so each drawn frame brings
    // an earlier frame's GPU time.
    const overlay::Timings timings = renderer_->timings();
    if (timings.gpu_frames != gpu_frames_seen_) {
        gpu_frames_seen_ = timings.gpu_frames;
        gpu_us_.push_back(timings.gpu_ms * 1000.0);
    }
}

void OverlaySession::destroy_swapchain() noexcept {
    if (swapchain_ == XR_NULL_HANDLE) return;
    try {
        // The first call waits for every frame in flight; the others find none.
        for (const VkImage image : images_) renderer_->forget_image(image);
    } catch (const std::exception& e) {
        log_failure("destroying the overlay swapchain", e.what());
    }
    next_.DestroySwapchain(swapchain_);
    swapchain_ = XR_NULL_HANDLE;
    images_.clear();
    extents_.clear();
    swapchain_size_ = {};
}

// One array swapchain with a layer per view, made once for the largest of the app's views
// and the runtime's recommended sizes, and again only for views that outgrow it: views
// that change size (dynamic resolution) are drawn into its top left.
void OverlaySession::ensure_swapchain(std::vector<VkExtent2D> extents) {
    const auto fits = [&](const VkExtent2D& e) {
        return e.width <= swapchain_size_.width && e.height <= swapchain_size_.height;
    };
    if (swapchain_ != XR_NULL_HANDLE && extents.size() == extents_.size() &&
        std::all_of(extents.begin(), extents.end(), fits)) {
        extents_ = std::move(extents);
        return;
    }
    VkExtent2D size = swapchain_ != XR_NULL_HANDLE ? swapchain_size_ : VkExtent2D{};
    for (const VkExtent2D& e : extents) {
        size.width = std::max(size.width, e.width);
        size.height = std::max(size.height, e.height);
    }
    for (const VkExtent2D& recommended : recommended_) {
        const VkExtent2D e = overlay::drawn_extent(recommended);
        size.width = std::min(std::max(size.width, e.width), limits_.maxSwapchainImageWidth);
        size.height = std::min(std::max(size.height, e.height), limits_.maxSwapchainImageHeight);
    }
    destroy_swapchain();
    XrSwapchainCreateInfo info{};
    info.type = XR_TYPE_SWAPCHAIN_CREATE_INFO;
    info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
    info.format = format_;
    info.sampleCount = 1;
    info.width = size.width;
    info.height = size.height;
    info.faceCount = 1;
    info.arraySize = static_cast<uint32_t>(extents.size());
    info.mipCount = 1;
    check(next_.CreateSwapchain(session_, &info, &swapchain_), "xrCreateSwapchain");
    uint32_t count = 0;
    check(next_.EnumerateSwapchainImages(swapchain_, 0, &count, nullptr),
          "xrEnumerateSwapchainImages");
    XrSwapchainImageVulkanKHR blank{};
    blank.type = XR_TYPE_SWAPCHAIN_IMAGE_VULKAN_KHR;
    std::vector<XrSwapchainImageVulkanKHR> images(count, blank);
    check(next_.EnumerateSwapchainImages(
              swapchain_, count, &count,
              reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())),
          "xrEnumerateSwapchainImages");
    for (const XrSwapchainImageVulkanKHR& image : images) images_.push_back(image.image);
    swapchain_size_ = size;
    ++swapchains_made_;
    extents_ = std::move(extents);
}

const XrCompositionLayerProjection* OverlaySession::draw(
    const XrCompositionLayerProjection& app_layer, const std::array<overlay::Hand, 2>& hands) {
    std::optional<std::vector<VkExtent2D>> extents = overlay_extents(app_layer, limits_);
    if (!extents) return nullptr;
    runtime_time_ = {};
    // Times a call of the runtime's, which is not the overlay's own work.
    const auto in_runtime = [&](auto&& call) {
        const Clock::time_point start = Clock::now();
        const XrResult result = call();
        runtime_time_ += Clock::now() - start;
        return result;
    };
    ensure_swapchain(std::move(*extents));
    uint32_t index = 0;
    check(in_runtime([&] { return next_.AcquireSwapchainImage(swapchain_, nullptr, &index); }),
          "xrAcquireSwapchainImage");
    XrSwapchainImageWaitInfo wait{};
    wait.type = XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO;
    wait.timeout = XR_INFINITE_DURATION;
    check(in_runtime([&] { return next_.WaitSwapchainImage(swapchain_, &wait); }),
          "xrWaitSwapchainImage");

    views_.clear();
    layer_views_.clear();
    for (uint32_t i = 0; i < app_layer.viewCount; ++i) {
        const XrCompositionLayerProjectionView& app_view = app_layer.views[i];
        views_.push_back({to_eye(app_view.pose, app_view.fov), images_.at(index), i, extents_[i]});
        XrCompositionLayerProjectionView view{};
        view.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW;
        view.pose = app_view.pose;
        view.fov = app_view.fov;
        view.subImage.swapchain = swapchain_;
        view.subImage.imageRect.extent = {static_cast<int32_t>(extents_[i].width),
                                          static_cast<int32_t>(extents_[i].height)};
        view.subImage.imageArrayIndex = i;
        layer_views_.push_back(view);
    }
    overlay::Frame frame;
    frame.views = views_;
    frame.hands = hands;
    static const std::array<int, overlay::kJointCount> parents = joint_parents();
    frame.parents = parents;
    frame.settings = settings_;
    bool drawn = false;
    try {
        drawn = renderer_->render(frame);
    } catch (...) {
        // The image goes back to the runtime whatever happened to the drawing.
        next_.ReleaseSwapchainImage(swapchain_, nullptr);
        throw;
    }
    check(in_runtime([&] { return next_.ReleaseSwapchainImage(swapchain_, nullptr); }),
          "xrReleaseSwapchainImage");
    if (!drawn) return nullptr;

    layer_.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION;
    layer_.layerFlags = XR_COMPOSITION_LAYER_BLEND_TEXTURE_SOURCE_ALPHA_BIT;
    layer_.space = app_layer.space;
    layer_.viewCount = static_cast<uint32_t>(layer_views_.size());
    layer_.views = layer_views_.data();
    return &layer_;
}

}  // namespace physhand::layer
