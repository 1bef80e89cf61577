#include "physics_hands.h"

namespace physhand::overlay::testing {

Joints to_overlay(const HandPose& pose) {
    Joints joints;
    for (size_t j = 0; j < physhand::kJointCount; ++j) {
        const auto& p = pose.joints[j].position;
        joints.positions[j] = {static_cast<float>(p.x()), static_cast<float>(p.y()),
                               static_cast<float>(p.z())};
        joints.radii[j] = static_cast<float>(pose.radii[j]);
    }
    return joints;
}

std::array<int, kJointCount> skeleton_parents() {
    std::array<int, kJointCount> parents{};
    for (size_t j = 0; j < physhand::kJointCount; ++j) {
        const auto parent = joint_parent(static_cast<Joint>(j));
        parents[j] = parent ? static_cast<int>(index_of(*parent)) : -1;
    }
    return parents;
}

Frame demo_frame(std::span<const View> views) {
    Frame frame;
    frame.views = views;
    frame.parents = skeleton_parents();
    const HandArticulation articulation{.curl = {0.3, 0.2, 0.2, 0.4, 0.5}, .spread = 0.2};
    for (const HandSide side : kHandSides) {
        const double x = side == HandSide::Left ? -0.12 : 0.12;
        const physhand::Pose wrist{physhand::Vec3(x, -0.1, -0.3), physhand::Quat::Identity()};
        const HandPose pose = pose_hand(side, wrist, articulation);
        Hand& hand = frame.hands[static_cast<size_t>(side)];
        hand.ghost_active = true;
        hand.physical_active = true;
        hand.physical = to_overlay(pose);
        hand.ghost = hand.physical;
        for (const Joint tip : {Joint::IndexTip, Joint::MiddleTip}) {
            hand.in_contact[index_of(tip)] = true;
            hand.ghost.positions[index_of(tip)].y -= 0.015f;
        }
    }
    return frame;
}

}  // namespace physhand::overlay::testing
