#pragma once

#include <openxr/openxr.h>

#include <optional>

#include "hand_trackers.h"
#include "run_observer.h"
#include "scene.h"
#include "scene_colliders.h"
#include "scene_run.h"
#include "xr_handle.h"

namespace physhand::sample {

// A headless OpenXR app that plays a scene through the loader, the physhand layer and the
// runtime: it declares the scene's colliders, moves the kinematic ones along their paths
// and reads back the physical hands and colliders every frame.
class XrApp {
  public:
    // Creates the instance (XR_EXT_hand_tracking, XR_MND_headless, XR_PHYSHAND_physical_hands),
    // a headless session, a STAGE space and both hand trackers. Throws XrCallError for a
    // failed call, std::runtime_error when an extension is missing.
    explicit XrApp(const Scene& scene);

    // Runs the frame loop until the scene has played or the runtime ends the session.
    RunResult run();

  private:
    // Handles every queued event; false once the session is over.
    bool poll_events();
    // Scene frame `frame` (1, 2, ...), displayed at `time`.
    void play_frame(int frame, XrTime time, RunObserver& observer);

    const Scene& scene_;
    // Declared parents first: members are destroyed in reverse order.
    XrHandle<XrInstance> instance_;
    XrHandle<XrSession> session_;
    XrHandle<XrSpace> stage_;
    std::optional<HandTrackers> trackers_;  // made once the session exists
    ColliderFunctions collider_functions_;
    std::optional<SceneColliders> colliders_;  // declared at the first frame
    bool running_ = false;                     // between xrBeginSession and xrEndSession
};

}  // namespace physhand::sample
