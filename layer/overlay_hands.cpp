#include "overlay_hands.h"

#include <tuple>

namespace physhand::layer {

namespace {

overlay::Vec3 to_overlay(const Vec3& v) {
    return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

}  // namespace

overlay::Joints to_overlay(const HandPose& hand, const Pose& frame) {
    overlay::Joints joints;
    for (std::size_t i = 0; i < kJointCount; ++i) {
        joints.positions[i] = to_overlay(frame * hand.joints[i].position);
        joints.radii[i] = static_cast<float>(hand.radii[i]);
    }
    return joints;
}

std::array<overlay::Solid, overlay::kMaxSolids> to_overlay(const HandSolids& solids,
                                                           const Pose& frame) {
    static_assert(overlay::kMaxSolids >= std::tuple_size_v<decltype(HandSolids::parts)>);
    std::array<overlay::Solid, overlay::kMaxSolids> out{};
    for (std::size_t i = 0; i < solids.count; ++i) {
        const HandSolid& solid = solids.parts[i];
        const Pose pose = frame * solid.pose;
        overlay::Solid& drawn = out[i];
        drawn.in_contact = solid.in_contact;
        drawn.start = drawn.end = to_overlay(pose.position);
        drawn.radius = static_cast<float>(solid.size.x());
        switch (solid.kind) {
            case HandSolid::Kind::Sphere:
                break;
            case HandSolid::Kind::Capsule: {
                const Vec3 half_axis = pose.orientation * Vec3(0.0, 0.0, solid.size.z());
                drawn.start = to_overlay(pose.position - half_axis);
                drawn.end = to_overlay(pose.position + half_axis);
                break;
            }
            case HandSolid::Kind::Box: {
                const Quat& q = pose.orientation;
                drawn.kind = overlay::Solid::Kind::Box;
                drawn.orientation = {static_cast<float>(q.x()), static_cast<float>(q.y()),
                                     static_cast<float>(q.z()), static_cast<float>(q.w())};
                drawn.half_extents = to_overlay(solid.size);
                break;
            }
        }
    }
    return out;
}

}  // namespace physhand::layer
