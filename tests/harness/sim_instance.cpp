// Instances: extensions, creation (and reading the scene to play and the capture settings),
// properties, events, enum names.

#include <openxr/openxr_reflection.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

#include "sim_joint_sets.h"
#include "sim_runtime.h"

namespace physhand::sim {
namespace {

constexpr auto kExtensions = std::to_array<XrExtensionProperties>({
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, XR_EXT_HAND_TRACKING_EXTENSION_NAME,
     XR_EXT_hand_tracking_SPEC_VERSION},
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, XR_MND_HEADLESS_EXTENSION_NAME,
     XR_MND_headless_SPEC_VERSION},
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME,
     XR_KHR_vulkan_enable2_SPEC_VERSION},
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, XR_KHR_VULKAN_ENABLE_EXTENSION_NAME,
     XR_KHR_vulkan_enable_SPEC_VERSION},
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME,
     XR_KHR_convert_timespec_time_SPEC_VERSION},
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, "XR_ULTRALEAP_hand_tracking_forearm",
     1},  // kForearm...
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, XR_FB_HAND_TRACKING_AIM_EXTENSION_NAME,
     XR_FB_hand_tracking_aim_SPEC_VERSION},
    // The scene's hands hold no controller, so conforming to one changes nothing.
    {XR_TYPE_EXTENSION_PROPERTIES, nullptr, XR_EXT_HAND_JOINTS_MOTION_RANGE_EXTENSION_NAME,
     XR_EXT_hand_joints_motion_range_SPEC_VERSION},
});

constexpr const char* kRuntimeName = "physhand simulated runtime";

bool is_supported_extension(std::string_view name) {
    for (const XrExtensionProperties& extension : kExtensions) {
        if (name == extension.extensionName) return true;
    }
    return false;
}

// The scene is read once per instance; without one the runtime still works, the hands are
// simply never tracked, and the reason is printed once.
std::optional<PlayedScene> load_played_scene() {
    const char* path = std::getenv("PHYSHAND_SIM_SCENE");
    if (path == nullptr || *path == '\0') {
        std::fprintf(stderr,
                     "physhand simulated runtime: PHYSHAND_SIM_SCENE is not set; hands are "
                     "never tracked\n");
        return std::nullopt;
    }
    try {
        return std::optional<PlayedScene>(std::in_place, load_scene(path));
    } catch (const std::exception& e) {
        std::fprintf(stderr,
                     "physhand simulated runtime: cannot play scene %s (%s); hands are never "
                     "tracked\n",
                     path, e.what());
        return std::nullopt;
    }
}

#define PHYSHAND_SIM_NAME_CASE(name, number) \
    case name:                               \
        return #name;

const char* result_name(XrResult value) {
    switch (value) { XR_LIST_ENUM_XrResult(PHYSHAND_SIM_NAME_CASE) }
    return nullptr;
}

}  // namespace

const char* structure_type_name(XrStructureType type) {
    switch (type) { XR_LIST_ENUM_XrStructureType(PHYSHAND_SIM_NAME_CASE) }
    return nullptr;
}

#undef PHYSHAND_SIM_NAME_CASE

std::optional<std::int64_t> whole_number_env(const char* name, std::int64_t min) {
    const char* text = std::getenv(name);
    if (text == nullptr || *text == '\0') return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const long long n = std::strtoll(text, &end, 10);
    if (*end == '\0' && errno == 0 && n >= min) return n;
    std::fprintf(stderr,
                 "physhand simulated runtime: %s=%s is not a whole number of at least %lld; "
                 "ignored\n",
                 name, text, static_cast<long long>(min));
    return std::nullopt;
}

std::optional<double> decimal_env(const char* name, double min, double max) {
    const char* text = std::getenv(name);
    if (text == nullptr || *text == '\0') return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(text, &end);
    if (*end == '\0' && errno == 0 && x >= min && x <= max) return x;
    std::fprintf(stderr,
                 "physhand simulated runtime: %s=%s is not a number from %g to %g; ignored\n", name,
                 text, min, max);
    return std::nullopt;
}

XrResult xrEnumerateInstanceExtensionProperties(const char* layerName,
                                                uint32_t propertyCapacityInput,
                                                uint32_t* propertyCountOutput,
                                                XrExtensionProperties* properties) {
    return guarded([&](Runtime&) {
        if (layerName != nullptr) return XR_ERROR_API_LAYER_NOT_PRESENT;
        return fill_array(propertyCapacityInput, propertyCountOutput, properties,
                          static_cast<uint32_t>(kExtensions.size()),
                          [](XrExtensionProperties& out, uint32_t i) {
                              if (out.type != XR_TYPE_EXTENSION_PROPERTIES) {
                                  return XR_ERROR_VALIDATION_FAILURE;
                              }
                              copy_string(out.extensionName, kExtensions[i].extensionName);
                              out.extensionVersion = kExtensions[i].extensionVersion;
                              return XR_SUCCESS;
                          });
    });
}

XrResult xrCreateInstance(const XrInstanceCreateInfo* createInfo, XrInstance* instance) {
    return guarded([&](Runtime& rt) {
        if (!has_type(createInfo, XR_TYPE_INSTANCE_CREATE_INFO) || instance == nullptr ||
            (createInfo->enabledExtensionCount > 0 &&
             createInfo->enabledExtensionNames == nullptr)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const XrApplicationInfo& app = createInfo->applicationInfo;
        if (XR_VERSION_MAJOR(app.apiVersion) != 1) return XR_ERROR_API_VERSION_UNSUPPORTED;
        if (app.applicationName[0] == '\0') return XR_ERROR_NAME_INVALID;
        InstanceData data;
        for (uint32_t i = 0; i < createInfo->enabledExtensionCount; ++i) {
            const char* name = createInfo->enabledExtensionNames[i];
            if (name == nullptr) return XR_ERROR_VALIDATION_FAILURE;
            if (!is_supported_extension(name)) return XR_ERROR_EXTENSION_NOT_PRESENT;
            std::string_view extension = name;
            data.hand_tracking |= extension == XR_EXT_HAND_TRACKING_EXTENSION_NAME;
            data.headless |= extension == XR_MND_HEADLESS_EXTENSION_NAME;
            data.vulkan_enable |= extension == XR_KHR_VULKAN_ENABLE_EXTENSION_NAME;
            data.vulkan_enable2 |= extension == XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME;
            data.convert_timespec |= extension == XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME;
            data.forearm |= extension == kForearmExtensionName;
            data.hand_aim |= extension == XR_FB_HAND_TRACKING_AIM_EXTENSION_NAME;
        }
        data.scene = load_played_scene();
        data.capture = capture_settings();
        data.end_after_frame = whole_number_env("PHYSHAND_SIM_END_AFTER_FRAME", 1);
        *instance = rt.instances.add(std::move(data));
        return XR_SUCCESS;
    });
}

XrResult xrDestroyInstance(XrInstance instance) {
    return guarded([&](Runtime& rt) {
        if (rt.instances.find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
        std::vector<XrSession> sessions;
        rt.sessions.for_each([&](XrSession handle, const SessionData& session) {
            if (session.instance == instance) sessions.push_back(handle);
        });
        for (XrSession session : sessions) destroy_session(rt, session);
        std::vector<XrActionSet> action_sets;
        rt.action_sets.for_each([&](XrActionSet handle, const ActionSetData& set) {
            if (set.instance == instance) action_sets.push_back(handle);
        });
        for (XrActionSet set : action_sets) destroy_action_set(rt, set);
        rt.instances.erase(instance);
        return XR_SUCCESS;
    });
}

XrResult xrGetInstanceProperties(XrInstance instance, XrInstanceProperties* instanceProperties) {
    return guarded([&](Runtime& rt) {
        if (rt.instances.find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(instanceProperties, XR_TYPE_INSTANCE_PROPERTIES)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        instanceProperties->runtimeVersion =
            XR_MAKE_VERSION(PHYSHAND_VERSION_MAJOR, PHYSHAND_VERSION_MINOR, PHYSHAND_VERSION_PATCH);
        copy_string(instanceProperties->runtimeName, kRuntimeName);
        return XR_SUCCESS;
    });
}

XrResult xrPollEvent(XrInstance instance, XrEventDataBuffer* eventData) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(eventData, XR_TYPE_EVENT_DATA_BUFFER)) return XR_ERROR_VALIDATION_FAILURE;
        if (data->events.empty()) return XR_EVENT_UNAVAILABLE;
        StateChange change = data->events.front();
        data->events.pop_front();
        // The session enters the state when the application hears of it; destroying a
        // session drops its queued changes, so it is still alive here.
        rt.sessions.find(change.session)->state = change.state;
        auto* out = reinterpret_cast<XrEventDataSessionStateChanged*>(eventData);
        *out = {XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED, nullptr, change.session, change.state,
                change.time};
        return XR_SUCCESS;
    });
}

XrResult xrResultToString(XrInstance instance, XrResult value,
                          char buffer[XR_MAX_RESULT_STRING_SIZE]) {
    return guarded([&](Runtime& rt) {
        if (rt.instances.find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
        if (const char* name = result_name(value)) {
            std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "%s", name);
        } else {
            std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_UNKNOWN_%s_%d",
                          XR_SUCCEEDED(value) ? "SUCCESS" : "FAILURE", static_cast<int>(value));
        }
        return XR_SUCCESS;
    });
}

XrResult xrStructureTypeToString(XrInstance instance, XrStructureType value,
                                 char buffer[XR_MAX_STRUCTURE_NAME_SIZE]) {
    return guarded([&](Runtime& rt) {
        if (rt.instances.find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
        if (const char* name = structure_type_name(value)) {
            std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "%s", name);
        } else {
            std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "XR_UNKNOWN_STRUCTURE_TYPE_%d",
                          static_cast<int>(value));
        }
        return XR_SUCCESS;
    });
}

}  // namespace physhand::sim
