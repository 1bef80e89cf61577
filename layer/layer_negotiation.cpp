#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "config.h"
#include "dispatch.h"
#include "layer_log.h"
#include "loader_negotiation.h"
#include "sessions.h"

// The loader's side of the layer (docs/design.md, "The OpenXR loader"): negotiation,
// instance creation through the chain, and instance destruction.
namespace physhand::layer {

namespace {

bool is_layer_extension(const char* name) {
    return std::strcmp(name, XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME) == 0;
}

bool is_hand_tracking(const char* name) {
    return name != nullptr && std::strcmp(name, XR_EXT_HAND_TRACKING_EXTENSION_NAME) == 0;
}

void destroy_instance(XrInstance instance, PFN_xrGetInstanceProcAddr next_gipa) {
    PFN_xrVoidFunction destroy = nullptr;
    if (XR_SUCCEEDED(next_gipa(instance, "xrDestroyInstance", &destroy)) && destroy != nullptr) {
        reinterpret_cast<PFN_xrDestroyInstance>(destroy)(instance);
    }
}

XRAPI_ATTR XrResult XRAPI_CALL CreateApiLayerInstance(const XrInstanceCreateInfo* info,
                                                      const XrApiLayerCreateInfo* layerInfo,
                                                      XrInstance* instance) {
    return guarded("xrCreateApiLayerInstance", [&] {
        if (info == nullptr || layerInfo == nullptr || instance == nullptr ||
            (info->enabledExtensionCount > 0 && info->enabledExtensionNames == nullptr)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const XrApiLayerNextInfo* next = layerInfo->nextInfo;
        if (layerInfo->structType != XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO ||
            next == nullptr || next->structType != XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO ||
            std::strcmp(next->layerName, kLayerName) != 0 ||
            next->nextGetInstanceProcAddr == nullptr ||
            next->nextCreateApiLayerInstance == nullptr) {
            log_once("xrCreateApiLayerInstance: the loader passed a malformed layer chain");
            return XR_ERROR_INITIALIZATION_FAILED;
        }

        // The loader passes the app's extensions down unchanged, and the layers and runtime
        // below would refuse the one only this layer provides.
        std::vector<const char*> extensions;
        bool extension_enabled = false;
        bool app_hand_tracking = false;
        for (std::uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
            const char* name = info->enabledExtensionNames[i];
            if (name != nullptr && is_layer_extension(name)) {
                extension_enabled = true;
            } else {
                app_hand_tracking = app_hand_tracking || is_hand_tracking(name);
                extensions.push_back(name);
            }
        }
        Config config = load_config();
        XrInstanceCreateInfo down_info = *info;
        XrApiLayerCreateInfo down_layer_info = *layerInfo;
        down_layer_info.nextInfo = next->next;
        const auto create_down = [&] {
            down_info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
            down_info.enabledExtensionNames = extensions.data();
            return next->nextCreateApiLayerInstance(&down_info, &down_layer_info, instance);
        };
        XrResult result = XR_ERROR_EXTENSION_NOT_PRESENT;
        // Hand tracking for the layer's own trackers, in apps that do not track hands. A
        // runtime without it refuses the list: then the app's own list, as it asked.
        if (config.enabled && !app_hand_tracking) {
            extensions.push_back(XR_EXT_HAND_TRACKING_EXTENSION_NAME);
            result = create_down();
            extensions.pop_back();
        }
        if (result == XR_ERROR_EXTENSION_NOT_PRESENT) result = create_down();
        if (XR_FAILED(result)) return result;

        try {
            auto state = std::make_shared<InstanceState>();
            state->instance = *instance;
            state->next = make_next_dispatch(*instance, next->nextGetInstanceProcAddr);
            state->extension_enabled = extension_enabled;
            state->app_hand_tracking = app_hand_tracking;
            state->config = std::move(config);
            add_instance(std::move(state));
        } catch (const std::exception& e) {
            log_failure("xrCreateApiLayerInstance", e.what());
            destroy_instance(*instance, next->nextGetInstanceProcAddr);
            *instance = XR_NULL_HANDLE;
            return XR_ERROR_INITIALIZATION_FAILED;
        }
        return result;
    });
}

}  // namespace

XRAPI_ATTR XrResult XRAPI_CALL DestroyInstance(XrInstance instance) {
    return guarded("xrDestroyInstance", [&] {
        // Forgets every session of the instance too; the runtime destroys their spaces.
        const std::shared_ptr<const InstanceState> state = remove_instance(instance);
        if (!state) return XR_ERROR_HANDLE_INVALID;
        return state->next.DestroyInstance(instance);
    });
}

}  // namespace physhand::layer

namespace {
// OpenXR 1.1, any patch (the 1.0.20 headers know no XR_API_VERSION_1_1).
constexpr XrVersion kNewestApiVersion = XR_MAKE_VERSION(1, 1, 0xffffffffULL);
}  // namespace

// The layer's only exported symbol: the loader finds everything else through it.
extern "C" [[gnu::visibility("default")]] XRAPI_ATTR XrResult XRAPI_CALL
xrNegotiateLoaderApiLayerInterface(const XrNegotiateLoaderInfo* loaderInfo, const char* layerName,
                                   XrNegotiateApiLayerRequest* apiLayerRequest) {
    using namespace physhand::layer;
    if (loaderInfo == nullptr || layerName == nullptr || apiLayerRequest == nullptr ||
        std::strcmp(layerName, kLayerName) != 0 ||
        loaderInfo->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
        loaderInfo->structVersion != XR_LOADER_INFO_STRUCT_VERSION ||
        loaderInfo->structSize != sizeof(XrNegotiateLoaderInfo) ||
        apiLayerRequest->structType != XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST ||
        apiLayerRequest->structVersion != XR_API_LAYER_INFO_STRUCT_VERSION ||
        apiLayerRequest->structSize != sizeof(XrNegotiateApiLayerRequest)) {
        return XR_ERROR_INITIALIZATION_FAILED;
    }
    // Loader interface 1; OpenXR 1.0 and 1.1. The layer intercepts functions of 1.0 that 1.1
    // keeps as they were (sessions, frames, hand tracking) and passes every other one down
    // untouched, so it serves a 1.1 instance as it serves a 1.0 one; a 2.x API it cannot know.
    if (loaderInfo->minInterfaceVersion > XR_CURRENT_LOADER_API_LAYER_VERSION ||
        loaderInfo->maxInterfaceVersion < XR_CURRENT_LOADER_API_LAYER_VERSION ||
        loaderInfo->minApiVersion > kNewestApiVersion ||
        loaderInfo->maxApiVersion < XR_MAKE_VERSION(1, 0, 0)) {
        return XR_ERROR_INITIALIZATION_FAILED;
    }
    apiLayerRequest->layerInterfaceVersion = XR_CURRENT_LOADER_API_LAYER_VERSION;
    // The newest the loader takes: a loader of 1.0 only is told 1.0.
    apiLayerRequest->layerApiVersion = std::min(loaderInfo->maxApiVersion, kNewestApiVersion);
    apiLayerRequest->getInstanceProcAddr = &GetInstanceProcAddr;
    apiLayerRequest->createApiLayerInstance = &CreateApiLayerInstance;
    return XR_SUCCESS;
}
