#include "layer_fixture.h"

#include <openxr/openxr_platform.h>
#include <time.h>  // the timespec of XR_KHR_convert_timespec_time
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <type_traits>

#include "frame_clock.h"

namespace physhand::layer_test {

namespace {

namespace fs = std::filesystem;

// Build-tree paths (tests/layer/CMakeLists.txt).
const fs::path kBuildShare = PHYSHAND_BUILD_SHARE_DIR;
const fs::path kExplicitLayerDir = kBuildShare / "physhand/explicit";
const fs::path kSimulatedRuntime = kBuildShare / "openxr/1/runtimes/physhand_simulated.json";
// The folder of the core validation layer's manifest; empty when it is not installed.
const std::string kCoreValidationDir = PHYSHAND_CORE_VALIDATION_LAYER_DIR;

// The process's folder (scene, config and validation files), removed at exit.
const fs::path& process_dir() {
    static const fs::path dir =
        fs::temp_directory_path() / ("physhand_layer_tests_" + std::to_string(::getpid()));
    return dir;
}
fs::path validation_file() {
    return process_dir() / "core_validation.txt";
}

// Process-wide settings, made once before the first instance: core validation reads its
// settings when it is first loaded.
class LoaderEnvironment : public ::testing::Environment {
  public:
    void SetUp() override {
        fs::create_directories(process_dir());
        // Another runtime may be named by the caller; the simulated one otherwise.
        setenv("XR_RUNTIME_JSON", kSimulatedRuntime.c_str(), 0);
        unsetenv("XR_LOADER_DEBUG");
        // XR_EXT_debug_utils cannot carry core validation's messages here: with the
        // loader and core validation of OpenXR 1.0.20, a messenger chained to
        // XrInstanceCreateInfo silences them and one created later never receives them.
        // Its text output to a file is reliable, so each test reads that file.
        setenv("XR_CORE_VALIDATION_EXPORT_TYPE", "text", 1);
        setenv("XR_CORE_VALIDATION_FILE_NAME", validation_file().c_str(), 1);
        std::ofstream(validation_file(), std::ios::app).flush();
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(process_dir(), ignored);
    }
};

[[maybe_unused]] ::testing::Environment* const kLoaderEnvironment =
    ::testing::AddGlobalTestEnvironment(new LoaderEnvironment);

std::string file_name_of(const ::testing::TestInfo& info) {
    std::string name = std::string(info.test_suite_name()) + "." + info.name();
    std::replace_if(
        name.begin(), name.end(), [](char c) { return c == '/' || c == ' '; }, '_');
    return name;
}

bool contains(const std::vector<const char*>& names, const char* name) {
    return std::any_of(names.begin(), names.end(),
                       [&](const char* n) { return std::strcmp(n, name) == 0; });
}

// Output arrays start as all-ones bytes (NaN floats): a field nobody wrote shows.
template <typename T>
void poison(T& value) {
    std::memset(static_cast<void*>(&value), 0xFF, sizeof(value));
}

// A cube of 5 cm half extent, as a convex hull and as a closed triangle mesh.
constexpr std::array<XrVector3f, 8> kCubeVertices = {{{-0.05f, -0.05f, -0.05f},
                                                      {0.05f, -0.05f, -0.05f},
                                                      {0.05f, 0.05f, -0.05f},
                                                      {-0.05f, 0.05f, -0.05f},
                                                      {-0.05f, -0.05f, 0.05f},
                                                      {0.05f, -0.05f, 0.05f},
                                                      {0.05f, 0.05f, 0.05f},
                                                      {-0.05f, 0.05f, 0.05f}}};
constexpr std::array<std::uint32_t, 36> kCubeIndices = {
    0, 2, 1, 0, 3, 2,  // -Z
    4, 5, 6, 4, 6, 7,  // +Z
    0, 1, 5, 0, 5, 4,  // -Y
    3, 7, 6, 3, 6, 2,  // +Y
    0, 4, 7, 0, 7, 3,  // -X
    1, 2, 6, 1, 6, 5,  // +X
};

}  // namespace

// ---- small helpers -----------------------------------------------------------------------

bool same_bits(const XrPosef& a, const XrPosef& b) {
    return std::memcmp(&a, &b, sizeof(XrPosef)) == 0;
}
bool same_bits(const XrVector3f& a, const XrVector3f& b) {
    return std::memcmp(&a, &b, sizeof(XrVector3f)) == 0;
}
bool same_bits(const HandSample& a, const HandSample& b) {
    return a.is_active == b.is_active &&
           std::memcmp(a.joints.data(), b.joints.data(), sizeof(a.joints)) == 0 &&
           std::memcmp(a.velocities.data(), b.velocities.data(), sizeof(a.velocities)) == 0;
}
bool is_finite(const XrVector3f& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool is_finite(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    return is_finite(p.position) && std::isfinite(q.x) && std::isfinite(q.y) &&
           std::isfinite(q.z) && std::isfinite(q.w);
}
double unit_error(const XrQuaternionf& q) {
    return std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z +
                     double(q.w) * q.w) -
           1.0;
}
double distance(const XrVector3f& a, const XrVector3f& b) {
    const double dx = double(a.x) - b.x, dy = double(a.y) - b.y, dz = double(a.z) - b.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

void ScopedEnv::save(const std::string& name) {
    const char* old = std::getenv(name.c_str());
    saved_.emplace_back(name, old ? std::optional<std::string>(old) : std::nullopt);
}
void ScopedEnv::set(const std::string& name, const std::string& value) {
    save(name);
    setenv(name.c_str(), value.c_str(), 1);
}
void ScopedEnv::unset(const std::string& name) {
    save(name);
    unsetenv(name.c_str());
}
void ScopedEnv::restore() {
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
        if (it->second) {
            setenv(it->first.c_str(), it->second->c_str(), 1);
        } else {
            unsetenv(it->first.c_str());
        }
    }
    saved_.clear();
}

HandJoints::HandJoints()
    : locations(xr<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT)),
      velocities(xr<XrHandJointVelocitiesEXT>(XR_TYPE_HAND_JOINT_VELOCITIES_EXT)),
      physical(xr<XrHandJointsPhysicalStatePHYSHAND>(XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND)) {
}

bool HandJoints::any_contact() const {
    return std::any_of(in_contact.begin(), in_contact.end(), [](XrBool32 c) { return c; });
}

// ---- scenes ------------------------------------------------------------------------------

nlohmann::json keyframed_hand(const std::vector<WristKey>& keys, double curl) {
    nlohmann::json keyframes = nlohmann::json::array();
    for (const WristKey& key : keys) {
        nlohmann::json frame = {
            {"t", key.t}, {"wrist", {{"position", key.position}, {"orientation", {0, 0, 0, 1}}}}};
        if (keyframes.empty()) frame["curl"] = {curl, curl, curl, curl, curl};
        keyframes.push_back(frame);
    }
    return {{"keyframes", keyframes}, {"interpolation", "smooth"}};
}

nlohmann::json scene_with_hands(const nlohmann::json& hands, double duration_s) {
    return {{"format", "physhand-scene/1"},
            {"name", "layer_test"},
            {"description", "hands played by the simulated runtime for the layer's tests"},
            {"duration_s", duration_s},
            {"colliders", nlohmann::json::array()},
            {"hands", hands}};
}

nlohmann::json pressing_hand(double x) {
    return keyframed_hand({{0.0, {x, 0.86, -0.3}}, {kPressTime, {x, 0.716, -0.3}}}, 0.0);
}

double lowest_joint_over_desk(const std::array<XrHandJointLocationEXT, kJointCount>& joints) {
    double lowest = std::numeric_limits<double>::infinity();
    for (const XrHandJointLocationEXT& joint : joints) {
        const XrVector3f& p = joint.pose.position;
        if (std::abs(p.x - kDeskCenter.x) <= kDeskHalfExtents.x &&
            std::abs(p.z - kDeskCenter.z) <= kDeskHalfExtents.z) {
            lowest = std::min(lowest, double(p.y));
        }
    }
    return lowest;
}

nlohmann::json still_hands_scene() {
    return scene_with_hands({{"left", keyframed_hand({{0.0, {-0.2, 1.2, -0.3}}})},
                             {"right", keyframed_hand({{0.0, {0.2, 1.2, -0.3}}})}});
}

// ---- colliders ---------------------------------------------------------------------------

XrPhysicalColliderCreateInfoPHYSHAND collider_info(XrPhysicalColliderShapePHYSHAND shape,
                                                   XrPhysicalColliderMotionPHYSHAND motion,
                                                   XrSpace space, const XrPosef& pose,
                                                   XrTime time) {
    auto info =
        xr<XrPhysicalColliderCreateInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND);
    info.shape = shape;
    info.motion = motion;
    info.halfExtents = {0.05f, 0.05f, 0.05f};
    info.radius = 0.05f;
    info.halfHeight = 0.05f;
    if (shape == XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND ||
        shape == XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND) {
        info.vertexCount = static_cast<std::uint32_t>(kCubeVertices.size());
        info.vertices = kCubeVertices.data();
    }
    if (shape == XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND) {
        info.indexCount = static_cast<std::uint32_t>(kCubeIndices.size());
        info.indices = kCubeIndices.data();
    }
    info.planeNormal = {0.0f, 1.0f, 0.0f};
    info.planeOffset = 0.0f;
    info.mass = 0.5f;
    info.friction = 0.8f;
    info.restitution = 0.0f;
    info.space = space;
    info.pose = pose;
    info.time = time;
    return info;
}

const char* shape_name(XrPhysicalColliderShapePHYSHAND shape) {
    switch (shape) {
        case XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND:
            return "Box";
        case XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND:
            return "Sphere";
        case XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND:
            return "Capsule";
        case XR_PHYSICAL_COLLIDER_SHAPE_CYLINDER_PHYSHAND:
            return "Cylinder";
        case XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND:
            return "Convex";
        case XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND:
            return "Mesh";
        case XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND:
            return "Plane";
        default:
            return "Unknown";
    }
}

// ---- fixture: environment ----------------------------------------------------------------

std::vector<const char*> LayerTest::all_extensions() {
    return {XR_EXT_HAND_TRACKING_EXTENSION_NAME, XR_MND_HEADLESS_EXTENSION_NAME,
            XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME, XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME};
}

std::vector<const char*> LayerTest::without_physhand() {
    return {XR_EXT_HAND_TRACKING_EXTENSION_NAME, XR_MND_HEADLESS_EXTENSION_NAME,
            XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME};
}

void LayerTest::SetUp() {
    test_dir_ =
        process_dir() / file_name_of(*::testing::UnitTest::GetInstance()->current_test_info());
    fs::create_directories(test_dir_ / "empty");
    // Nothing of the machine's own may reach the test: no user config of the layer, no
    // layers installed on the system, no recording.
    env_.set("XDG_CONFIG_HOME", (test_dir_ / "empty").string());
    env_.set("XDG_CONFIG_DIRS", (test_dir_ / "empty").string());
    env_.set("XDG_DATA_DIRS", (test_dir_ / "empty").string());
    for (const char* name :
         {"PHYSHAND_CONFIG", "PHYSHAND_RECORD", "PHYSHAND_SIM_SCENE", "PHYSHAND_SIM_CAPTURE"}) {
        env_.unset(name);
    }
    use_layer(LayerMode::Implicit);
    take_validation_output();  // what earlier tests left is theirs
}

void LayerTest::TearDown() {
    if (session_ != XR_NULL_HANDLE) end_session();
    if (instance_ != XR_NULL_HANDLE) destroy_instance();
    const std::string output = take_validation_output();
    const bool complaint = output.find("VALID_ERROR") != std::string::npos ||
                           output.find("VALID_WARNING") != std::string::npos;
    EXPECT_FALSE(complaint) << "core validation reported:\n" << output;
    env_.restore();
    std::error_code ignored;
    fs::remove_all(test_dir_, ignored);
}

void LayerTest::use_layer(LayerMode mode, bool validation) {
    const std::string empty = (test_dir_ / "empty").string();
    std::string layer_path = validation ? kCoreValidationDir : "";
    std::string enabled = layer_path.empty() ? "" : kCoreValidationName;
    if (mode == LayerMode::Explicit) {
        env_.set("XDG_DATA_HOME", empty);
        layer_path = kExplicitLayerDir.string() + (layer_path.empty() ? "" : ":" + layer_path);
        // The first named is the nearest the app: core validation goes beneath the layer.
        enabled = std::string(kLayerName) + (enabled.empty() ? "" : ":" + enabled);
    } else {
        env_.set("XDG_DATA_HOME", kBuildShare.string());
    }
    env_.set("XR_API_LAYER_PATH", layer_path.empty() ? empty : layer_path);
    if (enabled.empty()) {
        env_.unset("XR_ENABLE_API_LAYERS");
    } else {
        env_.set("XR_ENABLE_API_LAYERS", enabled);
    }
    if (mode == LayerMode::Disabled) {
        env_.set(kDisableVariable, "1");
    } else {
        env_.unset(kDisableVariable);
    }
}

void LayerTest::use_scene(const nlohmann::json& scene) {
    const fs::path path = write_file("scene.json", scene.dump(2));
    env_.set("PHYSHAND_SIM_SCENE", path.string());
}

fs::path LayerTest::write_file(const std::string& name, const std::string& text) {
    const fs::path path = test_dir_ / name;
    std::ofstream(path) << text;
    return path;
}

// ---- fixture: core validation ------------------------------------------------------------

bool LayerTest::validation_available() {
    return !kCoreValidationDir.empty();
}

std::string LayerTest::take_validation_output() {
    std::ifstream file(validation_file(), std::ios::binary);
    if (!file) return {};
    file.seekg(0, std::ios::end);
    const auto size = static_cast<std::uintmax_t>(file.tellg());
    if (size < validation_offset_) validation_offset_ = 0;  // started over
    file.seekg(static_cast<std::streamoff>(validation_offset_));
    std::stringstream text;
    text << file.rdbuf();
    validation_offset_ = size;
    return text.str();
}

void LayerTest::expect_validation_messages(const std::vector<std::string>& texts) {
    const std::string output = take_validation_output();
    if (!validation_available()) return;
    for (const std::string& text : texts) {
        EXPECT_NE(output.find(text), std::string::npos)
            << "expected core validation to report " << text << "; it reported:\n"
            << output;
    }
}

// ---- fixture: instance and session -------------------------------------------------------

XrResult LayerTest::create_instance(const std::vector<const char*>& extensions,
                                    XrVersion api_version) {
    auto info = xr<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
    std::strcpy(info.applicationInfo.applicationName, "physhand_layer_tests");
    info.applicationInfo.applicationVersion = 1;
    info.applicationInfo.apiVersion = api_version;
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.enabledExtensionNames = extensions.data();
    const XrResult result = xrCreateInstance(&info, &instance_);
    if (XR_FAILED(result)) {
        instance_ = XR_NULL_HANDLE;
        return result;
    }
    physhand_enabled_ = contains(extensions, XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME);
    api_ = {};
    display_time_ = 0;
    if (physhand_enabled_) {
        // Quietly: a layer turned off by its config has none of them.
        const auto load = [&](auto& slot, const char* name) {
            PFN_xrVoidFunction fn = nullptr;
            if (XR_SUCCEEDED(xrGetInstanceProcAddr(instance_, name, &fn))) {
                slot = reinterpret_cast<std::remove_reference_t<decltype(slot)>>(fn);
            }
        };
        load(api_.create_collider, "xrCreatePhysicalColliderPHYSHAND");
        load(api_.destroy_collider, "xrDestroyPhysicalColliderPHYSHAND");
        load(api_.set_pose, "xrSetPhysicalColliderPosePHYSHAND");
        load(api_.locate_colliders, "xrLocatePhysicalCollidersPHYSHAND");
        load(api_.set_drive, "xrSetHandDrivePHYSHAND");
        load(api_.set_contact_reporting, "xrSetPhysicalContactReportingPHYSHAND");
        load(api_.get_contact_events, "xrGetPhysicalContactEventsPHYSHAND");
    }
    return result;
}

void LayerTest::destroy_instance() {
    EXPECT_EQ(xrDestroyInstance(instance_), XR_SUCCESS);
    instance_ = XR_NULL_HANDLE;
    session_ = XR_NULL_HANDLE;
    stage_ = local_ = XR_NULL_HANDLE;
    states_.clear();
}

XrSystemId LayerTest::system() {
    auto info = xr<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    XrSystemId id = XR_NULL_SYSTEM_ID;
    EXPECT_EQ(xrGetSystem(instance_, &info, &id), XR_SUCCESS);
    return id;
}

void LayerTest::poll_events() {
    for (;;) {
        auto event = xr<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        const XrResult result = xrPollEvent(instance_, &event);
        if (result != XR_SUCCESS) {
            EXPECT_EQ(result, XR_EVENT_UNAVAILABLE);
            return;
        }
        if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
            const auto& change = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
            states_[change.session] = change.state;
        }
    }
}

std::optional<XrSessionState> LayerTest::poll_until(XrSession session, XrSessionState state) {
    for (int i = 0; i < 16; ++i) {
        auto event = xr<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
        const XrResult result = xrPollEvent(instance_, &event);
        if (result != XR_SUCCESS) break;
        if (event.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) continue;
        const auto& change = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
        states_[change.session] = change.state;
        if (change.session == session && change.state == state) return state;
    }
    ADD_FAILURE() << "session never reached state " << state;
    return std::nullopt;
}

void LayerTest::start_session() {
    auto info = xr<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    info.systemId = system();
    ASSERT_EQ(xrCreateSession(instance_, &info, &session_), XR_SUCCESS);
    ASSERT_TRUE(poll_until(session_, XR_SESSION_STATE_READY));
    auto begin = xr<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
    begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    ASSERT_EQ(xrBeginSession(session_, &begin), XR_SUCCESS);
    ASSERT_TRUE(poll_until(session_, XR_SESSION_STATE_FOCUSED));
    stage_ = reference_space(session_, XR_REFERENCE_SPACE_TYPE_STAGE);
    local_ = reference_space(session_, XR_REFERENCE_SPACE_TYPE_LOCAL);
    // Until the first frame, extension calls use the first frame's time.
    display_time_ = 0;
    no_frame_loop_ = false;
    unlooped_frames_ = 0;
}

XrSession LayerTest::extra_session() {
    auto info = xr<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    info.systemId = system();
    XrSession session = XR_NULL_HANDLE;
    EXPECT_EQ(xrCreateSession(instance_, &info, &session), XR_SUCCESS);
    return session;
}

void LayerTest::end_session() {
    if (states_[session_] != XR_SESSION_STATE_STOPPING) {
        poll_events();
    }
    if (states_[session_] != XR_SESSION_STATE_STOPPING) {
        EXPECT_EQ(xrRequestExitSession(session_), XR_SUCCESS);
        EXPECT_TRUE(poll_until(session_, XR_SESSION_STATE_STOPPING));
    }
    EXPECT_EQ(xrEndSession(session_), XR_SUCCESS);
    EXPECT_TRUE(poll_until(session_, XR_SESSION_STATE_EXITING));
    destroy_session();
}

void LayerTest::destroy_session() {
    EXPECT_EQ(xrDestroySession(session_), XR_SUCCESS);
    states_.erase(session_);
    session_ = XR_NULL_HANDLE;
    stage_ = local_ = XR_NULL_HANDLE;
}

XrSpace LayerTest::reference_space(XrSession session, XrReferenceSpaceType type,
                                   const XrPosef& pose) {
    auto info = xr<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
    info.referenceSpaceType = type;
    info.poseInReferenceSpace = pose;
    XrSpace space = XR_NULL_HANDLE;
    EXPECT_EQ(xrCreateReferenceSpace(session, &info, &space), XR_SUCCESS);
    return space;
}

XrTime LayerTest::frame() {
    auto wait = xr<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
    auto state = xr<XrFrameState>(XR_TYPE_FRAME_STATE);
    if (!no_frame_loop_) {
        EXPECT_EQ(xrWaitFrame(session_, &wait, &state), XR_SUCCESS);
        no_frame_loop_ = state.predictedDisplayTime == 0;
    }
    if (no_frame_loop_) {
        poll_events();
        display_time_ = unlooped_frame_time();
        return display_time_;
    }
    auto begin = xr<XrFrameBeginInfo>(XR_TYPE_FRAME_BEGIN_INFO);
    EXPECT_EQ(xrBeginFrame(session_, &begin), XR_SUCCESS);
    auto end = xr<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    end.displayTime = state.predictedDisplayTime;
    end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    EXPECT_EQ(xrEndFrame(session_, &end), XR_SUCCESS);
    poll_events();
    display_time_ = state.predictedDisplayTime;
    return display_time_;
}

XrTime LayerTest::unlooped_frame_time() {
    const auto convert =
        function<PFN_xrConvertTimespecTimeToTimeKHR>("xrConvertTimespecTimeToTimeKHR");
    if (convert == nullptr) {
        ADD_FAILURE() << "no frame loop, and no XR_KHR_convert_timespec_time to tell the time";
        return display_time_;
    }
    if (unlooped_frames_ == 0) {
        timespec now{};
        clock_gettime(CLOCK_MONOTONIC, &now);
        unlooped_start_ns_ = now.tv_sec * 1'000'000'000LL + now.tv_nsec;
    }
    const std::int64_t ns = unlooped_start_ns_ + unlooped_frames_++ * kFramePeriodNs;
    const timespec at{static_cast<time_t>(ns / 1'000'000'000),
                      static_cast<long>(ns % 1'000'000'000)};
    XrTime time = 0;
    EXPECT_EQ(convert(instance_, &at, &time), XR_SUCCESS);
    return time;
}

XrTime LayerTest::frames(int count) {
    for (int i = 0; i < count; ++i) frame();
    return display_time_;
}

XrTime LayerTest::simulate_frames(int count) {
    std::vector<XrPhysicalColliderLocationPHYSHAND> none;
    for (int i = 0; i < count; ++i) {
        EXPECT_EQ(locate_colliders({}, stage_, frame(), none), XR_SUCCESS);
    }
    return display_time_;
}

// ---- fixture: hand tracking --------------------------------------------------------------

XrHandTrackerEXT LayerTest::hand_tracker(XrHandEXT hand, XrSession session) {
    auto info = xr<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
    info.hand = hand;
    info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
    XrHandTrackerEXT tracker = XR_NULL_HANDLE;
    EXPECT_EQ(function<PFN_xrCreateHandTrackerEXT>("xrCreateHandTrackerEXT")(
                  session == XR_NULL_HANDLE ? session_ : session, &info, &tracker),
              XR_SUCCESS);
    return tracker;
}

XrResult LayerTest::locate(XrHandTrackerEXT tracker, XrSpace base, XrTime time, HandJoints& out,
                           Chain chain) {
    auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
    info.baseSpace = base;
    info.time = time;
    poison(out.joints);
    poison(out.joint_velocities);
    poison(out.ghost);
    poison(out.in_contact);
    poison(out.spring_force);
    out.locations.isActive = 0xFFFF;
    out.locations.next = chain == Chain::None ? nullptr : &out.velocities;
    out.locations.jointCount = kJointCount;
    out.locations.jointLocations = out.joints.data();
    out.velocities.next = chain == Chain::Physical ? &out.physical : nullptr;
    out.velocities.jointCount = kJointCount;
    out.velocities.jointVelocities = out.joint_velocities.data();
    out.physical.next = nullptr;
    out.physical.jointCount = kJointCount;
    out.physical.ghostPoses = out.ghost.data();
    out.physical.inContact = out.in_contact.data();
    out.physical.springForce = out.spring_force.data();
    out.physical.ghostIsActive = 0xFFFF;
    out.physical.isSimulated = 0xFFFF;
    return function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")(tracker, &info,
                                                                        &out.locations);
}

void LayerTest::locate_ok(XrHandTrackerEXT tracker, XrTime time, HandJoints& out, Chain chain) {
    EXPECT_EQ(locate(tracker, stage_, time, out, chain), XR_SUCCESS);
}

HandSample LayerTest::sample(XrHandTrackerEXT tracker, XrTime time, Chain chain) {
    HandJoints out;
    locate_ok(tracker, time, out, chain);
    HandSample s;
    s.is_active = out.locations.isActive;
    s.joints = out.joints;
    if (chain != Chain::None) s.velocities = out.joint_velocities;
    return s;
}

// ---- fixture: the extension --------------------------------------------------------------

XrPhysicalColliderPHYSHAND LayerTest::create_collider(
    const XrPhysicalColliderCreateInfoPHYSHAND& info, XrSession session) {
    XrPhysicalColliderPHYSHAND collider = XR_NULL_HANDLE;
    EXPECT_EQ(
        api_.create_collider(session == XR_NULL_HANDLE ? session_ : session, &info, &collider),
        XR_SUCCESS)
        << shape_name(info.shape);
    EXPECT_NE(collider, XR_NULL_HANDLE);
    return collider;
}

XrPhysicalColliderPHYSHAND LayerTest::create_desk() {
    auto info = collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND, stage_,
                              {{0, 0, 0, 1}, kDeskCenter}, now() > 0 ? now() : 1);
    info.halfExtents = kDeskHalfExtents;
    info.friction = 0.6f;
    return create_collider(info);
}

void LayerTest::start_with_desk(const nlohmann::json& scene) {
    use_scene(scene);
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    start_session();
    frame();
    create_desk();
}

XrResult LayerTest::locate_colliders(const std::vector<XrPhysicalColliderPHYSHAND>& colliders,
                                     XrSpace base, XrTime time,
                                     std::vector<XrPhysicalColliderLocationPHYSHAND>& out,
                                     XrSession session) {
    auto info =
        xr<XrPhysicalCollidersLocateInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND);
    info.baseSpace = base;
    info.time = time;
    info.colliderCount = static_cast<std::uint32_t>(colliders.size());
    info.colliders = colliders.data();
    out.resize(colliders.size());
    for (auto& location : out) poison(location);
    auto locations =
        xr<XrPhysicalColliderLocationsPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND);
    locations.locationCount = static_cast<std::uint32_t>(out.size());
    locations.locations = out.data();
    return api_.locate_colliders(session == XR_NULL_HANDLE ? session_ : session, &info, &locations);
}

XrPhysicalColliderLocationPHYSHAND LayerTest::locate_collider(XrPhysicalColliderPHYSHAND collider,
                                                              XrTime time) {
    std::vector<XrPhysicalColliderLocationPHYSHAND> out;
    EXPECT_EQ(locate_colliders({collider}, stage_, time, out), XR_SUCCESS);
    return out.front();
}

XrResult LayerTest::set_drive(XrHandDriveKindPHYSHAND kind) {
    auto info = xr<XrHandDriveInfoPHYSHAND>(XR_TYPE_HAND_DRIVE_INFO_PHYSHAND);
    info.drive = kind;
    return api_.set_drive(session_, &info);
}

// ---- fixture: whole runs -----------------------------------------------------------------

LayerTest::RunResult LayerTest::record_run(LayerMode mode, int frame_count,
                                           const std::vector<const char*>& extensions) {
    RunResult run;
    use_layer(mode);
    const XrResult created = create_instance(extensions);
    EXPECT_EQ(created, XR_SUCCESS);
    if (XR_FAILED(created)) return run;
    start_session();
    if (session_ == XR_NULL_HANDLE || ::testing::Test::HasFatalFailure()) return run;
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrHandTrackerEXT left = hand_tracker(XR_HAND_LEFT_EXT);
    for (int f = 0; f < frame_count; ++f) {
        const XrTime time = frame();
        run.right.push_back(sample(right, time));
        run.left.push_back(sample(left, time));
    }
    end_session();
    destroy_instance();
    return run;
}

}  // namespace physhand::layer_test
