#pragma once

// The one fixture of the layer's conformance-style harness. A test is an OpenXR app: it
// goes through the real Khronos loader, which finds the physhand layer (implicit through
// XDG_DATA_HOME, or explicit through XR_API_LAYER_PATH) and the Khronos core validation
// layer beneath it, down to the runtime named by XR_RUNTIME_JSON (the simulated one unless
// the caller set another). Every test fails on a core validation error or warning it did
// not expect. Headless sessions without a frame loop (Monado's; the simulated runtime's with
// PHYSHAND_SIM_HEADLESS_FRAME_LOOP=0) get their frames' times from
// XR_KHR_convert_timespec_time instead, and call no frame functions.

#include <gtest/gtest.h>
#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace physhand::layer_test {

inline constexpr const char* kLayerName = "XR_APILAYER_PHYSHAND_physical_hands";
inline constexpr const char* kCoreValidationName = "XR_APILAYER_LUNARG_core_validation";
inline constexpr const char* kDisableVariable = "DISABLE_XR_APILAYER_PHYSHAND_physical_hands";
inline constexpr std::uint32_t kJointCount = XR_HAND_JOINT_COUNT_EXT;

// A zeroed OpenXR struct carrying its type tag (`XrFoo x{XR_TYPE_FOO}` trips
// -Wmissing-field-initializers).
template <typename T>
T xr(XrStructureType type) {
    T s{};
    s.type = type;
    return s;
}

// A handle value nothing ever handed out.
template <typename Handle>
Handle bogus_handle() {
    return reinterpret_cast<Handle>(std::uintptr_t{0xdead0000});
}

inline XrPosef pose_at(float x, float y, float z, XrQuaternionf q = {0, 0, 0, 1}) {
    return {q, {x, y, z}};
}
inline XrPosef identity_pose() {
    return pose_at(0, 0, 0);
}

// Equal bit for bit (NaN payloads and signed zeros included).
bool same_bits(const XrPosef& a, const XrPosef& b);
bool same_bits(const XrVector3f& a, const XrVector3f& b);
bool is_finite(const XrVector3f& v);
bool is_finite(const XrPosef& p);
// |q| - 1, in double.
double unit_error(const XrQuaternionf& q);
double distance(const XrVector3f& a, const XrVector3f& b);

// Environment variables changed for the lifetime of the object, restored after.
class ScopedEnv {
  public:
    ScopedEnv() = default;
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;
    ~ScopedEnv() { restore(); }

    void set(const std::string& name, const std::string& value);
    void unset(const std::string& name);
    void restore();

  private:
    void save(const std::string& name);
    std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

// How the loader finds the physhand layer.
enum class LayerMode {
    Implicit,  // its implicit manifest, through XDG_DATA_HOME=BUILD/share
    Explicit,  // its explicit manifest, through XR_API_LAYER_PATH and XR_ENABLE_API_LAYERS
    Disabled,  // implicit, turned off by DISABLE_XR_APILAYER_PHYSHAND_physical_hands=1
};

// The extension's functions, from xrGetInstanceProcAddr.
struct PhysicalHandsApi {
    PFN_xrCreatePhysicalColliderPHYSHAND create_collider = nullptr;
    PFN_xrDestroyPhysicalColliderPHYSHAND destroy_collider = nullptr;
    PFN_xrSetPhysicalColliderPosePHYSHAND set_pose = nullptr;
    PFN_xrLocatePhysicalCollidersPHYSHAND locate_colliders = nullptr;
    PFN_xrSetHandDrivePHYSHAND set_drive = nullptr;
    PFN_xrSetPhysicalContactReportingPHYSHAND set_contact_reporting = nullptr;
    PFN_xrGetPhysicalContactEventsPHYSHAND get_contact_events = nullptr;
};

// The output of xrLocateHandJointsEXT with velocities and the physical state chained;
// pinned, as it points into itself.
struct HandJoints {
    HandJoints();
    HandJoints(const HandJoints&) = delete;
    HandJoints& operator=(const HandJoints&) = delete;

    const XrPosef& pose(XrHandJointEXT joint) const { return joints[joint].pose; }
    const XrPosef& ghost_pose(XrHandJointEXT joint) const { return ghost[joint]; }
    bool any_contact() const;

    XrHandJointLocationsEXT locations;
    XrHandJointVelocitiesEXT velocities;
    XrHandJointsPhysicalStatePHYSHAND physical;
    std::array<XrHandJointLocationEXT, kJointCount> joints{};
    std::array<XrHandJointVelocityEXT, kJointCount> joint_velocities{};
    std::array<XrPosef, kJointCount> ghost{};
    std::array<XrBool32, kJointCount> in_contact{};
    std::array<float, kJointCount> spring_force{};
};

// What a test chains to XrHandJointLocationsEXT.
enum class Chain {
    None,
    Velocities,
    Physical,  // velocities and the extension's physical state (needs the extension)
};

// One frame's answer for one hand, copied out (for comparing runs).
struct HandSample {
    XrBool32 is_active = XR_FALSE;
    std::array<XrHandJointLocationEXT, kJointCount> joints{};
    std::array<XrHandJointVelocityEXT, kJointCount> velocities{};
};
bool same_bits(const HandSample& a, const HandSample& b);

// ---- scene files (docs/scene-format.md) -------------------------------------------------

struct WristKey {
    double t;
    std::array<double, 3> position;
};
// A keyframed hand, palm down (identity wrist orientation), fingers slightly curled.
nlohmann::json keyframed_hand(const std::vector<WristKey>& keys, double curl = 0.1);
// A scene with these hands ({"left": ..., "right": ...}) and no colliders: the colliders
// of a layer test are declared through the extension (or the layer's config).
nlohmann::json scene_with_hands(const nlohmann::json& hands, double duration_s = 60.0);

// The desk every pressing test uses, also as a config collider: top at y = 0.75 (STAGE).
inline constexpr float kDeskTop = 0.75f;
inline constexpr XrVector3f kDeskCenter = {0.0f, 0.725f, -0.4f};
inline constexpr XrVector3f kDeskHalfExtents = {0.4f, 0.025f, 0.3f};
// The right (left) wrist comes down from 11 cm above the desk top, out of the layer's
// reach, to 3.4 cm below it in 1 s, and stays there: the ghost palm ends inside the desk.
inline constexpr double kPressTime = 1.0;
nlohmann::json pressing_hand(double x);
// Allowed depth of a hand body inside a collider (docs/metrics.md, max_penetration_mm).
inline constexpr double kMaxPenetration = 0.005;
// No hand body is thinner than this (sphere or capsule radius, palm box half thickness:
// physics/physical_hand.cpp), whatever the drive; joint radii describe the tracked hand,
// not the bodies, so a joint centre this high above a surface is on it, not in it.
inline constexpr double kThinnestHandBody = 0.004;
// The lowest joint centre over the desk's footprint (+infinity if none is over it).
double lowest_joint_over_desk(const std::array<XrHandJointLocationEXT, kJointCount>& joints);
// Both hands held still, 45 cm above the desk and far from anything.
nlohmann::json still_hands_scene();

// ---- collider create infos ---------------------------------------------------------------

// A valid create info of each shape: 5 cm boxes, spheres, capsules and cylinders, a cube's
// convex hull and triangle mesh, the floor plane; dynamic ones weigh 0.5 kg.
XrPhysicalColliderCreateInfoPHYSHAND collider_info(XrPhysicalColliderShapePHYSHAND shape,
                                                   XrPhysicalColliderMotionPHYSHAND motion,
                                                   XrSpace space, const XrPosef& pose, XrTime time);
const char* shape_name(XrPhysicalColliderShapePHYSHAND shape);

// ---- the fixture -------------------------------------------------------------------------

class LayerTest : public ::testing::Test {
  protected:
    // The extensions of a typical app of this layer.
    static std::vector<const char*> all_extensions();
    static std::vector<const char*> without_physhand();

    void SetUp() override;
    void TearDown() override;

    // -- environment (each call replaces the previous choice; restored after the test) --
    // `validation`: core validation enabled beneath the layer (where installed).
    void use_layer(LayerMode mode, bool validation = true);
    // Writes the scene to the test's folder and names it in PHYSHAND_SIM_SCENE.
    void use_scene(const nlohmann::json& scene);
    // Writes a file to the test's folder; returns its path.
    std::filesystem::path write_file(const std::string& name, const std::string& text);
    const std::filesystem::path& test_dir() const { return test_dir_; }
    ScopedEnv env_;

    // -- core validation --
    static bool validation_available();
    // The core validation layer's output since the last call.
    std::string take_validation_output();
    // Expects each text (a VUID, say) in the output since the last check, and accepts
    // that output: the next check sees only what comes after.
    void expect_validation_messages(const std::vector<std::string>& texts);

    // -- instance --
    XrResult create_instance(const std::vector<const char*>& extensions = all_extensions(),
                             XrVersion api_version = XR_CURRENT_API_VERSION);
    void destroy_instance();
    XrSystemId system();
    bool physhand_enabled() const { return physhand_enabled_; }
    const PhysicalHandsApi& api() const { return api_; }
    template <typename Pfn>
    Pfn function(const char* name) {
        PFN_xrVoidFunction fn = nullptr;
        EXPECT_EQ(xrGetInstanceProcAddr(instance_, name, &fn), XR_SUCCESS) << name;
        return reinterpret_cast<Pfn>(fn);
    }

    // -- session: created, begun and FOCUSED, with STAGE and LOCAL spaces --
    void start_session();
    // Another session of the instance, created but not begun.
    XrSession extra_session();
    // Asks the runtime to exit, ends and destroys the session.
    void end_session();
    // Destroys the session as it is (running or not).
    void destroy_session();
    XrSpace reference_space(XrSession session, XrReferenceSpaceType type,
                            const XrPosef& pose = identity_pose());
    // One whole frame (wait, begin, end; events polled); its predicted display time. Without
    // a frame loop (xrWaitFrame gives no display time), the time 1/90 s after the last, by
    // the runtime's clock (the first: now), without waiting for it, as an app that paces
    // itself would predict it.
    XrTime frame();
    // The session has no frame loop: the frame functions are not called.
    bool no_frame_loop() const { return no_frame_loop_; }
    XrTime frames(int count);
    // Frames in which the app also reads the simulation back (an empty collider list), as
    // apps locate every frame: the layer simulates at most 0.1 s per call, so a long gap
    // between locates is time dropped, not simulated.
    XrTime simulate_frames(int count);
    XrTime now() const { return display_time_; }

    // -- hand tracking --
    XrHandTrackerEXT hand_tracker(XrHandEXT hand, XrSession session = XR_NULL_HANDLE);
    XrResult locate(XrHandTrackerEXT tracker, XrSpace base, XrTime time, HandJoints& out,
                    Chain chain = Chain::Physical);
    // Locates in STAGE at `time`, expecting success.
    void locate_ok(XrHandTrackerEXT tracker, XrTime time, HandJoints& out,
                   Chain chain = Chain::Physical);
    HandSample sample(XrHandTrackerEXT tracker, XrTime time, Chain chain = Chain::Velocities);

    // -- the extension --
    XrPhysicalColliderPHYSHAND create_collider(const XrPhysicalColliderCreateInfoPHYSHAND& info,
                                               XrSession session = XR_NULL_HANDLE);
    // A static desk (kDeskCenter, kDeskHalfExtents) in STAGE.
    XrPhysicalColliderPHYSHAND create_desk();
    // The runtime playing `scene`, an instance and a running session with one frame done,
    // and the desk declared.
    void start_with_desk(const nlohmann::json& scene);
    XrResult locate_colliders(const std::vector<XrPhysicalColliderPHYSHAND>& colliders,
                              XrSpace base, XrTime time,
                              std::vector<XrPhysicalColliderLocationPHYSHAND>& out,
                              XrSession session = XR_NULL_HANDLE);
    // One collider in STAGE at `time`, expecting success.
    XrPhysicalColliderLocationPHYSHAND locate_collider(XrPhysicalColliderPHYSHAND collider,
                                                       XrTime time);
    XrResult set_drive(XrHandDriveKindPHYSHAND kind);

    // -- whole runs --
    // One app from instance to exit, in `mode`, on the current scene: a right (and left)
    // tracker located in STAGE each frame. `extensions` as for create_instance.
    struct RunResult {
        std::vector<HandSample> right;
        std::vector<HandSample> left;
    };
    RunResult record_run(LayerMode mode, int frame_count,
                         const std::vector<const char*>& extensions = without_physhand());

    XrInstance instance_ = XR_NULL_HANDLE;
    XrSession session_ = XR_NULL_HANDLE;
    XrSpace stage_ = XR_NULL_HANDLE;
    XrSpace local_ = XR_NULL_HANDLE;

  private:
    std::optional<XrSessionState> poll_until(XrSession session, XrSessionState state);
    void poll_events();

    std::filesystem::path test_dir_;
    std::uintmax_t validation_offset_ = 0;
    bool physhand_enabled_ = false;
    PhysicalHandsApi api_;
    XrTime unlooped_frame_time();

    XrTime display_time_ = 0;
    bool no_frame_loop_ = false;
    std::int64_t unlooped_start_ns_ = 0;  // CLOCK_MONOTONIC at the session's first frame
    std::int64_t unlooped_frames_ = 0;
    std::map<XrSession, XrSessionState> states_;
};

}  // namespace physhand::layer_test
