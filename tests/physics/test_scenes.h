#pragma once

#include <random>
#include <string>

#include "hand_skeleton.h"
#include "scene.h"

namespace physhand::testing {

inline Scene sample_scene(const std::string& name) {
    return load_scene(std::string(PHYSHAND_SCENES_DIR) + "/" + name + ".json");
}

// The default hand with every finger curled by `curl`, its wrist at `wrist`.
inline HandPose hand_pose(HandSide side, const Vec3& wrist, double curl,
                          const Quat& orientation = Quat::Identity()) {
    HandArticulation a;
    a.curl.fill(curl);
    return pose_hand(side, Pose{wrist, orientation}, a);
}

inline HandPose right_hand(const Vec3& wrist, double curl) {
    return hand_pose(HandSide::Right, wrist, curl);
}

inline Collider static_box(const std::string& id, const Vec3& center, const Vec3& half) {
    Collider c;
    c.id = id;
    c.shape.kind = ShapeKind::Box;
    c.shape.half_extents = half;
    c.motion = Motion::Static;
    c.pose.position = center;
    return c;
}

inline Collider floor_plane() {
    Collider c;
    c.id = "floor";
    c.shape.kind = ShapeKind::Plane;
    c.motion = Motion::Static;
    return c;
}

inline Collider dynamic_box(const std::string& id, const Vec3& center, double half, double mass) {
    Collider c = static_box(id, center, Vec3::Constant(half));
    c.motion = Motion::Dynamic;
    c.mass = mass;
    return c;
}

inline Collider dynamic_ball(const std::string& id, const Vec3& center, double radius,
                             double mass) {
    Collider c;
    c.id = id;
    c.shape.kind = ShapeKind::Sphere;
    c.shape.radius = radius;
    c.motion = Motion::Dynamic;
    c.mass = mass;
    c.pose.position = center;
    return c;
}

// Adds white noise of `sigma` per axis to every joint's position.
class Noisy {
  public:
    explicit Noisy(double sigma, std::uint64_t seed = 7) : rng_(seed), noise_(0.0, sigma) {}
    HandPose operator()(HandPose hand) {
        for (Pose& joint : hand.joints)
            joint.position += Vec3(noise_(rng_), noise_(rng_), noise_(rng_));
        return hand;
    }

  private:
    std::mt19937_64 rng_;
    std::normal_distribution<double> noise_;
};

}  // namespace physhand::testing
