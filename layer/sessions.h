#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "config.h"
#include "dispatch.h"
#include "simulation.h"
#include "vulkan_binding.h"

// Per-instance and per-session state, the registry that finds it from a handle, and the
// conversion between the app's spaces and the layer's own frame.
namespace physhand::layer {

class OverlaySession;
class Recorder;

struct InstanceState {
    XrInstance instance = XR_NULL_HANDLE;
    NextDispatch next;
    bool extension_enabled = false;  // the app enabled XR_PHYSHAND_physical_hands
    // The app enabled XR_EXT_hand_tracking itself. When it did not, the layer may have
    // enabled it down the chain for its own trackers (next.LocateHandJointsEXT is then
    // set), but the app still cannot get its functions.
    bool app_hand_tracking = false;
    Config config;
};

struct ColliderRecord {
    ColliderHandle handle = 0;  // in the session's simulation
    Motion motion = Motion::Static;
};

// Everything the layer keeps for one session. `mutex` guards the members from it to
// `overlay_mutex`: the simulation is not thread-safe, and apps locate hands from any thread.
// `overlay_mutex` guards the overlay's members after it; xrEndFrame draws under it alone,
// so the swapchain and GPU waits of drawing never hold up a locate. Whoever takes both takes
// `overlay_mutex` first.
class SessionState {
  public:
    SessionState(std::shared_ptr<const InstanceState> owner, XrSession handle);
    ~SessionState();
    SessionState(const SessionState&) = delete;
    SessionState& operator=(const SessionState&) = delete;

    const std::shared_ptr<const InstanceState> instance;
    const XrSession session;

    std::mutex mutex;
    bool alive = true;  // false once xrDestroySession began: late callers get HANDLE_INVALID
    // The layer's own STAGE (LOCAL without one) reference space: the simulation's frame.
    // Destroyed under both locks, so the overlay reads it under `overlay_mutex` alone.
    XrSpace frame = XR_NULL_HANDLE;
    // Null when the layer could not set the session up; its hands then pass through.
    std::unique_ptr<Simulation> simulation;
    std::array<std::vector<XrHandTrackerEXT>, 2> trackers;  // by HandSide; the first one
                                                            // feeds the simulation
    // The system supports XR_EXT_hand_tracking and it is enabled down the chain.
    bool hand_tracking = false;
    // The layer's own tracker of a hand the app tracks with none, made by step_frame and
    // never seen by the app; it feeds the simulation while the app has none of that hand.
    std::array<XrHandTrackerEXT, 2> own_trackers{};
    std::unordered_map<XrPhysicalColliderPHYSHAND, ColliderRecord> colliders;
    std::unique_ptr<Recorder> recorder;  // null unless PHYSHAND_RECORD is set
    std::optional<XrTime> epoch;         // the XrTime of simulation time 0
    XrTime advanced_to = 0;              // the latest time the simulation was advanced to
    std::array<HandPose, 2> ghosts;      // the runtime's hands at advanced_to, in the frame

    std::mutex overlay_mutex;
    // The app's Vulkan objects; empty for other graphics APIs, headless sessions, with the
    // overlay turned off in the config or after it failed: then there is no overlay.
    std::optional<VulkanBinding> vulkan;
    // The system's: room for the overlay's extra layer, its largest swapchain.
    XrSystemGraphicsProperties graphics{};
    // The runtime's recommended view sizes (primary stereo, else mono; empty when it does
    // not say), to size the overlay's swapchain once.
    std::vector<VkExtent2D> recommended_views;
    std::unique_ptr<OverlaySession> overlay;  // created with the first frame it draws
    std::vector<const XrCompositionLayerBaseHeader*> submitted_layers;  // the app's + overlay

    // Where `space` is in the layer's frame at `time`. XR_ERROR_POSE_INVALID when the
    // runtime cannot locate it then; XR_ERROR_HANDLE_INVALID for a null space,
    // XR_ERROR_TIME_INVALID for time <= 0, runtime errors unchanged.
    XrResult space_in_frame(XrSpace space, XrTime time, Pose& pose) const;
    // Where the layer's frame is in `base` at `time`, and the location's flags; when
    // `flags` lacks a valid bit, `pose` is identity. Errors as above, except that an
    // unlocatable base is not one.
    XrResult frame_in_space(XrSpace base, XrTime time, Pose& pose,
                            XrSpaceLocationFlags& flags) const;

    // Advances the simulation to `time`, with both hands sampled from the runtime at each
    // physics frame's time and at `time`; does nothing for a time at or before the latest
    // (hand_tracking.cpp).
    void advance(XrTime time);
    // The once-per-frame step at xrEndFrame, for apps that locate no hands: when the frame
    // has something to show (an overlay, or colliders), creates the layer's own trackers
    // where needed and advances to `display_time` (frame_step.cpp). Both locks held.
    void step_frame(XrTime display_time);
    // Destroys the layer's own trackers (frame_step.cpp).
    void destroy_own_trackers() noexcept;

  private:
    XrResult locate(XrSpace space, XrSpace base, XrTime time, Pose& pose,
                    XrSpaceLocationFlags& flags) const;
};

// The registry of handles. Its lock is taken only inside these functions, never while
// calling out, so it nests inside any session's mutex without deadlock.
std::shared_ptr<const InstanceState> find_instance(XrInstance instance);
void add_instance(std::shared_ptr<const InstanceState> state);
// Forgets the instance and its sessions, trackers and colliders.
std::shared_ptr<const InstanceState> remove_instance(XrInstance instance);

std::shared_ptr<SessionState> find_session(XrSession session);
void add_session(std::shared_ptr<SessionState> state);
// Forgets the session and its trackers and colliders.
std::shared_ptr<SessionState> remove_session(XrSession session);

struct TrackerRef {
    std::shared_ptr<SessionState> session;
    HandSide side = HandSide::Left;
    // False for a tracker of another joint set, or created with a structure the layer does not
    // model chained to its create info: the runtime alone answers for it.
    bool simulated = true;
};
std::optional<TrackerRef> find_tracker(XrHandTrackerEXT tracker);
void add_tracker(XrHandTrackerEXT tracker, TrackerRef ref);
void remove_tracker(XrHandTrackerEXT tracker);

std::shared_ptr<SessionState> find_collider(XrPhysicalColliderPHYSHAND collider);
void add_collider(XrPhysicalColliderPHYSHAND collider, std::shared_ptr<SessionState> session);
void remove_collider(XrPhysicalColliderPHYSHAND collider);

// A session found and locked for an extension function, or the error to return: an
// unknown or destroyed session is XR_ERROR_HANDLE_INVALID, one the layer could not set up
// XR_ERROR_RUNTIME_FAILURE.
struct LockedSession {
    std::shared_ptr<SessionState> state;
    std::unique_lock<std::mutex> lock;
    XrResult result = XR_ERROR_HANDLE_INVALID;
};
LockedSession lock_session(std::shared_ptr<SessionState> state);

}  // namespace physhand::layer
