#include "hand_skeleton.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace physhand {

// The default adult hand (a right hand; the left is its mirror image through the wrist's
// YZ plane). Lengths in metres, in the wrist joint's frame: +X toward the little finger
// for the right hand, +Y out of the back of the hand, -Z toward the fingertips.
//
//   finger   metacarpal base      knuckle (MCP)          proximal  middle  distal  (phalanx
//   lengths) index    (-0.010, 0, -0.010)  (-0.024,  0.000, -0.075)  0.040  0.024  0.022 middle   (
//   0.000, 0, -0.010)  ( 0.000,  0.000, -0.078)  0.045  0.028  0.023 ring     ( 0.010, 0, -0.010)
//   ( 0.021, -0.002, -0.072)  0.042  0.027  0.023 little   ( 0.020, 0, -0.010)  ( 0.040, -0.006,
//   -0.064)  0.033  0.019  0.021 thumb    carpometacarpal joint at (-0.020, -0.008, -0.015);
//   metacarpal 0.045,
//            proximal 0.032, distal 0.028; at rest it points along (-0.55, -0.25, -0.80)
//            and flexes toward (0.6, -0.8, 0) (across the palm).
// Joint radii (centre to skin): wrist 18 mm, palm 16 mm, metacarpals 12 mm (thumb 14),
// finger joints from 9.5 mm at the knuckle to 7 mm at the tip (middle +0.5 mm, ring
// -0.3 mm, little -1 mm), thumb 10.5 / 9 / 8 mm. Overall: 186 mm wrist to middle tip,
// 84 mm across the knuckles.
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct FingerDims {
    Vec3 base;
    Vec3 knuckle;
    std::array<double, 3> phalanx;
    double radius_offset;
};

const std::array<FingerDims, 4> kFingers = {{
    {{-0.010, 0, -0.010}, {-0.024, 0.000, -0.075}, {0.040, 0.024, 0.022}, 0.0},
    {{0.000, 0, -0.010}, {0.000, 0.000, -0.078}, {0.045, 0.028, 0.023}, 0.0005},
    {{0.010, 0, -0.010}, {0.021, -0.002, -0.072}, {0.042, 0.027, 0.023}, -0.0003},
    {{0.020, 0, -0.010}, {0.040, -0.006, -0.064}, {0.033, 0.019, 0.021}, -0.001},
}};
constexpr std::array<double, 4> kFingerRadii = {0.0095, 0.0085, 0.0078, 0.0070};
// Abduction per spread step: index one step toward the thumb, ring one and little two
// steps away from it, middle fixed.
constexpr std::array<double, 4> kSpreadSteps = {1.0, 0.0, -1.0, -2.0};

const Vec3 kThumbBase{-0.020, -0.008, -0.015};
const Vec3 kThumbDirection{-0.55, -0.25, -0.80};
const Vec3 kThumbFlexToward{0.6, -0.8, 0.0};
constexpr std::array<double, 3> kThumbLengths = {0.045, 0.032, 0.028};
constexpr std::array<double, 4> kThumbRadii = {0.014, 0.0105, 0.009, 0.008};

// Frame whose -Z is `forward` and whose +Y is as close to `up` as possible.
Quat frame_from(const Vec3& forward, const Vec3& up) {
    Vec3 z = -forward.normalized();
    Vec3 y = (up - up.dot(z) * z).normalized();
    Vec3 x = y.cross(z);
    Eigen::Matrix3d m;
    m.col(0) = x;
    m.col(1) = y;
    m.col(2) = z;
    return Quat(m).normalized();
}

// Flexion bends -Z toward -Y (the palm): a rotation about -X.
Quat flex(double angle) {
    return Quat(Eigen::AngleAxisd(-angle, Vec3::UnitX()));
}

// Lays a chain of bones from `start`, rotating by flexions[i] at joint i.
void lay_chain(HandPose& hand, Joint first, Pose start, const double* lengths,
               const double* flexions, std::size_t bones, double scale) {
    Pose current = start;
    for (std::size_t i = 0; i < bones; ++i) {
        current.orientation = (current.orientation * flex(flexions[i])).normalized();
        hand.joints[index_of(first) + i] = current;
        current.position += current.orientation * Vec3(0, 0, -lengths[i] * scale);
    }
    hand.joints[index_of(first) + bones] = current;  // the tip keeps the last bone's axes
}

HandPose pose_right_hand_local(const HandArticulation& a, double scale) {
    HandPose hand;
    hand.active = true;
    hand[Joint::Wrist] = Pose{};
    hand.radii[index_of(Joint::Wrist)] = 0.018 * scale;

    const double spread_step = 7.5 * kDeg * (1.0 + std::clamp(a.spread, -1.0, 1.0));
    for (std::size_t f = 0; f < kFingers.size(); ++f) {
        const FingerDims& d = kFingers[f];
        const Joint metacarpal = static_cast<Joint>(index_of(Joint::IndexMetacarpal) + 5 * f);
        const Vec3 base = d.base * scale;
        const Vec3 knuckle = d.knuckle * scale;
        const Quat mc_frame = frame_from(knuckle - base, Vec3::UnitY());
        hand[metacarpal] = Pose{base, mc_frame};
        hand.radii[index_of(metacarpal)] = 0.012 * scale;

        const double c = a.curl[f + 1];
        const Quat abduct(Eigen::AngleAxisd(kSpreadSteps[f] * spread_step, Vec3::UnitY()));
        const double flexions[3] = {c * 90 * kDeg, c * 100 * kDeg, c * 70 * kDeg};
        lay_chain(hand, static_cast<Joint>(index_of(metacarpal) + 1), Pose{knuckle, abduct},
                  d.phalanx.data(), flexions, 3, scale);
        for (std::size_t k = 0; k < 4; ++k) {
            hand.radii[index_of(metacarpal) + 1 + k] = (kFingerRadii[k] + d.radius_offset) * scale;
        }
    }

    const Pose& middle_mc = hand[Joint::MiddleMetacarpal];
    hand[Joint::Palm] = Pose{(middle_mc.position + hand[Joint::MiddleProximal].position) / 2,
                             middle_mc.orientation};
    hand.radii[index_of(Joint::Palm)] = 0.016 * scale;

    const double c = a.curl[0];
    const Quat oppose(Eigen::AngleAxisd(c * 45 * kDeg, Vec3::UnitZ()));
    const Quat rest = frame_from(kThumbDirection, -kThumbFlexToward);
    const double flexions[3] = {c * 40 * kDeg, c * 50 * kDeg, c * 70 * kDeg};
    lay_chain(hand, Joint::ThumbMetacarpal, Pose{kThumbBase * scale, oppose * rest},
              kThumbLengths.data(), flexions, 3, scale);
    for (std::size_t k = 0; k < 4; ++k) {
        hand.radii[index_of(Joint::ThumbMetacarpal) + k] = kThumbRadii[k] * scale;
    }
    return hand;
}

}  // namespace

std::string_view hand_side_name(HandSide side) {
    return side == HandSide::Left ? "left" : "right";
}

std::optional<Joint> joint_parent(Joint j) {
    const int i = static_cast<int>(j);
    if (j == Joint::Wrist) return std::nullopt;
    if (j == Joint::Palm) return Joint::Wrist;
    // Metacarpals hang off the wrist; every other joint off the previous one.
    if (i == index_of(Joint::ThumbMetacarpal) || (i >= 6 && (i - 6) % 5 == 0)) return Joint::Wrist;
    return static_cast<Joint>(i - 1);
}

std::string_view joint_name(Joint j) {
    static constexpr std::array<std::string_view, kJointCount> kNames = {
        "palm",
        "wrist",
        "thumb_metacarpal",
        "thumb_proximal",
        "thumb_distal",
        "thumb_tip",
        "index_metacarpal",
        "index_proximal",
        "index_intermediate",
        "index_distal",
        "index_tip",
        "middle_metacarpal",
        "middle_proximal",
        "middle_intermediate",
        "middle_distal",
        "middle_tip",
        "ring_metacarpal",
        "ring_proximal",
        "ring_intermediate",
        "ring_distal",
        "ring_tip",
        "little_metacarpal",
        "little_proximal",
        "little_intermediate",
        "little_distal",
        "little_tip",
    };
    return kNames[index_of(j)];
}

HandPose pose_hand(HandSide side, const Pose& wrist, const HandArticulation& articulation,
                   double scale) {
    HandPose hand = pose_right_hand_local(articulation, scale);
    for (Pose& joint : hand.joints) {
        const Pose local = side == HandSide::Left ? mirror_x(joint) : joint;
        joint = wrist * local;
        joint.orientation.normalize();
    }
    return hand;
}

}  // namespace physhand
