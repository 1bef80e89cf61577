#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

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
