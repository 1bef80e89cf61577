#include "sim_app.h"

#include <openxr/physhand_physical_hands.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim_app_vulkan.h"

namespace physhand::test {

namespace {

constexpr const char* kDisableLayer = "DISABLE_XR_APILAYER_PHYSHAND_physical_hands";
// State changes a fresh headless session goes through before it is READY.
constexpr int kMaxEventsBeforeReady = 8;

// The loader reads its variables at xrCreateInstance, the layer its config and the runtime
// its scene then too, so each instance can be created with or without the layer.
void set_environment(const SimAppOptions& options) {
    setenv("XR_RUNTIME_JSON", PHYSHAND_SIM_RUNTIME_JSON, 1);
    setenv("XDG_DATA_HOME", PHYSHAND_SIM_APP_DATA_HOME, 1);  // the build tree's layer manifests
    unsetenv("XR_ENABLE_API_LAYERS");
    // The user's own layer config (which may turn it off) must not change what is tested.
    setenv("XDG_CONFIG_HOME", PHYSHAND_SIM_APP_CONFIG_HOME, 1);
    if (options.config.empty()) {
        unsetenv("PHYSHAND_CONFIG");
    } else {
        setenv("PHYSHAND_CONFIG", options.config.c_str(), 1);
    }
    if (options.layer) {
        unsetenv(kDisableLayer);
    } else {
        setenv(kDisableLayer, "1", 1);
    }
    setenv("PHYSHAND_SIM_SCENE", options.scene.c_str(), 1);
}

XrSessionState next_state(XrInstance instance) {
    auto event = xr<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
    check(xrPollEvent(instance, &event), "xrPollEvent");
    if (event.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) return XR_SESSION_STATE_UNKNOWN;
    return reinterpret_cast<const XrEventDataSessionStateChanged&>(event).state;
}

}  // namespace

void check(XrResult result, const char* call) {
    if (XR_FAILED(result)) {
        throw std::runtime_error(std::string(call) + " failed with XrResult " +
                                 std::to_string(result));
    }
}

SimApp::Instance::~Instance() {
    if (handle != XR_NULL_HANDLE) xrDestroyInstance(handle);
}

SimApp::SimApp(const SimAppOptions& options) {
    set_environment(options);
    std::vector<const char*> extensions = {
        XR_EXT_HAND_TRACKING_EXTENSION_NAME,
        options.vulkan ? XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME : XR_MND_HEADLESS_EXTENSION_NAME};
    if (options.extension) extensions.push_back(XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME);
    auto instance_info = xr<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
    std::strcpy(instance_info.applicationInfo.applicationName, "physhand sim app");
    instance_info.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
    instance_info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    instance_info.enabledExtensionNames = extensions.data();
    check(xrCreateInstance(&instance_info, &instance_.handle), "xrCreateInstance");

    auto system_info = xr<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    XrSystemId system = XR_NULL_SYSTEM_ID;
    check(xrGetSystem(instance(), &system_info, &system), "xrGetSystem");
    auto session_info = xr<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    session_info.systemId = system;  // headless: no graphics binding
    if (options.vulkan) {
        vulkan_ = std::make_unique<AppVulkan>(instance(), system);
        session_info.next = &vulkan_->binding();
    }
    check(xrCreateSession(instance(), &session_info, &session_), "xrCreateSession");

    int events = 0;
    while (next_state(instance()) != XR_SESSION_STATE_READY) {
        if (++events == kMaxEventsBeforeReady) {
            throw std::runtime_error("the session did not become READY");
        }
    }
    auto begin_info = xr<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
    begin_info.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    check(xrBeginSession(session_, &begin_info), "xrBeginSession");

    for (const XrReferenceSpaceType type :
         {XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL,
          XR_REFERENCE_SPACE_TYPE_STAGE}) {
        auto space_info = xr<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
        space_info.referenceSpaceType = type;
        space_info.poseInReferenceSpace.orientation.w = 1.0f;
        check(xrCreateReferenceSpace(session_, &space_info, &spaces_[type - 1]),
              "xrCreateReferenceSpace");
    }

    if (vulkan_) {
        // The views, which the head never moves, where the runtime has them at a frame.
        vulkan_->start(session_, space(XR_REFERENCE_SPACE_TYPE_LOCAL),
                       frame().predictedDisplayTime);
    }

    const auto create_tracker = function<PFN_xrCreateHandTrackerEXT>("xrCreateHandTrackerEXT");
    for (const XrHandEXT hand : {XR_HAND_LEFT_EXT, XR_HAND_RIGHT_EXT}) {
        auto tracker_info = xr<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
        tracker_info.hand = hand;
        tracker_info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
        check(create_tracker(session_, &tracker_info, &hand_trackers_[hand - 1]),
              "xrCreateHandTrackerEXT");
    }
}

SimApp::~SimApp() = default;

XrSpace SimApp::space(XrReferenceSpaceType type) const {
    return spaces_.at(type - 1);
}

XrHandTrackerEXT SimApp::hand_tracker(XrHandEXT hand) const {
    return hand_trackers_.at(hand - 1);
}

XrFrameState SimApp::frame() const {
    auto wait_info = xr<XrFrameWaitInfo>(XR_TYPE_FRAME_WAIT_INFO);
    auto state = xr<XrFrameState>(XR_TYPE_FRAME_STATE);
    check(xrWaitFrame(session_, &wait_info, &state), "xrWaitFrame");
    check(xrBeginFrame(session_, nullptr), "xrBeginFrame");
    auto end_info = xr<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
    end_info.displayTime = state.predictedDisplayTime;
    end_info.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
    const auto* layer = reinterpret_cast<const XrCompositionLayerBaseHeader*>(
        vulkan_ ? vulkan_->render() : nullptr);
    if (layer != nullptr) {
        end_info.layerCount = 1;
        end_info.layers = &layer;
    }
    check(xrEndFrame(session_, &end_info), "xrEndFrame");
    return state;
}

PFN_xrVoidFunction SimApp::void_function(const char* name) const {
    PFN_xrVoidFunction function = nullptr;
    check(xrGetInstanceProcAddr(instance(), name, &function), name);
    return function;
}

}  // namespace physhand::test
