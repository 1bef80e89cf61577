// Loader negotiation and the xrGetInstanceProcAddr table: the only way in.

#include <array>
#include <string_view>
#include <type_traits>

#include "loader_negotiation.h"
#include "sim_runtime.h"

namespace physhand::sim {
namespace {

// What a function needs: an instance, none, or an instance with its extension enabled.
enum class Needs {
    Instance,
    NoInstance,
    HandTracking,
    VulkanEnable,
    VulkanEnable2,
    ConvertTimespec
};

struct Entry {
    std::string_view name;
    PFN_xrVoidFunction function;
    Needs needs;
};

// The static_cast checks each function against the PFN_ type openxr.h declares for it.
// (Formatting off: clang-format mangles token pasting inside template arguments.)
// clang-format off
#define PHYSHAND_SIM_ENTRY(fn, needs) \
    {#fn, reinterpret_cast<PFN_xrVoidFunction>(static_cast<PFN_##fn>(&fn)), needs}
// clang-format on

const auto kEntries = std::to_array<Entry>({
    PHYSHAND_SIM_ENTRY(xrGetInstanceProcAddr, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateInstanceExtensionProperties, Needs::NoInstance),
    PHYSHAND_SIM_ENTRY(xrCreateInstance, Needs::NoInstance),
    PHYSHAND_SIM_ENTRY(xrDestroyInstance, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetInstanceProperties, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrPollEvent, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrResultToString, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrStructureTypeToString, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetSystem, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetSystemProperties, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateViewConfigurations, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetViewConfigurationProperties, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateViewConfigurationViews, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateEnvironmentBlendModes, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrStringToPath, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrPathToString, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrCreateSession, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrDestroySession, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrBeginSession, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEndSession, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrRequestExitSession, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrWaitFrame, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrBeginFrame, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEndFrame, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateReferenceSpaces, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrCreateReferenceSpace, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetReferenceSpaceBoundsRect, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrLocateSpace, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrDestroySpace, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrLocateViews, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrCreateActionSet, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrDestroyActionSet, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrCreateAction, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrDestroyAction, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrSuggestInteractionProfileBindings, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrAttachSessionActionSets, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrSyncActions, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetActionStateBoolean, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetActionStateFloat, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetActionStateVector2f, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetActionStatePose, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrCreateActionSpace, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetCurrentInteractionProfile, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateBoundSourcesForAction, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrGetInputSourceLocalizedName, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrApplyHapticFeedback, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrStopHapticFeedback, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateSwapchainFormats, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrCreateSwapchain, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrDestroySwapchain, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrEnumerateSwapchainImages, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrAcquireSwapchainImage, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrWaitSwapchainImage, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrReleaseSwapchainImage, Needs::Instance),
    PHYSHAND_SIM_ENTRY(xrCreateHandTrackerEXT, Needs::HandTracking),
    PHYSHAND_SIM_ENTRY(xrDestroyHandTrackerEXT, Needs::HandTracking),
    PHYSHAND_SIM_ENTRY(xrLocateHandJointsEXT, Needs::HandTracking),
    PHYSHAND_SIM_ENTRY(xrGetVulkanGraphicsRequirements2KHR, Needs::VulkanEnable2),
    PHYSHAND_SIM_ENTRY(xrCreateVulkanInstanceKHR, Needs::VulkanEnable2),
    PHYSHAND_SIM_ENTRY(xrGetVulkanGraphicsDevice2KHR, Needs::VulkanEnable2),
    PHYSHAND_SIM_ENTRY(xrCreateVulkanDeviceKHR, Needs::VulkanEnable2),
    PHYSHAND_SIM_ENTRY(xrGetVulkanInstanceExtensionsKHR, Needs::VulkanEnable),
    PHYSHAND_SIM_ENTRY(xrGetVulkanDeviceExtensionsKHR, Needs::VulkanEnable),
    PHYSHAND_SIM_ENTRY(xrGetVulkanGraphicsDeviceKHR, Needs::VulkanEnable),
    PHYSHAND_SIM_ENTRY(xrGetVulkanGraphicsRequirementsKHR, Needs::VulkanEnable),
    PHYSHAND_SIM_ENTRY(xrConvertTimespecTimeToTimeKHR, Needs::ConvertTimespec),
    PHYSHAND_SIM_ENTRY(xrConvertTimeToTimespecTimeKHR, Needs::ConvertTimespec),
});

#undef PHYSHAND_SIM_ENTRY

const Entry* find_entry(std::string_view name) {
    for (const Entry& entry : kEntries) {
        if (entry.name == name) return &entry;
    }
    return nullptr;
}

}  // namespace

XrResult xrGetInstanceProcAddr(XrInstance instance, const char* name,
                               PFN_xrVoidFunction* function) {
    return guarded([&](Runtime& rt) {
        if (name == nullptr || function == nullptr) return XR_ERROR_VALIDATION_FAILURE;
        *function = nullptr;
        const Entry* entry = find_entry(name);
        if (instance == XR_NULL_HANDLE) {
            // Without an instance only the functions that create one may be asked for.
            if (entry == nullptr || entry->needs != Needs::NoInstance) {
                return XR_ERROR_HANDLE_INVALID;
            }
        } else {
            const InstanceData* data = rt.instances.find(instance);
            if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
            if (entry == nullptr) return XR_ERROR_FUNCTION_UNSUPPORTED;
            bool enabled = (entry->needs != Needs::HandTracking || data->hand_tracking) &&
                           (entry->needs != Needs::VulkanEnable || data->vulkan_enable) &&
                           (entry->needs != Needs::VulkanEnable2 || data->vulkan_enable2) &&
                           (entry->needs != Needs::ConvertTimespec || data->convert_timespec);
            if (!enabled) return XR_ERROR_FUNCTION_UNSUPPORTED;
        }
        *function = entry->function;
        return XR_SUCCESS;
    });
}

}  // namespace physhand::sim

extern "C" __attribute__((visibility("default"))) XRAPI_ATTR XrResult XRAPI_CALL
xrNegotiateLoaderRuntimeInterface(const XrNegotiateLoaderInfo* loaderInfo,
                                  XrNegotiateRuntimeRequest* runtimeRequest) {
    if (loaderInfo == nullptr || runtimeRequest == nullptr ||
        loaderInfo->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
        loaderInfo->structVersion != XR_LOADER_INFO_STRUCT_VERSION ||
        loaderInfo->structSize != sizeof(XrNegotiateLoaderInfo) ||
        runtimeRequest->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST ||
        runtimeRequest->structVersion != XR_RUNTIME_INFO_STRUCT_VERSION ||
        runtimeRequest->structSize != sizeof(XrNegotiateRuntimeRequest)) {
        return XR_ERROR_INITIALIZATION_FAILED;
    }
    if (loaderInfo->minInterfaceVersion > XR_CURRENT_LOADER_RUNTIME_VERSION ||
        loaderInfo->maxInterfaceVersion < XR_CURRENT_LOADER_RUNTIME_VERSION ||
        loaderInfo->minApiVersion > XR_CURRENT_API_VERSION ||
        loaderInfo->maxApiVersion < XR_CURRENT_API_VERSION) {
        return XR_ERROR_INITIALIZATION_FAILED;
    }
    runtimeRequest->runtimeInterfaceVersion = XR_CURRENT_LOADER_RUNTIME_VERSION;
    runtimeRequest->runtimeApiVersion = XR_CURRENT_API_VERSION;
    runtimeRequest->getInstanceProcAddr = &physhand::sim::xrGetInstanceProcAddr;
    return XR_SUCCESS;
}
// No prototype is in scope (XR_NO_PROTOTYPES), so check the signature the loader expects.
static_assert(std::is_same_v<decltype(&xrNegotiateLoaderRuntimeInterface),
                             PFN_xrNegotiateLoaderRuntimeInterface>);
