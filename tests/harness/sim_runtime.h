#pragma once

// Internal header of the simulated OpenXR runtime: its state, the handle registries and
// the entry points each sim_*.cpp file implements. Nothing here is exported; the loader
// reaches the entry points only through xrGetInstanceProcAddr.

#include <openxr/openxr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "frame_clock.h"
#include "pose.h"
#include "scene.h"
#include "sim_vulkan.h"
#include "tracking.h"

namespace physhand::sim {

inline constexpr XrSystemId kSystemId = 1;
inline constexpr std::uint32_t kMaxLayerCount = 16;
inline constexpr std::uint32_t kViewCount = 2;    // PRIMARY_STEREO
inline constexpr std::uint32_t kViewSize = 1024;  // display pixels per eye, square
inline constexpr double kEyeHeight = 1.6;         // LOCAL and VIEW origins above the STAGE floor

// Everything the simulation locates is known exactly.
inline constexpr XrSpaceLocationFlags kLocatedFlags =
    XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
    XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
inline constexpr XrSpaceVelocityFlags kVelocityFlags =
    XR_SPACE_VELOCITY_LINEAR_VALID_BIT | XR_SPACE_VELOCITY_ANGULAR_VALID_BIT;

// Virtual clock: scene time 0 is kSceneStart, a whole number of 90 Hz periods (as any
// XrTime origin may be), and the first displayed frame is scene frame 1, as in the headless
// runner (scene/scene_run.cpp), so both play the very same ghosts. Nothing sleeps, so
// runs are deterministic (unless PHYSHAND_SIM_SWAPCHAIN_WAIT_MS asks, sim_swapchain.cpp).
inline constexpr XrTime kSceneStart = 90 * kFramePeriodNs;

// Scene time in seconds of an XrTime.
inline double scene_time(XrTime time) {
    return clock_seconds(time - kSceneStart);
}

// How the virtual display shows frames, from the environment: PHYSHAND_SIM_DISPLAY_HZ
// (20-240, default 90), PHYSHAND_SIM_FRAME_JITTER_MS (each frame early or late by up to
// this, uniformly, under a third of a period; seeded by PHYSHAND_SIM_FRAME_JITTER_SEED)
// and PHYSHAND_SIM_DROP_EVERY (every Nth frame is dropped: the next waited frame is shown
// a period later; N >= 2). A value out of range is reported on stderr and ignored.
// PHYSHAND_SIM_HEADLESS_FRAME_LOOP=0 gives headless sessions no frame loop, as Monado's:
// xrWaitFrame succeeds with no display time (0) and counts as no wait, so xrBeginFrame
// answers XR_ERROR_CALL_ORDER_INVALID; time then comes from XR_KHR_convert_timespec_time,
// on which XrTime is kSceneStart plus the CLOCK_MONOTONIC time since the instance was made.
struct DisplayClock {
    std::int64_t period_ns = kFramePeriodNs;
    std::int64_t jitter_ns = 0;
    std::uint64_t jitter_seed = 0;
    std::int64_t drop_every = 0;  // 0: no frame dropped
    bool headless_frame_loop = true;
    std::int64_t monotonic_origin_ns = 0;  // CLOCK_MONOTONIC at kSceneStart

    static DisplayClock from_environment();
    // The display time of the `waited`-th waited frame (from 0). The first is on time:
    // slot n is shown at kSceneStart + (n + 1) * period_ns, then moved by its jitter.
    XrTime display_time(std::int64_t waited) const;
    // The frame slot (from 1) nearest a display time, dropped slots counted.
    std::int64_t frame_slot(XrTime display_time) const;
    // The XrTime of a CLOCK_MONOTONIC time in nanoseconds, and back.
    XrTime from_monotonic(std::int64_t ns) const { return kSceneStart + ns - monotonic_origin_ns; }
    std::int64_t to_monotonic(XrTime time) const {
        return time - kSceneStart + monotonic_origin_ns;
    }
};

// ---- handles ----------------------------------------------------------------------------

// One counter for every handle type: a value is never reused, so a destroyed handle stays
// invalid and handles of different types never collide.
inline std::uint64_t new_handle_value() {
    static std::uint64_t last = 0;
    return ++last;
}

template <typename Handle>
std::uint64_t handle_value(Handle handle) {
    return reinterpret_cast<std::uintptr_t>(handle);
}

// The live objects of one handle type.
template <typename Handle, typename Object>
class Registry {
  public:
    Handle add(Object object) {
        std::uint64_t value = new_handle_value();
        objects_.emplace(value, std::move(object));
        return reinterpret_cast<Handle>(static_cast<std::uintptr_t>(value));
    }
    // nullptr for XR_NULL_HANDLE, destroyed and never-created handles.
    Object* find(Handle handle) {
        auto it = objects_.find(handle_value(handle));
        return it == objects_.end() ? nullptr : &it->second;
    }
    void erase(Handle handle) { objects_.erase(handle_value(handle)); }
    // Removes every object for which pred(handle, object) holds (children of a parent).
    template <typename Pred>
    void erase_if(Pred pred) {
        std::erase_if(objects_, [&](const auto& entry) {
            return pred(reinterpret_cast<Handle>(static_cast<std::uintptr_t>(entry.first)),
                        entry.second);
        });
    }
    template <typename Fn>
    void for_each(Fn fn) {
        for (auto& [value, object] : objects_) {
            fn(reinterpret_cast<Handle>(static_cast<std::uintptr_t>(value)), object);
        }
    }

  private:
    std::map<std::uint64_t, Object> objects_;
};

// ---- objects ----------------------------------------------------------------------------

// What the runtime plays of the scene named by PHYSHAND_SIM_SCENE.
struct PlayedScene {
    explicit PlayedScene(const Scene& scene) : duration_s(scene.duration_s), hands(scene) {}
    double duration_s;
    TrackedHands hands;
};

struct StateChange {
    XrSession session;
    XrSessionState state;
    XrTime time;
};

// What XR_KHR_vulkan_enable(2) told the application, for xrCreateSession to check.
struct VulkanSystem {
    bool requirements_queried = false;     // xrGetVulkanGraphicsRequirements(2)KHR was called
    VkInstance instance = VK_NULL_HANDLE;  // of the latest xrGetVulkanGraphicsDevice(2)KHR
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;  // what that call answered
};

// An 8-bit sRGB-encoded RGBA image, rows top to bottom: one composited view.
struct Rgba8Image {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint8_t> pixels;
};

// PHYSHAND_SIM_CAPTURE=DIR: composited frames are written there (sim_capture.cpp).
struct CaptureSettings {
    std::filesystem::path dir;
    std::int64_t every;  // write frames whose number is a multiple of this, and the last
    // PHYSHAND_SIM_CONTACT_SHEET=FILE: the captured frames of view 0 of a session, a few
    // evenly spaced, tiled into one PNG when the session is destroyed. Empty: none.
    std::filesystem::path contact_sheet;
};

struct InstanceData {
    bool hand_tracking = false;     // XR_EXT_hand_tracking enabled
    bool headless = false;          // XR_MND_headless enabled
    bool vulkan_enable = false;     // XR_KHR_vulkan_enable enabled
    bool vulkan_enable2 = false;    // XR_KHR_vulkan_enable2 enabled
    bool convert_timespec = false;  // XR_KHR_convert_timespec_time enabled
    bool forearm = false;           // XR_ULTRALEAP_hand_tracking_forearm enabled
    bool hand_aim = false;          // XR_FB_hand_tracking_aim enabled
    VulkanSystem vulkan;
    std::optional<CaptureSettings> capture;
    // Empty when there is no usable scene: hands are never active and sessions never end on
    // their own.
    std::optional<PlayedScene> scene;
    // PHYSHAND_SIM_END_AFTER_FRAME=N: sessions begin to stop after display frame N, as at
    // the scene's end, so a test that looks at one frame renders no more than it needs.
    std::optional<std::int64_t> end_after_frame;
    std::deque<StateChange> events;  // delivered by xrPollEvent, oldest first
    DisplayClock display = DisplayClock::from_environment();
    std::int64_t frames_waited = 0;  // frames waited on `display`
    std::vector<std::string> paths;  // XrPath n names paths[n - 1]
    std::map<std::string, XrPath, std::less<>> path_ids;
};

struct SessionData {
    XrInstance instance;
    // The state the application has been told about (changes when polled) and the state
    // after every change still queued; transitions are planned from the latter.
    XrSessionState state = XR_SESSION_STATE_IDLE;
    XrSessionState queued_state = XR_SESSION_STATE_IDLE;
    bool running = false;                   // between xrBeginSession and xrEndSession
    bool stop_queued = false;               // the path down to STOPPING is queued
    bool frame_waited = false;              // an xrWaitFrame not yet followed by xrBeginFrame
    bool frame_begun = false;               // an xrBeginFrame not yet followed by xrEndFrame
    bool actions_attached = false;          // xrAttachSessionActionSets succeeded (once only)
    bool last_frame_captured = false;       // the frame ended after the stop was queued
    std::vector<Rgba8Image> sheet_tiles{};  // view 0 of each captured frame, shrunk
    std::unique_ptr<VulkanSession> vulkan;  // null for a headless session
};

struct SwapchainData {
    XrSession session;
    VkFormat format;
    std::uint32_t width;
    std::uint32_t height;
    std::uint32_t array_size;
    bool is_static;  // XR_SWAPCHAIN_CREATE_STATIC_IMAGE_BIT: one image, acquired once
    // Where the images are between xrWaitSwapchainImage and the next acquire, as
    // XR_KHR_vulkan_enable promises: the attachment-optimal layout of their aspect.
    VkImageLayout layout;
    VkImageAspectFlags aspect;
    std::unique_ptr<SwapchainImages> images;
    bool layouts_set = false;                 // images out of UNDEFINED (at the first acquire)
    std::uint32_t next = 0;                   // the image the next acquire hands out
    std::deque<std::uint32_t> acquired{};     // acquired and not yet released, oldest first
    bool waited = false;                      // acquired.front() has been waited for
    std::optional<std::uint32_t> released{};  // the latest released image: what layers show
};

struct SpaceData {
    XrSession session;
    // nullopt: an action space; no action is ever bound, so it never locates.
    std::optional<XrReferenceSpaceType> reference;
    Pose pose_in_reference;
};

struct ActionSetData {
    XrInstance instance;
    std::string name;
    std::vector<XrSession> attached_to;  // sessions it was attached to
};

struct ActionData {
    XrActionSet action_set;
    std::string name;
    XrActionType type;
};

struct HandTrackerData {
    XrSession session;
    HandSide side;
    uint32_t joint_count = XR_HAND_JOINT_COUNT_EXT;  // of its joint set
};

struct Runtime {
    std::mutex mutex;
    Registry<XrInstance, InstanceData> instances;
    Registry<XrSession, SessionData> sessions;
    Registry<XrSpace, SpaceData> spaces;
    Registry<XrActionSet, ActionSetData> action_sets;
    Registry<XrAction, ActionData> actions;
    Registry<XrHandTrackerEXT, HandTrackerData> hand_trackers;
    Registry<XrSwapchain, SwapchainData> swapchains;

    // At unload, the Vulkan objects of what an application never destroyed are left alone:
    // their device, or the Vulkan loader, may be gone already.
    ~Runtime() {
        swapchains.for_each([](XrSwapchain, SwapchainData& swapchain) {
            static_cast<void>(swapchain.images.release());
        });
        sessions.for_each(
            [](XrSession, SessionData& session) { static_cast<void>(session.vulkan.release()); });
    }
};

inline Runtime& runtime() {
    static Runtime state;
    return state;
}

// Runs the body of an entry point with the runtime locked. No exception leaves the
// runtime: the loader and the application are C.
template <typename Body>
XrResult guarded(Body&& body) noexcept {
    try {
        Runtime& rt = runtime();
        std::lock_guard lock(rt.mutex);
        return body(rt);
    } catch (const std::bad_alloc&) {
        return XR_ERROR_OUT_OF_MEMORY;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "physhand simulated runtime: %s\n", e.what());
        return XR_ERROR_RUNTIME_FAILURE;
    } catch (...) {
        return XR_ERROR_RUNTIME_FAILURE;
    }
}

// ---- helpers shared between files ---------------------------------------------------------

// True for a non-null struct carrying the expected type tag.
template <typename T>
bool has_type(const T* s, XrStructureType type) {
    return s != nullptr && s->type == type;
}

// The first struct of the given type in an input or output `next` chain, or nullptr.
template <typename T>
T* find_in_chain(void* next, XrStructureType type) {
    for (auto* s = static_cast<XrBaseOutStructure*>(next); s != nullptr; s = s->next) {
        if (s->type == type) return reinterpret_cast<T*>(s);
    }
    return nullptr;
}
template <typename T>
const T* find_in_chain(const void* next, XrStructureType type) {
    for (auto* s = static_cast<const XrBaseInStructure*>(next); s != nullptr; s = s->next) {
        if (s->type == type) return reinterpret_cast<const T*>(s);
    }
    return nullptr;
}

// The two-call idiom: reports the count, and fills items[i] with write(items[i], i) when
// the caller's capacity suffices.
template <typename T, typename Write>
XrResult fill_array(std::uint32_t capacity, std::uint32_t* count_output, T* items,
                    std::uint32_t count, Write write) {
    if (count_output == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    *count_output = count;
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < count) return XR_ERROR_SIZE_INSUFFICIENT;
    if (items == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    for (std::uint32_t i = 0; i < count; ++i) {
        if (XrResult result = write(items[i], i); XR_FAILED(result)) return result;
    }
    return XR_SUCCESS;
}

// The characters allowed in path components and in action and action set names.
inline bool is_name_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
}

// Copies a string into one of the fixed-size char arrays of the OpenXR structs.
template <std::size_t N>
void copy_string(char (&out)[N], std::string_view text) {
    std::size_t n = std::min(text.size(), N - 1);
    std::memcpy(out, text.data(), n);
    out[n] = '\0';
}

inline XrVector3f to_xr(const Vec3& v) {
    return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}
inline XrPosef to_xr(const Pose& pose) {
    const Quat& q = pose.orientation;
    return {{static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()),
             static_cast<float>(q.w())},
            to_xr(pose.position)};
}
// Finite, with a unit quaternion up to the float rounding an application accumulates.
inline bool is_valid_pose(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    double norm =
        std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z + double(q.w) * q.w);
    return std::isfinite(p.position.x) && std::isfinite(p.position.y) &&
           std::isfinite(p.position.z) && std::abs(norm - 1.0) < 1e-2;
}
// Only for poses that passed is_valid_pose.
inline Pose from_xr(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    return {Vec3(p.position.x, p.position.y, p.position.z), Quat(q.w, q.x, q.y, q.z).normalized()};
}

// sim_instance.cpp
const char* structure_type_name(XrStructureType type);  // nullptr when unknown
// The environment variable `name` as a whole number of at least `min`; nullopt when it is
// unset or empty, and when it is anything else, which is reported on stderr as ignored.
std::optional<std::int64_t> whole_number_env(const char* name, std::int64_t min);
// The same for a decimal number from `min` to `max`.
std::optional<double> decimal_env(const char* name, double min, double max);
// sim_paths.cpp
bool path_exists(const InstanceData& instance, XrPath path);
// sim_session.cpp
void destroy_session(Runtime& rt, XrSession session);
// sim_spaces.cpp
// Pose of the space's origin in STAGE (the scene frame); nullopt if it does not locate.
std::optional<Pose> space_in_stage(const SpaceData& space);
Pose eye_in_stage(std::uint32_t view);  // view 0 is the left eye
XrFovf eye_fov();
// sim_actions.cpp
void destroy_action_set(Runtime& rt, XrActionSet action_set);
// sim_vulkan.cpp
// For xrCreateSession: the application's device from its binding, or why it cannot be used.
XrResult open_vulkan_session(const InstanceData& instance,
                             const XrGraphicsBindingVulkanKHR& binding,
                             std::unique_ptr<VulkanSession>* vulkan);
// sim_compositor.cpp
// The checks of xrEndFrame on its layers, their spaces and their swapchains; with
// PHYSHAND_SIM_REJECT_LAYERS_OVER=N, more than N layers are XR_ERROR_LAYER_LIMIT_EXCEEDED.
XrResult check_layers(Runtime& rt, XrSession session, const XrFrameEndInfo& info);
// The layers of a checked xrEndFrame composed in order over black, one image per view.
std::vector<Rgba8Image> compose_layers(Runtime& rt, XrSession session, const XrFrameEndInfo& info);
// sim_capture.cpp
// PHYSHAND_SIM_CAPTURE and PHYSHAND_SIM_CAPTURE_EVERY, read at instance creation.
std::optional<CaptureSettings> capture_settings();
// Writes the frame of a checked xrEndFrame as PNG when capture is on and its turn has come.
void capture_frame(Runtime& rt, XrSession session, const XrFrameEndInfo& info);
// Writes an image as PNG; failures are reported on stderr only.
void write_png(const std::filesystem::path& path, const Rgba8Image& image);
// sim_contact_sheet.cpp
// A composited view shrunk to a contact-sheet tile.
Rgba8Image sheet_tile(const Rgba8Image& view);
// Up to six of the tiles, evenly spaced from the first to the last, side by side in rows.
Rgba8Image contact_sheet(const std::vector<Rgba8Image>& tiles);

// ---- entry points, one file per concern --------------------------------------------------

#define PHYSHAND_SIM_API XRAPI_ATTR XrResult XRAPI_CALL

// sim_runtime_negotiation.cpp
PHYSHAND_SIM_API xrGetInstanceProcAddr(XrInstance instance, const char* name,
                                       PFN_xrVoidFunction* function);

// sim_instance.cpp
PHYSHAND_SIM_API xrEnumerateInstanceExtensionProperties(const char* layerName,
                                                        uint32_t propertyCapacityInput,
                                                        uint32_t* propertyCountOutput,
                                                        XrExtensionProperties* properties);
PHYSHAND_SIM_API xrCreateInstance(const XrInstanceCreateInfo* createInfo, XrInstance* instance);
PHYSHAND_SIM_API xrDestroyInstance(XrInstance instance);
PHYSHAND_SIM_API xrGetInstanceProperties(XrInstance instance,
                                         XrInstanceProperties* instanceProperties);
PHYSHAND_SIM_API xrPollEvent(XrInstance instance, XrEventDataBuffer* eventData);
PHYSHAND_SIM_API xrResultToString(XrInstance instance, XrResult value,
                                  char buffer[XR_MAX_RESULT_STRING_SIZE]);
PHYSHAND_SIM_API xrStructureTypeToString(XrInstance instance, XrStructureType value,
                                         char buffer[XR_MAX_STRUCTURE_NAME_SIZE]);

// sim_system.cpp
PHYSHAND_SIM_API xrGetSystem(XrInstance instance, const XrSystemGetInfo* getInfo,
                             XrSystemId* systemId);
PHYSHAND_SIM_API xrGetSystemProperties(XrInstance instance, XrSystemId systemId,
                                       XrSystemProperties* properties);
PHYSHAND_SIM_API xrEnumerateViewConfigurations(XrInstance instance, XrSystemId systemId,
                                               uint32_t viewConfigurationTypeCapacityInput,
                                               uint32_t* viewConfigurationTypeCountOutput,
                                               XrViewConfigurationType* viewConfigurationTypes);
PHYSHAND_SIM_API xrGetViewConfigurationProperties(
    XrInstance instance, XrSystemId systemId, XrViewConfigurationType viewConfigurationType,
    XrViewConfigurationProperties* configurationProperties);
PHYSHAND_SIM_API xrEnumerateViewConfigurationViews(XrInstance instance, XrSystemId systemId,
                                                   XrViewConfigurationType viewConfigurationType,
                                                   uint32_t viewCapacityInput,
                                                   uint32_t* viewCountOutput,
                                                   XrViewConfigurationView* views);
PHYSHAND_SIM_API xrEnumerateEnvironmentBlendModes(XrInstance instance, XrSystemId systemId,
                                                  XrViewConfigurationType viewConfigurationType,
                                                  uint32_t environmentBlendModeCapacityInput,
                                                  uint32_t* environmentBlendModeCountOutput,
                                                  XrEnvironmentBlendMode* environmentBlendModes);

// sim_paths.cpp
PHYSHAND_SIM_API xrStringToPath(XrInstance instance, const char* pathString, XrPath* path);
PHYSHAND_SIM_API xrPathToString(XrInstance instance, XrPath path, uint32_t bufferCapacityInput,
                                uint32_t* bufferCountOutput, char* buffer);

// sim_session.cpp
PHYSHAND_SIM_API xrCreateSession(XrInstance instance, const XrSessionCreateInfo* createInfo,
                                 XrSession* session);
PHYSHAND_SIM_API xrDestroySession(XrSession session);
PHYSHAND_SIM_API xrBeginSession(XrSession session, const XrSessionBeginInfo* beginInfo);
PHYSHAND_SIM_API xrEndSession(XrSession session);
PHYSHAND_SIM_API xrRequestExitSession(XrSession session);
PHYSHAND_SIM_API xrWaitFrame(XrSession session, const XrFrameWaitInfo* frameWaitInfo,
                             XrFrameState* frameState);
PHYSHAND_SIM_API xrBeginFrame(XrSession session, const XrFrameBeginInfo* frameBeginInfo);
PHYSHAND_SIM_API xrEndFrame(XrSession session, const XrFrameEndInfo* frameEndInfo);
PHYSHAND_SIM_API xrConvertTimespecTimeToTimeKHR(XrInstance instance,
                                                const struct timespec* timespecTime, XrTime* time);
PHYSHAND_SIM_API xrConvertTimeToTimespecTimeKHR(XrInstance instance, XrTime time,
                                                struct timespec* timespecTime);

// sim_spaces.cpp
PHYSHAND_SIM_API xrEnumerateReferenceSpaces(XrSession session, uint32_t spaceCapacityInput,
                                            uint32_t* spaceCountOutput,
                                            XrReferenceSpaceType* spaces);
PHYSHAND_SIM_API xrCreateReferenceSpace(XrSession session,
                                        const XrReferenceSpaceCreateInfo* createInfo,
                                        XrSpace* space);
PHYSHAND_SIM_API xrGetReferenceSpaceBoundsRect(XrSession session,
                                               XrReferenceSpaceType referenceSpaceType,
                                               XrExtent2Df* bounds);
PHYSHAND_SIM_API xrLocateSpace(XrSpace space, XrSpace baseSpace, XrTime time,
                               XrSpaceLocation* location);
PHYSHAND_SIM_API xrDestroySpace(XrSpace space);
PHYSHAND_SIM_API xrLocateViews(XrSession session, const XrViewLocateInfo* viewLocateInfo,
                               XrViewState* viewState, uint32_t viewCapacityInput,
                               uint32_t* viewCountOutput, XrView* views);

// sim_actions.cpp
PHYSHAND_SIM_API xrCreateActionSet(XrInstance instance, const XrActionSetCreateInfo* createInfo,
                                   XrActionSet* actionSet);
PHYSHAND_SIM_API xrDestroyActionSet(XrActionSet actionSet);
PHYSHAND_SIM_API xrCreateAction(XrActionSet actionSet, const XrActionCreateInfo* createInfo,
                                XrAction* action);
PHYSHAND_SIM_API xrDestroyAction(XrAction action);
PHYSHAND_SIM_API xrSuggestInteractionProfileBindings(
    XrInstance instance, const XrInteractionProfileSuggestedBinding* suggestedBindings);
PHYSHAND_SIM_API xrAttachSessionActionSets(XrSession session,
                                           const XrSessionActionSetsAttachInfo* attachInfo);
PHYSHAND_SIM_API xrSyncActions(XrSession session, const XrActionsSyncInfo* syncInfo);
PHYSHAND_SIM_API xrGetActionStateBoolean(XrSession session, const XrActionStateGetInfo* getInfo,
                                         XrActionStateBoolean* state);
PHYSHAND_SIM_API xrGetActionStateFloat(XrSession session, const XrActionStateGetInfo* getInfo,
                                       XrActionStateFloat* state);
PHYSHAND_SIM_API xrGetActionStateVector2f(XrSession session, const XrActionStateGetInfo* getInfo,
                                          XrActionStateVector2f* state);
PHYSHAND_SIM_API xrGetActionStatePose(XrSession session, const XrActionStateGetInfo* getInfo,
                                      XrActionStatePose* state);
PHYSHAND_SIM_API xrCreateActionSpace(XrSession session, const XrActionSpaceCreateInfo* createInfo,
                                     XrSpace* space);
PHYSHAND_SIM_API xrGetCurrentInteractionProfile(XrSession session, XrPath topLevelUserPath,
                                                XrInteractionProfileState* interactionProfile);
PHYSHAND_SIM_API xrEnumerateBoundSourcesForAction(
    XrSession session, const XrBoundSourcesForActionEnumerateInfo* enumerateInfo,
    uint32_t sourceCapacityInput, uint32_t* sourceCountOutput, XrPath* sources);
PHYSHAND_SIM_API xrGetInputSourceLocalizedName(XrSession session,
                                               const XrInputSourceLocalizedNameGetInfo* getInfo,
                                               uint32_t bufferCapacityInput,
                                               uint32_t* bufferCountOutput, char* buffer);
PHYSHAND_SIM_API xrApplyHapticFeedback(XrSession session,
                                       const XrHapticActionInfo* hapticActionInfo,
                                       const XrHapticBaseHeader* hapticFeedback);
PHYSHAND_SIM_API xrStopHapticFeedback(XrSession session,
                                      const XrHapticActionInfo* hapticActionInfo);

// sim_hand_tracking.cpp
PHYSHAND_SIM_API xrCreateHandTrackerEXT(XrSession session,
                                        const XrHandTrackerCreateInfoEXT* createInfo,
                                        XrHandTrackerEXT* handTracker);
PHYSHAND_SIM_API xrDestroyHandTrackerEXT(XrHandTrackerEXT handTracker);
PHYSHAND_SIM_API xrLocateHandJointsEXT(XrHandTrackerEXT handTracker,
                                       const XrHandJointsLocateInfoEXT* locateInfo,
                                       XrHandJointLocationsEXT* locations);

// sim_vulkan.cpp: XR_KHR_vulkan_enable2
PHYSHAND_SIM_API xrGetVulkanGraphicsRequirements2KHR(
    XrInstance instance, XrSystemId systemId,
    XrGraphicsRequirementsVulkanKHR* graphicsRequirements);
PHYSHAND_SIM_API xrCreateVulkanInstanceKHR(XrInstance instance,
                                           const XrVulkanInstanceCreateInfoKHR* createInfo,
                                           VkInstance* vulkanInstance, VkResult* vulkanResult);
PHYSHAND_SIM_API xrGetVulkanGraphicsDevice2KHR(XrInstance instance,
                                               const XrVulkanGraphicsDeviceGetInfoKHR* getInfo,
                                               VkPhysicalDevice* vulkanPhysicalDevice);
PHYSHAND_SIM_API xrCreateVulkanDeviceKHR(XrInstance instance,
                                         const XrVulkanDeviceCreateInfoKHR* createInfo,
                                         VkDevice* vulkanDevice, VkResult* vulkanResult);
// sim_vulkan.cpp: XR_KHR_vulkan_enable
PHYSHAND_SIM_API xrGetVulkanInstanceExtensionsKHR(XrInstance instance, XrSystemId systemId,
                                                  uint32_t bufferCapacityInput,
                                                  uint32_t* bufferCountOutput, char* buffer);
PHYSHAND_SIM_API xrGetVulkanDeviceExtensionsKHR(XrInstance instance, XrSystemId systemId,
                                                uint32_t bufferCapacityInput,
                                                uint32_t* bufferCountOutput, char* buffer);
PHYSHAND_SIM_API xrGetVulkanGraphicsDeviceKHR(XrInstance instance, XrSystemId systemId,
                                              VkInstance vkInstance,
                                              VkPhysicalDevice* vkPhysicalDevice);
PHYSHAND_SIM_API xrGetVulkanGraphicsRequirementsKHR(
    XrInstance instance, XrSystemId systemId,
    XrGraphicsRequirementsVulkanKHR* graphicsRequirements);

// sim_swapchain.cpp
PHYSHAND_SIM_API xrEnumerateSwapchainFormats(XrSession session, uint32_t formatCapacityInput,
                                             uint32_t* formatCountOutput, int64_t* formats);
PHYSHAND_SIM_API xrCreateSwapchain(XrSession session, const XrSwapchainCreateInfo* createInfo,
                                   XrSwapchain* swapchain);
PHYSHAND_SIM_API xrDestroySwapchain(XrSwapchain swapchain);
PHYSHAND_SIM_API xrEnumerateSwapchainImages(XrSwapchain swapchain, uint32_t imageCapacityInput,
                                            uint32_t* imageCountOutput,
                                            XrSwapchainImageBaseHeader* images);
PHYSHAND_SIM_API xrAcquireSwapchainImage(XrSwapchain swapchain,
                                         const XrSwapchainImageAcquireInfo* acquireInfo,
                                         uint32_t* index);
PHYSHAND_SIM_API xrWaitSwapchainImage(XrSwapchain swapchain,
                                      const XrSwapchainImageWaitInfo* waitInfo);
PHYSHAND_SIM_API xrReleaseSwapchainImage(XrSwapchain swapchain,
                                         const XrSwapchainImageReleaseInfo* releaseInfo);

}  // namespace physhand::sim
