#include "run_observer.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene_colliders.h"
#include "xr_convert.h"

namespace physhand::sample {

namespace {

bool is_finite(const XrVector3f& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool is_finite(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    return is_finite(p.position) && std::isfinite(q.x) && std::isfinite(q.y) &&
           std::isfinite(q.z) && std::isfinite(q.w);
}

BodyState body_state(const XrPhysicalColliderLocationPHYSHAND& location) {
    BodyState body;
    body.pose = to_pose(location.pose);
    body.linear_velocity = to_vec3(location.linearVelocity);
    body.angular_velocity = to_vec3(location.angularVelocity);
    body.touched_by = touched_by(location);
    body.asleep = (location.flags & XR_PHYSICAL_COLLIDER_ASLEEP_BIT_PHYSHAND) != 0;
    return body;
}

}  // namespace

RunObserver::RunObserver(const Scene& scene, const DriveSettings& drive)
    : scene_(scene), drive_(drive), predicates_(scene) {
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) index_[scene.colliders[i].id] = i;
}

void RunObserver::add_frame(double t, double step_us, const std::array<LocatedHand, 2>& hands,
                            const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders) {
    bool finite = true;
    std::array<std::optional<Pose>, 2> wrists;
    for (HandSide side : kHandSides) {
        const LocatedHand& located = hands[static_cast<int>(side)];
        // Radii are left out: no metric uses them.
        HandPose ghost, physical;
        std::array<bool, kJointCount> in_contact{};
        ghost.active = located.ghost_active;
        physical.active = located.active;
        for (std::size_t j = 0; j < kJointCount; ++j) {
            ghost.joints[j] = to_pose(located.ghost[j]);
            physical.joints[j] = to_pose(located.joints[j].pose);
            in_contact[j] = located.in_contact[j] == XR_TRUE;
            finite = finite && is_finite(located.ghost[j]) && is_finite(located.joints[j].pose) &&
                     std::isfinite(located.spring_force[j]);
        }
        metrics_.add_hand(t, side, ghost, physical, in_contact);
        if (physical.active) wrists[static_cast<int>(side)] = physical[Joint::Wrist];
    }

    last_ = colliders;
    for (std::size_t i = 0, body = 0; i < last_.size(); ++i) {
        if (scene_.colliders[i].motion == Motion::Dynamic)
            metrics_.add_body(t, body++, body_state(last_[i]));
    }
    double max_speed = 0.0;
    for (const XrPhysicalColliderLocationPHYSHAND& c : last_) {
        max_speed = std::max(max_speed, to_vec3(c.linearVelocity).norm());
        finite = finite && is_finite(c.pose) && is_finite(c.linearVelocity) &&
                 is_finite(c.angularVelocity);
    }
    // Penetration depths and speeds before the limit are not visible through the API.
    metrics_.add_frame({.step_us = step_us, .max_body_speed = max_speed, .nonfinite = !finite});
    predicates_.add_frame(
        t,
        [this](const std::string& id) -> std::optional<BodyState> {
            const auto it = index_.find(id);
            if (it == index_.end()) return std::nullopt;
            return body_state(last_[it->second]);
        },
        wrists);
}

RunResult RunObserver::result() const {
    RunResult result;
    result.scene = scene_.name;
    result.path = "layer";
    result.drive = drive_.name;
    result.substeps = drive_.substeps;
    result.predicates = predicates_.finish();
    result.success = std::all_of(result.predicates.begin(), result.predicates.end(),
                                 [](const PredicateResult& p) { return p.passed; });
    result.metrics = metrics_.summary();
    for (std::size_t i = 0; i < last_.size(); ++i) {
        const Collider& c = scene_.colliders[i];
        if (c.motion == Motion::Dynamic) result.bodies.emplace_back(c.id, to_pose(last_[i].pose));
    }
    return result;
}

}  // namespace physhand::sample
