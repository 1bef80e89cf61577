// The variants of scene_variants that change the objects a hand handles: made larger or
// smaller, the hands adapted to them as a person would adapt (the size family), or lying off the
// place the hand grasps (the off-centre grasp sweep of the robustness benchmark).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "scene_variants.h"
#include "tracking.h"

namespace physhand {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kSamplePeriod = 0.02;   // s between the script's samples searched for contact
constexpr int kCurlSteps = 100;          // curls tried per finger
constexpr double kGripTolerance = 5e-4;  // m of fingertip depth a person would not tell apart

constexpr std::array<Joint, kFingerCount> kTips = {
    Joint::ThumbTip, Joint::IndexTip, Joint::MiddleTip, Joint::RingTip, Joint::LittleTip};
constexpr std::array<const char*, kFingerCount> kFingerNames = {"thumb", "index", "middle", "ring",
                                                                "little"};

bool resizable(const Collider& c) {
    return c.motion == Motion::Dynamic &&
           (c.shape.kind == ShapeKind::Box || c.shape.kind == ShapeKind::Sphere ||
            c.shape.kind == ShapeKind::Capsule || c.shape.kind == ShapeKind::Cylinder);
}

// From `world` to the collider's surface, negative inside, m (resizable shapes only).
double signed_distance(const Collider& c, const Vec3& world) {
    const Vec3 p = c.pose.inverse() * world;
    const double r = c.shape.radius;
    const double h = c.shape.half_height;
    switch (c.shape.kind) {
        case ShapeKind::Box: {
            const Vec3 q = p.cwiseAbs() - c.shape.half_extents;
            return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
        }
        case ShapeKind::Sphere:
            return p.norm() - r;
        case ShapeKind::Capsule:
            return (p - Vec3(0, std::clamp(p.y(), -h, h), 0)).norm() - r;
        case ShapeKind::Cylinder: {
            const double out = std::hypot(p.x(), p.z()) - r;
            const double along = std::abs(p.y()) - h;
            return std::min(std::max(out, along), 0.0) +
                   std::hypot(std::max(out, 0.0), std::max(along, 0.0));
        }
        default:
            return kInfinity;
    }
}

// How far the collider reaches from its centre against `up`: its centre's height above what
// it rests on.
double reach_below(const Collider& c, const Vec3& up) {
    const Vec3 u = c.pose.orientation.inverse() * up;
    const double r = c.shape.radius;
    const double h = c.shape.half_height;
    switch (c.shape.kind) {
        case ShapeKind::Box:
            return u.cwiseAbs().dot(c.shape.half_extents);
        case ShapeKind::Sphere:
            return r;
        case ShapeKind::Capsule:
            return r + std::abs(u.y()) * h;
        case ShapeKind::Cylinder:
            return std::abs(u.y()) * h + r * std::sqrt(std::max(0.0, 1.0 - u.y() * u.y()));
        default:
            return 0.0;
    }
}

// How deep `world` lies in the collider along the ray from its centre (negative: outside), m:
// the depth a finger closing toward an object's centre reaches, which a larger object deepens
// and a smaller one lessens wherever the finger touches it.
double radial_depth(const Collider& c, const Vec3& world) {
    const Vec3 p = c.pose.inverse() * world;
    const double r = c.shape.radius;
    const double h = c.shape.half_height;
    double fraction = 0.0;  // of the way from the centre to the surface
    switch (c.shape.kind) {
        case ShapeKind::Box:
            fraction = p.cwiseAbs().cwiseQuotient(c.shape.half_extents).maxCoeff();
            break;
        case ShapeKind::Sphere:
            fraction = p.norm() / r;
            break;
        case ShapeKind::Capsule:
        case ShapeKind::Cylinder:
            fraction = std::max(std::hypot(p.x(), p.z()) / r,
                                std::abs(p.y()) / (c.shape.kind == ShapeKind::Capsule ? h + r : h));
            break;
        default:
            return -kInfinity;
    }
    return fraction > 0.0 ? p.norm() * (1.0 / fraction - 1.0) : kInfinity;
}

// How deep the fingertip's skin reaches into the nearest of `objects` (negative: short of it).
double tip_depth(const HandPose& hand, Joint tip, const std::vector<const Collider*>& objects) {
    double deepest = -kInfinity;
    for (const Collider* c : objects)
        deepest = std::max(deepest, radial_depth(*c, hand[tip].position));
    return hand.radii[index_of(tip)] + deepest;
}

// How close the hand's skin comes to the collider at any joint (negative: inside), m.
double skin_gap(const HandPose& hand, const Collider& c) {
    double gap = kInfinity;
    for (std::size_t j = 0; j < kJointCount; ++j)
        gap = std::min(gap, signed_distance(c, hand.joints[j].position) - hand.radii[j]);
    return gap;
}

// Closest a ghost joint's skin comes to the collider while the hands' scripts play.
double closest_approach(const Scene& scene, const Collider& c) {
    double closest = kInfinity;
    for (HandSide side : kHandSides) {
        const auto& script = scene.hand(side);
        if (!script) continue;
        const double from =
            script->keyframes.empty() ? script->recorded.front().t : script->keyframes.front().t;
        const double to =
            script->keyframes.empty() ? script->recorded.back().t : script->keyframes.back().t;
        for (double t = from; t <= to + 1e-9; t += kSamplePeriod) {
            const HandPose hand = evaluate_script(*script, side, t);
            if (!hand.active) continue;
            closest = std::min(closest, skin_gap(hand, c));
        }
    }
    return closest;
}

// Where a hand works on the handled objects: the keyframe reaching deepest into one with its
// fingertips (a grip), or else coming closest to one with any joint (a push or a flick), and
// that object.
struct WorkPoint {
    const Keyframe* key = nullptr;
    const Collider* object = nullptr;
};

WorkPoint work_point(const HandScript& script, HandSide side,
                     const std::vector<const Collider*>& objects) {
    WorkPoint grip, touch;
    double deepest = 0.0, closest = kInfinity;
    for (const Keyframe& k : script.keyframes) {
        const HandPose hand = pose_hand(side, k.wrist, k.articulation, script.scale);
        for (const Collider* c : objects) {
            double depth = 0.0;
            for (Joint tip : kTips) depth += std::max(0.0, tip_depth(hand, tip, {c}));
            if (depth > deepest) {
                deepest = depth;
                grip = {&k, c};
            }
            const double gap = skin_gap(hand, *c);
            if (gap < closest) {
                closest = gap;
                touch = {&k, c};
            }
        }
    }
    return grip.key ? grip : touch;
}

// The change of each finger's curl that keeps its tip as deep in the grip as before, for the
// hand at `grip` raised by `rise`, gripping `after` instead of `before`.
std::array<double, kFingerCount> grip_change(const HandScript& script, HandSide side,
                                             const Keyframe& grip, const Vec3& rise,
                                             const std::vector<const Collider*>& before,
                                             const std::vector<const Collider*>& after) {
    std::array<double, kFingerCount> change{};
    const HandPose held = pose_hand(side, grip.wrist, grip.articulation, script.scale);
    Pose wrist = grip.wrist;
    wrist.position += rise;
    for (std::size_t f = 0; f < kFingerCount; ++f) {
        const double want = tip_depth(held, kTips[f], before);
        const double original = grip.articulation.curl[f];
        if (want < -kHandledDistance || original == 0.0) continue;  // not part of the grip
        double best = original, best_error = kInfinity;
        for (int step = 0; step <= kCurlSteps; ++step) {
            HandArticulation a = grip.articulation;
            a.curl[f] = static_cast<double>(step) / kCurlSteps;
            const HandPose hand = pose_hand(side, wrist, a, script.scale);
            // Within the tolerance every curl is as good: the nearest to the original wins.
            const double error =
                std::max(kGripTolerance, std::abs(tip_depth(hand, kTips[f], after) - want));
            const bool closer = std::abs(a.curl[f] - original) < std::abs(best - original);
            if (error < best_error || (error == best_error && closer)) {
                best_error = error;
                best = a.curl[f];
            }
        }
        change[f] = best - original;
    }
    return change;
}

}  // namespace

Scene resized(const Scene& input, double scale, std::string& adapted) {
    adapted.clear();
    Scene scene = input;
    const Vec3 up = input.gravity.norm() > 0.0 ? Vec3(-input.gravity.normalized()) : Vec3::UnitY();
    std::vector<const Collider*> before, after;
    double support = kInfinity;  // height of what the handled objects rest on
    double stack = 0.0;          // their heights, one on another
    double closest = kInfinity;
    double nearest_rise = 0.0;  // of the centre of the object a hand comes closest to
    for (std::size_t i = 0; i < input.colliders.size(); ++i) {
        const Collider& c = input.colliders[i];
        if (!resizable(c)) continue;
        const double approach = closest_approach(input, c);
        if (approach > kHandledDistance) continue;
        Collider& resized = scene.colliders[i];
        const double below = reach_below(c, up);
        resized.shape.half_extents *= scale;
        resized.shape.radius *= scale;
        resized.shape.half_height *= scale;
        resized.pose.position += (scale - 1.0) * below * up;
        resized.mass *= scale * scale * scale;
        before.push_back(&c);
        after.push_back(&resized);
        support = std::min(support, c.pose.position.dot(up) - below);
        stack += 2.0 * below;
        if (approach < closest) {
            closest = approach;
            nearest_rise = (scale - 1.0) * below;
        }
    }
    if (before.empty()) return scene;

    std::ostringstream what;
    what.precision(1);
    what << std::fixed;
    for (HandSide side : kHandSides) {
        auto& script = scene.hands[static_cast<int>(side)];
        if (!script) continue;
        for (RecordedSample& sample : script->recorded) {
            for (Pose& joint : sample.hand.joints) joint.position += nearest_rise * up;
        }
        const WorkPoint work = work_point(*input.hand(side), side, before);
        if (!work.key) continue;
        // Everything the hand handles grows about what it rests on, a stack of them too: the
        // point the hand works at (where the object's centre is in the hand) rises as the
        // height it works at, up to the height of all of them stacked.
        const Vec3 in_hand = work.key->wrist.inverse() * work.object->pose.position;
        const auto rise = [&](const Keyframe& k) {
            const double height = (k.wrist * in_hand).dot(up) - support;
            return (scale - 1.0) * std::clamp(height, 0.0, stack) * up;
        };
        const std::array<double, kFingerCount> change =
            grip_change(*input.hand(side), side, *work.key, rise(*work.key), before, after);
        double lowest = kInfinity, highest = -kInfinity;
        for (Keyframe& k : script->keyframes) {
            const Vec3 raised = rise(k);
            lowest = std::min(lowest, raised.dot(up));
            highest = std::max(highest, raised.dot(up));
            k.wrist.position += raised;
            for (std::size_t f = 0; f < kFingerCount; ++f) {
                double& curl = k.articulation.curl[f];
                if (curl > 0.0) curl = std::clamp(curl + change[f], 0.0, 1.0);
            }
        }
        what << (what.tellp() > 0 ? "; " : "") << "hand raised " << rise(*work.key).dot(up) * 1000.0
             << " mm at " << std::setprecision(2) << work.key->t << std::setprecision(1) << " s ("
             << lowest * 1000.0 << " to " << highest * 1000.0
             << " mm over the script, as the height it works at grows)";
        for (std::size_t f = 0; f < kFingerCount; ++f) {
            if (change[f] != 0.0) {
                what << ", " << kFingerNames[f] << " curl " << std::showpos << std::setprecision(2)
                     << change[f] << std::setprecision(1) << std::noshowpos;
            }
        }
    }
    adapted = what.str();
    return scene;
}

Scene grasped_off_centre(const Scene& input, const Vec3& offset) {
    Scene scene = input;
    for (std::size_t i = 0; i < input.colliders.size(); ++i) {
        const Collider& c = input.colliders[i];
        if (resizable(c) && closest_approach(input, c) <= kHandledDistance)
            scene.colliders[i].pose.position += offset;
    }
    return scene;
}

}  // namespace physhand
