#include "sessions.h"

#include <atomic>
#include <shared_mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "layer_log.h"
#include "overlay_session.h"
#include "recording.h"
#include "xr_util.h"

namespace physhand::layer {

namespace {

constexpr double kGravity = 9.81;  // m/s², along -Y of STAGE and LOCAL

struct Registry {
    std::shared_mutex mutex;
    std::unordered_map<XrInstance, std::shared_ptr<const InstanceState>> instances;
    std::unordered_map<XrSession, std::shared_ptr<SessionState>> sessions;
    std::unordered_map<XrHandTrackerEXT, TrackerRef> trackers;
    std::unordered_map<XrPhysicalColliderPHYSHAND, std::shared_ptr<SessionState>> colliders;

    // Lock held.
    void forget_children(const SessionState* session) {
        std::erase_if(trackers,
                      [&](const auto& entry) { return entry.second.session.get() == session; });
        std::erase_if(colliders, [&](const auto& entry) { return entry.second.get() == session; });
    }
};

Registry& registry() {
    static Registry instance;
    return instance;
}

template <typename Map, typename Key>
typename Map::mapped_type find_in(Map& map, const Key& key) {
    std::shared_lock lock(registry().mutex);
    const auto it = map.find(key);
    return it == map.end() ? typename Map::mapped_type{} : it->second;
}

template <typename Map, typename Key, typename Value>
void add_to(Map& map, const Key& key, Value&& value) {
    std::unique_lock lock(registry().mutex);
    map.insert_or_assign(key, std::forward<Value>(value));
}

template <typename Map, typename Key>
void remove_from(Map& map, const Key& key) {
    std::unique_lock lock(registry().mutex);
    map.erase(key);
}

// STAGE keeps the config's colliders (given in the room) where they belong; LOCAL is the
// fallback every runtime has.
XrSpace create_frame(const NextDispatch& next, XrSession session, XrReferenceSpaceType& type) {
    for (const XrReferenceSpaceType candidate :
         {XR_REFERENCE_SPACE_TYPE_STAGE, XR_REFERENCE_SPACE_TYPE_LOCAL}) {
        XrReferenceSpaceCreateInfo info{};
        info.type = XR_TYPE_REFERENCE_SPACE_CREATE_INFO;
        info.referenceSpaceType = candidate;
        info.poseInReferenceSpace.orientation.w = 1.0f;
        XrSpace space = XR_NULL_HANDLE;
        if (XR_SUCCEEDED(next.CreateReferenceSpace(session, &info, &space))) {
            type = candidate;
            return space;
        }
    }
    return XR_NULL_HANDLE;
}

// What the session needs to know of its system: room for one more composition layer (the
// overlay's), and whether it tracks hands (the layer's own trackers). A failure leaves
// both unknown, which turns the overlay and the layer's own trackers off.
void read_system(SessionState& state, XrSystemId system) {
    XrSystemHandTrackingPropertiesEXT hand_tracking{};
    hand_tracking.type = XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT;
    XrSystemProperties properties{};
    properties.type = XR_TYPE_SYSTEM_PROPERTIES;
    // Chained only where the extension is enabled down the chain.
    if (state.instance->next.CreateHandTrackerEXT != nullptr) properties.next = &hand_tracking;
    const XrResult result =
        state.instance->next.GetSystemProperties(state.instance->instance, system, &properties);
    if (XR_FAILED(result)) {
        log_once("xrCreateSession: xrGetSystemProperties failed with XrResult " +
                 std::to_string(result) + "; no overlay and no hand tracking of the layer's own");
        return;
    }
    state.graphics = properties.graphicsProperties;
    state.hand_tracking = properties.next != nullptr && hand_tracking.supportsHandTracking;
}

// The system's recommended view sizes for its primary stereo or mono views; empty when
// the runtime tells neither.
std::vector<VkExtent2D> recommended_views(const SessionState& state, XrSystemId system) {
    const NextDispatch& next = state.instance->next;
    for (const XrViewConfigurationType type :
         {XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO}) {
        uint32_t count = 0;
        if (XR_FAILED(next.EnumerateViewConfigurationViews(state.instance->instance, system, type,
                                                           0, &count, nullptr)) ||
            count == 0) {
            continue;
        }
        XrViewConfigurationView blank{};
        blank.type = XR_TYPE_VIEW_CONFIGURATION_VIEW;
        std::vector<XrViewConfigurationView> views(count, blank);
        if (XR_FAILED(next.EnumerateViewConfigurationViews(state.instance->instance, system, type,
                                                           count, &count, views.data()))) {
            continue;
        }
        std::vector<VkExtent2D> sizes;
        for (const XrViewConfigurationView& view : views) {
            sizes.push_back({view.recommendedImageRectWidth, view.recommendedImageRectHeight});
        }
        return sizes;
    }
    return {};
}

// The overlay needs the app's Vulkan objects and room for one more composition layer.
// Without them the session runs unchanged, without the overlay.
void set_up_overlay(SessionState& state, const XrSessionCreateInfo& info) {
    try {
        state.vulkan = capture_vulkan_binding(info);
        if (!state.vulkan) {
            log_once("xrCreateSession: not a Vulkan session; the hands are not drawn");
            return;
        }
        if (state.graphics.maxLayerCount == 0) {
            throw std::runtime_error("the system's composition layer count is unknown");
        }
        state.recommended_views = recommended_views(state, info.systemId);
    } catch (const std::exception& e) {
        state.vulkan.reset();
        log_failure("xrCreateSession (the hands are not drawn)", e.what());
    }
}

// A session the layer cannot simulate still works: its hands pass through unchanged.
std::shared_ptr<SessionState> make_session_state(std::shared_ptr<const InstanceState> instance,
                                                 XrSession session) {
    static std::atomic<unsigned> session_count{0};
    auto state = std::make_shared<SessionState>(instance, session);
    try {
        XrReferenceSpaceType type{};
        state->frame = create_frame(instance->next, session, type);
        if (state->frame == XR_NULL_HANDLE) {
            log_once("xrCreateSession: no STAGE or LOCAL space; hands pass through unchanged");
            return state;
        }
        SimulationSettings settings;
        settings.drive = instance->config.drive;
        auto simulation = std::make_unique<Simulation>(settings, Vec3(0, -kGravity, 0));
        if (type == XR_REFERENCE_SPACE_TYPE_STAGE) {
            for (const Collider& collider : instance->config.colliders) {
                simulation->add_collider(collider);
            }
        } else if (!instance->config.colliders.empty()) {
            log_once(
                "xrCreateSession: no STAGE space, so the config's colliders (given in the "
                "STAGE frame) are left out");
        }
        state->recorder = Recorder::from_environment(++session_count);
        state->simulation = std::move(simulation);
    } catch (const std::exception& e) {
        log_failure("xrCreateSession (hands pass through unchanged)", e.what());
    }
    return state;
}

}  // namespace

SessionState::SessionState(std::shared_ptr<const InstanceState> owner, XrSession handle)
    : instance(std::move(owner)), session(handle) {}

SessionState::~SessionState() = default;

XrResult SessionState::locate(XrSpace space, XrSpace base, XrTime time, Pose& pose,
                              XrSpaceLocationFlags& flags) const {
    if (space == XR_NULL_HANDLE || base == XR_NULL_HANDLE) return XR_ERROR_HANDLE_INVALID;
    if (time <= 0) return XR_ERROR_TIME_INVALID;
    XrSpaceLocation location{};
    location.type = XR_TYPE_SPACE_LOCATION;
    const XrResult result = instance->next.LocateSpace(space, base, time, &location);
    if (XR_FAILED(result)) return result;
    flags = location.locationFlags;
    pose = (flags & kPoseValid) == kPoseValid ? to_pose(location.pose) : Pose{};
    return result;
}

XrResult SessionState::space_in_frame(XrSpace space, XrTime time, Pose& pose) const {
    XrSpaceLocationFlags flags = 0;
    const XrResult result = locate(space, frame, time, pose, flags);
    if (XR_FAILED(result)) return result;
    return (flags & kPoseValid) == kPoseValid ? result : XR_ERROR_POSE_INVALID;
}

XrResult SessionState::frame_in_space(XrSpace base, XrTime time, Pose& pose,
                                      XrSpaceLocationFlags& flags) const {
    return locate(frame, base, time, pose, flags);
}

std::shared_ptr<const InstanceState> find_instance(XrInstance instance) {
    return find_in(registry().instances, instance);
}

void add_instance(std::shared_ptr<const InstanceState> state) {
    const XrInstance instance = state->instance;
    add_to(registry().instances, instance, std::move(state));
}

std::shared_ptr<const InstanceState> remove_instance(XrInstance instance) {
    Registry& r = registry();
    std::unique_lock lock(r.mutex);
    const auto it = r.instances.find(instance);
    if (it == r.instances.end()) return nullptr;
    std::shared_ptr<const InstanceState> state = std::move(it->second);
    r.instances.erase(it);
    std::erase_if(r.sessions, [&](const auto& entry) {
        if (entry.second->instance != state) return false;
        r.forget_children(entry.second.get());
        return true;
    });
    return state;
}

std::shared_ptr<SessionState> find_session(XrSession session) {
    return find_in(registry().sessions, session);
}

void add_session(std::shared_ptr<SessionState> state) {
    const XrSession session = state->session;
    add_to(registry().sessions, session, std::move(state));
}

std::shared_ptr<SessionState> remove_session(XrSession session) {
    Registry& r = registry();
    std::unique_lock lock(r.mutex);
    const auto it = r.sessions.find(session);
    if (it == r.sessions.end()) return nullptr;
    std::shared_ptr<SessionState> state = std::move(it->second);
    r.sessions.erase(it);
    r.forget_children(state.get());
    return state;
}

std::optional<TrackerRef> find_tracker(XrHandTrackerEXT tracker) {
    TrackerRef ref = find_in(registry().trackers, tracker);
    return ref.session ? std::optional<TrackerRef>(std::move(ref)) : std::nullopt;
}

void add_tracker(XrHandTrackerEXT tracker, TrackerRef ref) {
    add_to(registry().trackers, tracker, std::move(ref));
}

void remove_tracker(XrHandTrackerEXT tracker) {
    remove_from(registry().trackers, tracker);
}

std::shared_ptr<SessionState> find_collider(XrPhysicalColliderPHYSHAND collider) {
    return find_in(registry().colliders, collider);
}

void add_collider(XrPhysicalColliderPHYSHAND collider, std::shared_ptr<SessionState> session) {
    add_to(registry().colliders, collider, std::move(session));
}

void remove_collider(XrPhysicalColliderPHYSHAND collider) {
    remove_from(registry().colliders, collider);
}

LockedSession lock_session(std::shared_ptr<SessionState> state) {
    LockedSession locked;
    if (!state) return locked;
    // The state is held before its mutex is locked, so the mutex outlives the lock.
    locked.state = std::move(state);
    locked.lock = std::unique_lock(locked.state->mutex);
    if (locked.state->alive) {
        locked.result = locked.state->simulation ? XR_SUCCESS : XR_ERROR_RUNTIME_FAILURE;
    }
    return locked;
}

XRAPI_ATTR XrResult XRAPI_CALL CreateSession(XrInstance instance,
                                             const XrSessionCreateInfo* createInfo,
                                             XrSession* session) {
    return guarded("xrCreateSession", [&] {
        const std::shared_ptr<const InstanceState> state = find_instance(instance);
        if (!state) return XR_ERROR_HANDLE_INVALID;
        const XrResult result = state->next.CreateSession(instance, createInfo, session);
        if (XR_FAILED(result)) return result;
        try {
            std::shared_ptr<SessionState> session_state = make_session_state(state, *session);
            read_system(*session_state, createInfo->systemId);
            if (state->config.overlay) set_up_overlay(*session_state, *createInfo);
            add_session(std::move(session_state));
        } catch (...) {
            // Without its state the session would be unusable through the layer.
            state->next.DestroySession(*session);
            *session = XR_NULL_HANDLE;
            throw;
        }
        return result;
    });
}

XRAPI_ATTR XrResult XRAPI_CALL DestroySession(XrSession session) {
    return guarded("xrDestroySession", [&] {
        const std::shared_ptr<SessionState> state = remove_session(session);
        if (!state) return XR_ERROR_HANDLE_INVALID;
        {
            std::scoped_lock lock(state->overlay_mutex, state->mutex);
            state->alive = false;
            if (state->frame != XR_NULL_HANDLE) state->instance->next.DestroySpace(state->frame);
            state->frame = XR_NULL_HANDLE;
            // Freed now, not when the last concurrent caller lets go of the state.
            // Before the session: the overlay's swapchain belongs to it.
            state->overlay.reset();
            state->destroy_own_trackers();
            state->simulation.reset();
            state->colliders.clear();
            state->recorder.reset();
        }
        return state->instance->next.DestroySession(session);
    });
}

}  // namespace physhand::layer
