#include "physics_hands.h"

#include "overlay_hands.h"
#include "simulation.h"

namespace physhand::overlay::testing {

Joints to_overlay(const HandPose& pose) {
    return layer::to_overlay(pose, physhand::Pose{});
}

std::array<int, kJointCount> skeleton_parents() {
    std::array<int, kJointCount> parents{};
    for (size_t j = 0; j < physhand::kJointCount; ++j) {
        const auto parent = joint_parent(static_cast<Joint>(j));
        parents[j] = parent ? static_cast<int>(index_of(*parent)) : -1;
    }
    return parents;
}

namespace {

// The default drive's bodies (palm box, bone capsules) where the ghosts put them.
HandSolids hand_solids(const std::array<HandPose, 2>& ghosts, HandSide side) {
    Simulation simulation(SimulationSettings{}, physhand::Vec3(0.0, -9.81, 0.0));
    simulation.step_to(0.0, ghosts);
    return simulation.hand_solids(side);
}

}  // namespace

Frame demo_frame(std::span<const View> views) {
    Frame frame;
    frame.views = views;
    frame.parents = skeleton_parents();
    const HandArticulation articulation{.curl = {0.3, 0.2, 0.2, 0.4, 0.5}, .spread = 0.2};
    std::array<HandPose, 2> poses;
    for (const HandSide side : kHandSides) {
        const double x = side == HandSide::Left ? -0.12 : 0.12;
        const physhand::Pose wrist{physhand::Vec3(x, -0.1, -0.3), physhand::Quat::Identity()};
        poses[static_cast<size_t>(side)] = pose_hand(side, wrist, articulation);
    }
    for (const HandSide side : kHandSides) {
        const HandPose& pose = poses[static_cast<size_t>(side)];
        Hand& hand = frame.hands[static_cast<size_t>(side)];
        hand.ghost_active = true;
        hand.physical_active = true;
        hand.physical = to_overlay(pose);
        hand.ghost = hand.physical;
        const HandSolids solids = hand_solids(poses, side);
        hand.solids = layer::to_overlay(solids, physhand::Pose{});
        hand.solid_count = static_cast<uint32_t>(solids.count);
        // The index and middle fingers' last bones touch, and their ghosts press on.
        for (uint32_t i = 0; i < hand.solid_count; ++i) {
            Solid& solid = hand.solids[i];
            for (const Joint tip : {Joint::IndexTip, Joint::MiddleTip}) {
                const Vec3& p = hand.physical.positions[index_of(tip)];
                for (const Vec3& end : {solid.start, solid.end}) {
                    const float dx = end.x - p.x, dy = end.y - p.y, dz = end.z - p.z;
                    if (dx * dx + dy * dy + dz * dz < 1e-8f) solid.in_contact = true;
                }
            }
        }
        for (const Joint tip : {Joint::IndexTip, Joint::MiddleTip}) {
            hand.in_contact[index_of(tip)] = true;
            hand.ghost.positions[index_of(tip)].y -= 0.015f;
        }
    }
    return frame;
}

}  // namespace physhand::overlay::testing
