#include "scene_graphics.h"

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>

#include "xr_check.h"

namespace physhand::sample {

namespace {

constexpr float kNear = 0.02f;  // metres; hands come close to the eyes
constexpr float kFar = 50.0f;

// Scene frame to Vulkan clip space (+Y down, depth 0 at kNear to 1 at kFar) for an eye.
Eigen::Matrix4f view_projection(const XrView& view) {
    const float left = std::tan(view.fov.angleLeft), right = std::tan(view.fov.angleRight);
    const float up = std::tan(view.fov.angleUp), down = std::tan(view.fov.angleDown);
    Eigen::Matrix4f projection = Eigen::Matrix4f::Zero();
    projection(0, 0) = 2 / (right - left);
    projection(0, 2) = (right + left) / (right - left);
    projection(1, 1) = -2 / (up - down);
    projection(1, 2) = -(up + down) / (up - down);
    projection(2, 2) = -kFar / (kFar - kNear);
    projection(2, 3) = -kFar * kNear / (kFar - kNear);
    projection(3, 2) = -1;
    const XrQuaternionf& q = view.pose.orientation;
    Eigen::Matrix4f eye = Eigen::Matrix4f::Identity();
    eye.block<3, 3>(0, 0) = Eigen::Quaternionf(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
    eye.block<3, 1>(0, 3) =
        Eigen::Vector3f(view.pose.position.x, view.pose.position.y, view.pose.position.z);
    return projection * eye.inverse();
}

}  // namespace

SceneGraphics::SceneGraphics(XrInstance instance, XrSystemId system, XrSession session,
                             const VulkanDevice& device, std::optional<std::uint32_t> view_width)
    : instance_(instance),
      session_(session),
      device_(device),
      swapchains_(instance, system, session, view_width) {}

void SceneGraphics::show(const Scene& scene) {
    renderer_.reset();
    frame_ms_.clear();
    drawing_.emplace(scene);
    renderer_.emplace(device_, swapchains_.format(), drawing_->meshes());
}

const XrCompositionLayerBaseHeader* SceneGraphics::render(
    XrSpace stage, XrTime time, const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders,
    const std::array<LocatedHand, 2>& hands, const DrawSettings& drawing,
    const std::vector<float>& flashes) {
    XrViewLocateInfo locate{};
    locate.type = XR_TYPE_VIEW_LOCATE_INFO;
    locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    locate.displayTime = time;
    locate.space = stage;
    XrViewState state{};
    state.type = XR_TYPE_VIEW_STATE;
    XrView blank{};
    blank.type = XR_TYPE_VIEW;
    std::vector<XrView> views(swapchains_.count(), blank);
    std::uint32_t count = 0;
    xr_check(instance_,
             xrLocateViews(session_, &locate, &state, static_cast<std::uint32_t>(views.size()),
                           &count, views.data()),
             "xrLocateViews");
    const XrViewStateFlags valid =
        XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT;
    if ((state.viewStateFlags & valid) != valid || count != views.size()) return nullptr;

    std::vector<ViewTarget> targets;
    layer_views_.clear();
    for (std::size_t v = 0; v < views.size(); ++v) {
        const VkExtent2D extent = swapchains_.extent(v);
        const XrVector3f& p = views[v].pose.position;
        targets.push_back(
            {swapchains_.acquire(v), extent, view_projection(views[v]), {p.x, p.y, p.z}});
        XrCompositionLayerProjectionView layer_view{};
        layer_view.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW;
        layer_view.pose = views[v].pose;
        layer_view.fov = views[v].fov;
        layer_view.subImage = {
            swapchains_.swapchain(v),
            {{0, 0},
             {static_cast<std::int32_t>(extent.width), static_cast<std::int32_t>(extent.height)}},
            0};
        layer_views_.push_back(layer_view);
    }
    const auto start = std::chrono::steady_clock::now();
    renderer_->render(targets, drawing_->draws(colliders, hands, drawing, flashes));
    frame_ms_.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    for (std::size_t v = 0; v < views.size(); ++v) swapchains_.release(v);
    view0_projection_ = targets[0].view_projection;

    layer_ = {};
    layer_.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION;
    layer_.space = stage;
    layer_.viewCount = static_cast<std::uint32_t>(layer_views_.size());
    layer_.views = layer_views_.data();
    return reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer_);
}

std::optional<std::array<double, 2>> SceneGraphics::view0_position(const Vec3& point) const {
    if (!view0_projection_) return std::nullopt;
    const Eigen::Vector4f clip =
        *view0_projection_ * Eigen::Vector4f(static_cast<float>(point.x()),
                                             static_cast<float>(point.y()),
                                             static_cast<float>(point.z()), 1.0f);
    if (!(clip.w() > 0.0f)) return std::nullopt;
    return std::array<double, 2>{(clip.x() / clip.w() + 1.0) / 2, (clip.y() / clip.w() + 1.0) / 2};
}

}  // namespace physhand::sample
