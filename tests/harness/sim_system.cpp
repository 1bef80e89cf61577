// The one simulated system: a head-mounted display with a stereo view configuration and
// an opaque display.

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

constexpr const char* kSystemName = "physhand simulated HMD";
constexpr uint32_t kMaxViewSize = 4096;

XrResult check_system(Runtime& rt, XrInstance instance, XrSystemId systemId) {
    if (rt.instances.find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
    return systemId == kSystemId ? XR_SUCCESS : XR_ERROR_SYSTEM_INVALID;
}

XrResult check_view_configuration(Runtime& rt, XrInstance instance, XrSystemId systemId,
                                  XrViewConfigurationType type) {
    if (XrResult result = check_system(rt, instance, systemId); XR_FAILED(result)) {
        return result;
    }
    return type == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO
               ? XR_SUCCESS
               : XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
}

}  // namespace

XrResult xrGetSystem(XrInstance instance, const XrSystemGetInfo* getInfo, XrSystemId* systemId) {
    return guarded([&](Runtime& rt) {
        if (rt.instances.find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(getInfo, XR_TYPE_SYSTEM_GET_INFO) || systemId == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        switch (getInfo->formFactor) {
            case XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY:
                *systemId = kSystemId;
                return XR_SUCCESS;
            case XR_FORM_FACTOR_HANDHELD_DISPLAY:
                return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
            default:
                return XR_ERROR_VALIDATION_FAILURE;
        }
    });
}

XrResult xrGetSystemProperties(XrInstance instance, XrSystemId systemId,
                               XrSystemProperties* properties) {
    return guarded([&](Runtime& rt) {
        if (XrResult result = check_system(rt, instance, systemId); XR_FAILED(result)) {
            return result;
        }
        if (!has_type(properties, XR_TYPE_SYSTEM_PROPERTIES)) return XR_ERROR_VALIDATION_FAILURE;
        properties->systemId = kSystemId;
        properties->vendorId = 0;
        copy_string(properties->systemName, kSystemName);
        properties->graphicsProperties = {kMaxViewSize, kMaxViewSize, kMaxLayerCount};
        properties->trackingProperties = {XR_TRUE, XR_TRUE};
        // The extension struct is only defined when its extension is enabled.
        if (rt.instances.find(instance)->hand_tracking) {
            if (auto* hand = find_in_chain<XrSystemHandTrackingPropertiesEXT>(
                    properties->next, XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT)) {
                hand->supportsHandTracking = XR_TRUE;
            }
        }
        return XR_SUCCESS;
    });
}

XrResult xrEnumerateViewConfigurations(XrInstance instance, XrSystemId systemId,
                                       uint32_t viewConfigurationTypeCapacityInput,
                                       uint32_t* viewConfigurationTypeCountOutput,
                                       XrViewConfigurationType* viewConfigurationTypes) {
    return guarded([&](Runtime& rt) {
        if (XrResult result = check_system(rt, instance, systemId); XR_FAILED(result)) {
            return result;
        }
        return fill_array(viewConfigurationTypeCapacityInput, viewConfigurationTypeCountOutput,
                          viewConfigurationTypes, 1, [](XrViewConfigurationType& out, uint32_t) {
                              out = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
                              return XR_SUCCESS;
                          });
    });
}

XrResult xrGetViewConfigurationProperties(XrInstance instance, XrSystemId systemId,
                                          XrViewConfigurationType viewConfigurationType,
                                          XrViewConfigurationProperties* configurationProperties) {
    return guarded([&](Runtime& rt) {
        if (XrResult result =
                check_view_configuration(rt, instance, systemId, viewConfigurationType);
            XR_FAILED(result)) {
            return result;
        }
        if (!has_type(configurationProperties, XR_TYPE_VIEW_CONFIGURATION_PROPERTIES)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        configurationProperties->viewConfigurationType = viewConfigurationType;
        configurationProperties->fovMutable = XR_FALSE;
        return XR_SUCCESS;
    });
}

XrResult xrEnumerateViewConfigurationViews(XrInstance instance, XrSystemId systemId,
                                           XrViewConfigurationType viewConfigurationType,
                                           uint32_t viewCapacityInput, uint32_t* viewCountOutput,
                                           XrViewConfigurationView* views) {
    return guarded([&](Runtime& rt) {
        if (XrResult result =
                check_view_configuration(rt, instance, systemId, viewConfigurationType);
            XR_FAILED(result)) {
            return result;
        }
        return fill_array(viewCapacityInput, viewCountOutput, views, kViewCount,
                          [](XrViewConfigurationView& out, uint32_t) {
                              if (out.type != XR_TYPE_VIEW_CONFIGURATION_VIEW) {
                                  return XR_ERROR_VALIDATION_FAILURE;
                              }
                              out.recommendedImageRectWidth = kViewSize;
                              out.maxImageRectWidth = kMaxViewSize;
                              out.recommendedImageRectHeight = kViewSize;
                              out.maxImageRectHeight = kMaxViewSize;
                              out.recommendedSwapchainSampleCount = 1;
                              out.maxSwapchainSampleCount = 1;
                              return XR_SUCCESS;
                          });
    });
}

XrResult xrEnumerateEnvironmentBlendModes(XrInstance instance, XrSystemId systemId,
                                          XrViewConfigurationType viewConfigurationType,
                                          uint32_t environmentBlendModeCapacityInput,
                                          uint32_t* environmentBlendModeCountOutput,
                                          XrEnvironmentBlendMode* environmentBlendModes) {
    return guarded([&](Runtime& rt) {
        if (XrResult result =
                check_view_configuration(rt, instance, systemId, viewConfigurationType);
            XR_FAILED(result)) {
            return result;
        }
        return fill_array(environmentBlendModeCapacityInput, environmentBlendModeCountOutput,
                          environmentBlendModes, 1, [](XrEnvironmentBlendMode& out, uint32_t) {
                              out = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
                              return XR_SUCCESS;
                          });
    });
}

}  // namespace physhand::sim
