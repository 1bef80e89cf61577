#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <optional>
#include <vector>

#include "hand_trackers.h"
#include "scene.h"
#include "shape_meshes.h"
#include "shape_renderer.h"

namespace physhand::sample {

// What the sample draws besides the colliders, and how touched and nearly touched objects
// are shown (touch_feedback.h).
struct DrawSettings {
    bool feedback = true;   // false: every object stays opaque
    double hover_m = 0.03;  // objects start to fade within this gap to a hand
    bool hands = true;      // false: the app draws no hands (the layer's overlay may)
};

// What the sample draws of a scene: its colliders where the layer says they are, in
// colours by kind (floor, static, kinematic, one hue per dynamic collider), and the
// physical hands as the shapes they collide as (the layer's XrHandCollisionShapesPHYSHAND;
// without the layer, the runtime's joints and bones). The scene format has no colours, so these are
// the sample's own. A scene without a plane collider gets a floor at y = 0 to stand on, drawn only:
// nothing collides with it.
class SceneDrawing {
  public:
    explicit SceneDrawing(const Scene& scene);

    // The meshes every draw refers to.
    const MeshSet& meshes() const { return meshes_; }

    // Colliders (located in scene order) and both hands as draws; dynamic colliders are
    // translucent while touched or hovered over (DrawSettings), and each collider turns
    // toward white by its flash (0..1, scene order; missing ones are 0) as a touch begins.
    std::vector<Draw> draws(const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders,
                            const std::array<LocatedHand, 2>& hands, const DrawSettings& drawing,
                            const std::vector<float>& flashes = {}) const;

  private:
    void add_hand(const LocatedHand& hand, std::vector<Draw>& draws) const;
    void add_hand_shapes(const LocatedHand& hand, std::vector<Draw>& draws) const;
    void add_sphere(const Eigen::Vector3f& centre, float radius, std::vector<Draw>& draws) const;

    const Scene& scene_;
    MeshSet meshes_;
    std::vector<MeshRange> collider_meshes_;             // scene order
    std::vector<std::array<float, 3>> collider_colors_;  // linear rgb
    std::optional<MeshRange> visual_floor_;              // when the scene has no plane
    MeshRange sphere_;
    MeshRange cylinder_;
    MeshRange box_;
};

}  // namespace physhand::sample
