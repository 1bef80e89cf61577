#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <vector>

#include "scene.h"
#include "xr_handle.h"

namespace physhand::sample {

// The XR_PHYSHAND_physical_hands collider functions.
struct ColliderFunctions {
    PFN_xrCreatePhysicalColliderPHYSHAND create = nullptr;
    PFN_xrDestroyPhysicalColliderPHYSHAND destroy = nullptr;
    PFN_xrSetPhysicalColliderPosePHYSHAND set_pose = nullptr;
    PFN_xrLocatePhysicalCollidersPHYSHAND locate = nullptr;

    static ColliderFunctions load(XrInstance instance);
};

// Whether each hand (left, right, as physhand::HandSide) touched the collider in the last
// step, from the extension's flags.
inline std::array<bool, 2> touched_by(const XrPhysicalColliderLocationPHYSHAND& location) {
    return {(location.flags & XR_PHYSICAL_COLLIDER_TOUCHED_BY_LEFT_BIT_PHYSHAND) != 0,
            (location.flags & XR_PHYSICAL_COLLIDER_TOUCHED_BY_RIGHT_BIT_PHYSHAND) != 0};
}
// Whether either hand did.
inline bool touched(const XrPhysicalColliderLocationPHYSHAND& location) {
    const std::array<bool, 2> by = touched_by(location);
    return by[0] || by[1];
}

// A scene's colliders declared to the layer, in scene order, in the STAGE space.
class SceneColliders {
  public:
    // Declares every collider at its scene pose at `time`.
    SceneColliders(const Scene& scene, const ColliderFunctions& functions, XrInstance instance,
                   XrSession session, XrSpace stage, XrTime time);

    // Moves each kinematic collider that has a path to where the path is at scene time `t`
    // (`time` is the same instant as an XrTime).
    void follow_paths(XrTime time, double t) const;
    // Every collider, in scene order, at `time`.
    const std::vector<XrPhysicalColliderLocationPHYSHAND>& locate(XrTime time);
    // What the latest locate() returned.
    const std::vector<XrPhysicalColliderLocationPHYSHAND>& located() const { return locations_; }

  private:
    const Scene& scene_;
    ColliderFunctions functions_;
    XrInstance instance_;
    XrSession session_;
    XrSpace stage_;
    std::vector<XrHandle<XrPhysicalColliderPHYSHAND>> owned_;
    std::vector<XrPhysicalColliderPHYSHAND> handles_;  // the same, as the locate call wants them
    std::vector<XrPhysicalColliderLocationPHYSHAND> locations_;
};

}  // namespace physhand::sample
