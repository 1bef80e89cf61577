#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <optional>
#include <vector>

#include "app_engine.h"
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

// A scene's colliders declared to the layer, in scene order, in the STAGE space. Those the
// scene's app_engine names live in the sample's own engine (AppEngine) and are declared
// kinematic: the coupling recipe of XR_PHYSHAND_physical_hands, as an app would follow it.
class SceneColliders {
  public:
    // Declares every collider at its scene pose at `time`.
    SceneColliders(const Scene& scene, const ColliderFunctions& functions, XrInstance instance,
                   XrSession session, XrSpace stage, XrTime time);

    // Moves each kinematic collider that has a path to where the path is at scene time `t`
    // (`time` is the same instant as an XrTime), and each of the app's objects to where its
    // engine has it then.
    void follow(XrTime time, double t);
    // Every collider, in scene order, at `time`; the hands' impulses on the app's objects go
    // to its engine.
    const std::vector<XrPhysicalColliderLocationPHYSHAND>& locate(XrTime time);
    // What the latest locate() returned.
    const std::vector<XrPhysicalColliderLocationPHYSHAND>& located() const { return locations_; }
    // The scene index of a collider the layer names, if it is one of these.
    std::optional<std::size_t> index_of(XrPhysicalColliderPHYSHAND collider) const;

  private:
    const Scene& scene_;
    ColliderFunctions functions_;
    XrInstance instance_;
    XrSession session_;
    XrSpace stage_;
    std::vector<XrHandle<XrPhysicalColliderPHYSHAND>> owned_;
    std::vector<XrPhysicalColliderPHYSHAND> handles_;  // the same, as the locate call wants them
    std::vector<XrPhysicalColliderLocationPHYSHAND> locations_;
    AppEngine engine_;
    double engine_t_ = 0.0;  // the scene time the engine has reached
    std::vector<XrPhysicalColliderImpulsePHYSHAND> impulses_;
};

}  // namespace physhand::sample
