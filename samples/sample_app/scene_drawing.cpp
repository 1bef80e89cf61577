#include "scene_drawing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hand_skeleton.h"
#include "scene_colliders.h"
#include "touch_feedback.h"
#include "xr_convert.h"

namespace physhand::sample {

namespace {

using Rgb = std::array<float, 3>;

// sRGB-encoded picks, decoded for the linear shader.
constexpr Rgb kFloor = {0.62f, 0.62f, 0.6f};
constexpr Rgb kStatic = {0.6f, 0.46f, 0.33f};  // wood: tables, walls, baskets
constexpr Rgb kKinematic = {0.45f, 0.5f, 0.6f};
constexpr Rgb kSkin = {0.88f, 0.7f, 0.58f};
constexpr std::array<Rgb, 6> kDynamic = {{{0.9f, 0.3f, 0.25f},
                                          {0.25f, 0.55f, 0.95f},
                                          {0.95f, 0.75f, 0.2f},
                                          {0.35f, 0.75f, 0.35f},
                                          {0.7f, 0.4f, 0.85f},
                                          {0.2f, 0.8f, 0.8f}}};
constexpr float kFlashWhite = 0.8f;       // how far toward white a touched object flashes
constexpr float kBoneRadiusScale = 0.6f;  // of the smaller joint radius at its ends

Rgb linear(const Rgb& srgb) {
    Rgb out{};
    for (std::size_t i = 0; i < 3; ++i) {
        const float c = srgb[i];
        out[i] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    return out;
}

Eigen::Matrix4f pose_matrix(const XrPosef& pose) {
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    const XrQuaternionf& q = pose.orientation;
    m.block<3, 3>(0, 0) = Eigen::Quaternionf(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
    m.block<3, 1>(0, 3) = Eigen::Vector3f(pose.position.x, pose.position.y, pose.position.z);
    return m;
}

Eigen::Vector3f vec3f(const XrVector3f& v) {
    return {v.x, v.y, v.z};
}

bool position_valid(const XrHandJointLocationEXT& joint) {
    return (joint.locationFlags & XR_SPACE_LOCATION_POSITION_VALID_BIT) != 0 && joint.radius > 0.0f;
}

}  // namespace

SceneDrawing::SceneDrawing(const Scene& scene) : scene_(scene) {
    std::size_t dynamic = 0;
    bool has_plane = false;
    for (const Collider& c : scene.colliders) {
        collider_meshes_.push_back(meshes_.add_shape(c.shape));
        Rgb color = kStatic;
        if (c.shape.kind == ShapeKind::Plane) {
            color = kFloor;
            has_plane = true;
        }
        if (c.motion == Motion::Kinematic) color = kKinematic;
        if (c.motion == Motion::Dynamic) color = kDynamic[dynamic++ % kDynamic.size()];
        collider_colors_.push_back(linear(color));
    }
    if (!has_plane) {
        Shape floor;  // y = 0, facing up
        floor.kind = ShapeKind::Plane;
        visual_floor_ = meshes_.add_shape(floor);
    }
    sphere_ = meshes_.add_unit_sphere();
    cylinder_ = meshes_.add_unit_cylinder();
    box_ = meshes_.add_unit_box();
}

std::vector<Draw> SceneDrawing::draws(
    const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders,
    const std::array<LocatedHand, 2>& hands, const DrawSettings& drawing,
    const std::vector<float>& flashes) const {
    std::vector<Draw> out;
    for (std::size_t i = 0; i < colliders.size(); ++i) {
        const Collider& c = scene_.colliders[i];
        const XrPhysicalColliderLocationPHYSHAND& location = colliders[i];
        float alpha = 1.0f;
        if (drawing.feedback && c.motion == Motion::Dynamic) {
            double gap = std::numeric_limits<double>::infinity();
            const Pose pose = to_pose(location.pose);
            for (const LocatedHand& hand : hands) {
                if (!hand.active) continue;
                for (const XrHandJointLocationEXT& joint : hand.joints) {
                    if (!position_valid(joint)) continue;
                    gap = std::min(gap,
                                   surface_distance(c.shape, pose, to_vec3(joint.pose.position)) -
                                       joint.radius);
                }
            }
            alpha = object_alpha(touched(location), gap, drawing.hover_m);
        }
        Rgb rgb = collider_colors_[i];
        const float flash = i < flashes.size() ? kFlashWhite * flashes[i] : 0.0f;
        for (float& channel : rgb) channel += (1.0f - channel) * flash;
        out.push_back(
            {collider_meshes_[i], pose_matrix(location.pose), {rgb[0], rgb[1], rgb[2], alpha}});
    }
    if (visual_floor_) {
        const Rgb floor = linear(kFloor);
        out.push_back(
            {*visual_floor_, Eigen::Matrix4f::Identity(), {floor[0], floor[1], floor[2], 1.0f}});
    }
    for (const LocatedHand& hand : hands) {
        if (drawing.hands && hand.active) add_hand(hand, out);
    }
    return out;
}

namespace {

const std::array<float, 4> kSkinColor = [] {
    const Rgb skin = linear(kSkin);
    return std::array<float, 4>{skin[0], skin[1], skin[2], 1.0f};
}();

}  // namespace

void SceneDrawing::add_sphere(const Eigen::Vector3f& centre, float radius,
                              std::vector<Draw>& draws) const {
    Eigen::Matrix4f sphere = Eigen::Matrix4f::Identity();
    sphere.block<3, 3>(0, 0) *= radius;
    sphere.block<3, 1>(0, 3) = centre;
    draws.push_back({sphere_, sphere, kSkinColor});
}

void SceneDrawing::add_hand(const LocatedHand& hand, std::vector<Draw>& draws) const {
    if (hand.shape_count > 0) {
        add_hand_shapes(hand, draws);
        return;
    }
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const XrHandJointLocationEXT& joint = hand.joints[j];
        if (!position_valid(joint)) continue;
        add_sphere(vec3f(joint.pose.position), joint.radius, draws);

        const std::optional<Joint> parent = joint_parent(static_cast<Joint>(j));
        if (!parent) continue;
        const XrHandJointLocationEXT& base = hand.joints[index_of(*parent)];
        if (!position_valid(base)) continue;
        const Eigen::Vector3f a = vec3f(base.pose.position), b = vec3f(joint.pose.position);
        const float length = (b - a).norm();
        if (length < 1e-5f) continue;
        // The unit cylinder's Y axis onto the bone, scaled to its radius and half length.
        const Eigen::Matrix3f turn =
            Eigen::Quaternionf::FromTwoVectors(Eigen::Vector3f::UnitY(), (b - a) / length)
                .toRotationMatrix();
        const float radius = kBoneRadiusScale * std::min(joint.radius, base.radius);
        Eigen::Matrix4f bone = Eigen::Matrix4f::Identity();
        bone.block<3, 3>(0, 0) = turn * Eigen::Vector3f(radius, length / 2, radius).asDiagonal();
        bone.block<3, 1>(0, 3) = (a + b) / 2;
        draws.push_back({cylinder_, bone, kSkinColor});
    }
}

void SceneDrawing::add_hand_shapes(const LocatedHand& hand, std::vector<Draw>& draws) const {
    const auto count = std::min<std::size_t>(hand.shape_count, hand.shapes.size());
    for (std::size_t i = 0; i < count; ++i) {
        const XrHandCollisionShapePHYSHAND& shape = hand.shapes[i];
        const Eigen::Matrix4f pose = pose_matrix(shape.pose);
        const Eigen::Vector3f size = vec3f(shape.size);
        switch (shape.kind) {
            case XR_HAND_COLLISION_SHAPE_KIND_BOX_PHYSHAND: {
                Eigen::Matrix4f box = pose;
                box.block<3, 3>(0, 0) *= size.asDiagonal();
                draws.push_back({box_, box, kSkinColor});
                break;
            }
            case XR_HAND_COLLISION_SHAPE_KIND_CAPSULE_PHYSHAND: {
                // The unit cylinder's Y axis onto the capsule's Z axis, and a sphere each end.
                const Eigen::Vector3f axis = pose.block<3, 1>(0, 2);
                const Eigen::Vector3f centre = pose.block<3, 1>(0, 3);
                Eigen::Matrix4f side = Eigen::Matrix4f::Identity();
                side.block<3, 3>(0, 0) =
                    Eigen::Quaternionf::FromTwoVectors(Eigen::Vector3f::UnitY(), axis)
                        .toRotationMatrix() *
                    Eigen::Vector3f(size.x(), size.z(), size.x()).asDiagonal();
                side.block<3, 1>(0, 3) = centre;
                draws.push_back({cylinder_, side, kSkinColor});
                add_sphere(centre - size.z() * axis, size.x(), draws);
                add_sphere(centre + size.z() * axis, size.x(), draws);
                break;
            }
            default:
                add_sphere(vec3f(shape.pose.position), size.x(), draws);
        }
    }
}

}  // namespace physhand::sample
