#include "dispatch.h"

#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "layer_log.h"
#include "sessions.h"

namespace physhand::layer {

namespace {

// When the layer hands out its own entry point instead of the next layer's.
enum class Scope {
    Always,        // bookkeeping the layer needs even when the config turned it off
    Enabled,       // the layer is on and the chain below provides the function
    Extension,     // the layer is on and the app enabled XR_PHYSHAND_physical_hands
    HandTracking,  // the layer is on and the app enabled XR_EXT_hand_tracking
};

struct Intercept {
    const char* name;
    PFN_xrVoidFunction function;
    Scope scope;
};

template <typename F>
PFN_xrVoidFunction to_void(F* function) {
    return reinterpret_cast<PFN_xrVoidFunction>(function);
}

const Intercept* find_intercept(const char* name) {
    static const Intercept intercepts[] = {
        {"xrGetInstanceProcAddr", to_void(&GetInstanceProcAddr), Scope::Always},
        {"xrDestroyInstance", to_void(&DestroyInstance), Scope::Always},
        {"xrCreateSession", to_void(&CreateSession), Scope::Enabled},
        {"xrDestroySession", to_void(&DestroySession), Scope::Enabled},
        {"xrEndFrame", to_void(&EndFrame), Scope::Enabled},
        {"xrCreateHandTrackerEXT", to_void(&CreateHandTrackerEXT), Scope::HandTracking},
        {"xrDestroyHandTrackerEXT", to_void(&DestroyHandTrackerEXT), Scope::HandTracking},
        {"xrLocateHandJointsEXT", to_void(&LocateHandJointsEXT), Scope::HandTracking},
        {"xrCreatePhysicalColliderPHYSHAND", to_void(&CreatePhysicalColliderPHYSHAND),
         Scope::Extension},
        {"xrDestroyPhysicalColliderPHYSHAND", to_void(&DestroyPhysicalColliderPHYSHAND),
         Scope::Extension},
        {"xrSetPhysicalColliderPosePHYSHAND", to_void(&SetPhysicalColliderPosePHYSHAND),
         Scope::Extension},
        {"xrLocatePhysicalCollidersPHYSHAND", to_void(&LocatePhysicalCollidersPHYSHAND),
         Scope::Extension},
        {"xrSetHandDrivePHYSHAND", to_void(&SetHandDrivePHYSHAND), Scope::Extension},
        {"xrSetPhysicalContactReportingPHYSHAND", to_void(&SetPhysicalContactReportingPHYSHAND),
         Scope::Extension},
        {"xrGetPhysicalContactEventsPHYSHAND", to_void(&GetPhysicalContactEventsPHYSHAND),
         Scope::Extension},
    };
    for (const Intercept& intercept : intercepts) {
        if (std::strcmp(intercept.name, name) == 0) return &intercept;
    }
    return nullptr;
}

template <typename PFN>
PFN next_function(XrInstance instance, PFN_xrGetInstanceProcAddr next_gipa, const char* name) {
    PFN_xrVoidFunction function = nullptr;
    if (XR_FAILED(next_gipa(instance, name, &function))) return nullptr;
    return reinterpret_cast<PFN>(function);
}

}  // namespace

NextDispatch make_next_dispatch(XrInstance instance, PFN_xrGetInstanceProcAddr next_gipa) {
    NextDispatch next;
    next.GetInstanceProcAddr = next_gipa;
    const auto required = [&](auto& slot, const char* name) {
        slot = next_function<std::remove_reference_t<decltype(slot)>>(instance, next_gipa, name);
        if (slot == nullptr) throw std::runtime_error(std::string("the next layer has no ") + name);
    };
    required(next.DestroyInstance, "xrDestroyInstance");
    required(next.CreateSession, "xrCreateSession");
    required(next.DestroySession, "xrDestroySession");
    required(next.CreateReferenceSpace, "xrCreateReferenceSpace");
    required(next.DestroySpace, "xrDestroySpace");
    required(next.LocateSpace, "xrLocateSpace");
    required(next.GetSystemProperties, "xrGetSystemProperties");
    required(next.EnumerateViewConfigurationViews, "xrEnumerateViewConfigurationViews");
    required(next.EndFrame, "xrEndFrame");
    required(next.EnumerateSwapchainFormats, "xrEnumerateSwapchainFormats");
    required(next.CreateSwapchain, "xrCreateSwapchain");
    required(next.DestroySwapchain, "xrDestroySwapchain");
    required(next.EnumerateSwapchainImages, "xrEnumerateSwapchainImages");
    required(next.AcquireSwapchainImage, "xrAcquireSwapchainImage");
    required(next.WaitSwapchainImage, "xrWaitSwapchainImage");
    required(next.ReleaseSwapchainImage, "xrReleaseSwapchainImage");
    next.CreateHandTrackerEXT =
        next_function<PFN_xrCreateHandTrackerEXT>(instance, next_gipa, "xrCreateHandTrackerEXT");
    next.DestroyHandTrackerEXT =
        next_function<PFN_xrDestroyHandTrackerEXT>(instance, next_gipa, "xrDestroyHandTrackerEXT");
    next.LocateHandJointsEXT =
        next_function<PFN_xrLocateHandJointsEXT>(instance, next_gipa, "xrLocateHandJointsEXT");
    return next;
}

XRAPI_ATTR XrResult XRAPI_CALL GetInstanceProcAddr(XrInstance instance, const char* name,
                                                   PFN_xrVoidFunction* function) {
    return guarded("xrGetInstanceProcAddr", [&] {
        if (name == nullptr || function == nullptr) return XR_ERROR_VALIDATION_FAILURE;
        const std::shared_ptr<const InstanceState> state = find_instance(instance);
        if (!state) {
            *function = nullptr;
            return XR_ERROR_HANDLE_INVALID;
        }
        const Intercept* intercept = find_intercept(name);
        // Everything the layer does not need is the next layer's own pointer: zero overhead.
        if (intercept == nullptr || (!state->config.enabled && intercept->scope != Scope::Always)) {
            return state->next.GetInstanceProcAddr(instance, name, function);
        }
        // An extension's functions exist for the app only when it enabled the extension,
        // whatever the layer enabled down the chain for itself.
        const bool app_enabled = intercept->scope == Scope::Extension ? state->extension_enabled
                                 : intercept->scope == Scope::HandTracking
                                     ? state->app_hand_tracking
                                     : true;
        if (!app_enabled) {
            *function = nullptr;
            return XR_ERROR_FUNCTION_UNSUPPORTED;
        }
        if (intercept->scope == Scope::Extension) {
            *function = intercept->function;
            return XR_SUCCESS;
        }
        // Only replace what the chain provides: the answer for a function it lacks (hand
        // tracking on a runtime without it) must stay the chain's.
        const XrResult result = state->next.GetInstanceProcAddr(instance, name, function);
        if (XR_SUCCEEDED(result) && *function != nullptr) *function = intercept->function;
        return result;
    });
}

}  // namespace physhand::layer
