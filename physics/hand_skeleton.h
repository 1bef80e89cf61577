#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

#include "pose.h"

namespace physhand {

// The 26 joints of XR_EXT_hand_tracking, in its enum order (values equal XrHandJointEXT;
// physics/ may not include OpenXR, so the layer static_asserts the correspondence).
enum class Joint : int {
    Palm = 0,
    Wrist,
    ThumbMetacarpal,
    ThumbProximal,
    ThumbDistal,
    ThumbTip,
    IndexMetacarpal,
    IndexProximal,
    IndexIntermediate,
    IndexDistal,
    IndexTip,
    MiddleMetacarpal,
    MiddleProximal,
    MiddleIntermediate,
    MiddleDistal,
    MiddleTip,
    RingMetacarpal,
    RingProximal,
    RingIntermediate,
    RingDistal,
    RingTip,
    LittleMetacarpal,
    LittleProximal,
    LittleIntermediate,
    LittleDistal,
    LittleTip,
};

inline constexpr std::size_t kJointCount = 26;
inline constexpr std::size_t kFingerCount = 5;  // thumb, index, middle, ring, little

enum class HandSide : int { Left = 0, Right = 1 };
inline constexpr std::array<HandSide, 2> kHandSides = {HandSide::Left, HandSide::Right};
std::string_view hand_side_name(HandSide side);

constexpr std::size_t index_of(Joint j) {
    return static_cast<std::size_t>(j);
}

// Each finger's first bone that moves against the palm (the thumb's metacarpal, the other
// fingers' proximal): it and the two after it are the finger's bones, the last ending at
// the tip.
inline constexpr std::array<Joint, kFingerCount> kFingerFirstBone = {
    Joint::ThumbMetacarpal, Joint::IndexProximal, Joint::MiddleProximal, Joint::RingProximal,
    Joint::LittleProximal};

// Parent in the kinematic tree (the wrist is the root; the palm hangs off the wrist).
std::optional<Joint> joint_parent(Joint j);
std::string_view joint_name(Joint j);

// One sample of a hand: joint poses with XR_EXT_hand_tracking axes (-Z toward the
// fingertips, +Y out of the back of the hand) and radii (joint centre to skin).
struct HandPose {
    bool active = false;
    std::array<Pose, kJointCount> joints{};
    std::array<double, kJointCount> radii{};

    const Pose& operator[](Joint j) const { return joints[index_of(j)]; }
    Pose& operator[](Joint j) { return joints[index_of(j)]; }
};

// Shape parameters of the keyframed hand (docs/scene-format.md, HAND).
struct HandArticulation {
    std::array<double, kFingerCount> curl{};  // 0 open .. 1 fist
    double spread = 0.0;                      // -1 pressed together .. 1 fanned
};

// Builds the default adult hand (dimensions in hand_skeleton.cpp) in the given
// articulation, with its wrist joint at `wrist` and every length multiplied by `scale`.
HandPose pose_hand(HandSide side, const Pose& wrist, const HandArticulation& articulation,
                   double scale = 1.0);

}  // namespace physhand
