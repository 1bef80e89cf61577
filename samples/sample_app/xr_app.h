#pragma once

#include <openxr/openxr.h>

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "contact_announcer.h"
#include "drive.h"
#include "hand_trackers.h"
#include "run_observer.h"
#include "runtime_clock.h"
#include "scene.h"
#include "scene_colliders.h"
#include "scene_drawing.h"
#include "scene_graphics.h"
#include "scene_run.h"
#include "stdin_commands.h"
#include "touch_log.h"
#include "vulkan_device.h"
#include "xr_handle.h"

namespace physhand::sample {

struct AppOptions {
    bool rendered = true;  // false: XR_MND_headless, nothing drawn
    // Scenes do not end on their own, and stdin lines reset or switch them (stdin_commands.h):
    // for a headset. Otherwise each scene plays for its duration and the app asks to exit.
    bool live = false;
    DrawSettings drawing;
    // Set through the extension for the whole session, and reported with each result.
    DriveSettings drive = default_drive();
    std::optional<std::uint32_t> view_width;  // pixels; the runtime's recommendation if unset
    // Where the line of each touch that begins goes (stdout, or stderr beside JSON results).
    std::ostream* touch_lines = &std::cout;
};

// What playing one scene gave.
struct ScenePlayed {
    RunResult result;
    // Rendered mode only: {"frame_ms_median", "touches" (TouchLog)}; null when headless.
    nlohmann::json rendering;
    UserCommand next = UserCommand::Quit;  // what ended it; Quit when the session did
};

// An OpenXR app that plays scenes through the loader, the physhand layer and the runtime:
// it declares a scene's colliders, moves the kinematic ones along their paths and reads
// back the physical hands and colliders every frame, and in the rendered mode draws them.
class XrApp {
  public:
    // Creates the instance (XR_EXT_hand_tracking, XR_PHYSHAND_physical_hands, and
    // XR_KHR_vulkan_enable2 or XR_MND_headless), the Vulkan device when rendered, the
    // session with the options' hand drive, a STAGE space and both hand trackers. Throws
    // XrCallError for a failed call, std::runtime_error when an extension is missing.
    explicit XrApp(const AppOptions& options);

    // Runs the frame loop until the scene has played, the runtime ends the session, or (live)
    // the user asks for something else.
    ScenePlayed play(const Scene& scene);

  private:
    // Handles every queued event; false once the session is over.
    bool poll_events();
    // Begins the waited frame; false for a headless session without a frame loop, which
    // gives no display time or refuses to begin (Monado's XR_MND_headless).
    bool begin_frame(const XrFrameState& state);
    // Without a frame loop the app paces itself at 90 Hz and reads the runtime's clock.
    XrTime unlooped_frame_time();
    // Draws (when rendered) and ends a begun frame.
    void end_frame(const XrFrameState& state, bool playing, int frame, TouchLog& touches);
    // The frame of `scene` at scene time `t`, displayed at `time`.
    void play_frame(const Scene& scene, XrTime time, double t, RunObserver& observer);

    AppOptions options_;
    // Declared parents first: members are destroyed in reverse order.
    XrHandle<XrInstance> instance_;
    std::optional<VulkanDevice> vulkan_;  // outlives the session bound to it
    XrHandle<XrSession> session_;
    XrHandle<XrSpace> stage_;
    std::optional<SceneGraphics> graphics_;               // rendered mode
    std::optional<HandTrackers> trackers_;                // made once the session exists
    std::optional<RuntimeClock> clock_;                   // for sessions without a frame loop
    std::chrono::steady_clock::time_point next_frame_{};  // paces frames without a frame loop
    ColliderFunctions collider_functions_;
    std::optional<SceneColliders> colliders_;    // declared at a scene's first frame
    std::optional<ContactAnnouncer> announcer_;  // with the colliders
    double scene_t_ = 0.0;                       // scene time of the latest frame played
    std::array<LocatedHand, 2> hands_;           // as located at the latest frame played
    bool running_ = false;                       // between xrBeginSession and xrEndSession
    bool exit_requested_ = false;
};

}  // namespace physhand::sample
