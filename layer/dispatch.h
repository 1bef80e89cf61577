#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

// The next layer's functions, and the layer's own entry points (each defined in the file
// of its concern; dispatch.cpp hands them out through xrGetInstanceProcAddr).
namespace physhand::layer {

inline constexpr const char* kLayerName = "XR_APILAYER_PHYSHAND_physical_hands";

// What the layer calls down the chain. Filled once per instance from the next layer's
// xrGetInstanceProcAddr; the hand-tracking functions are null unless XR_EXT_hand_tracking
// is enabled down the chain (by the app, or by the layer for its own trackers).
struct NextDispatch {
    PFN_xrGetInstanceProcAddr GetInstanceProcAddr = nullptr;
    PFN_xrDestroyInstance DestroyInstance = nullptr;
    PFN_xrCreateSession CreateSession = nullptr;
    PFN_xrDestroySession DestroySession = nullptr;
    PFN_xrCreateReferenceSpace CreateReferenceSpace = nullptr;
    PFN_xrDestroySpace DestroySpace = nullptr;
    PFN_xrLocateSpace LocateSpace = nullptr;
    PFN_xrGetSystemProperties GetSystemProperties = nullptr;
    PFN_xrEnumerateViewConfigurationViews EnumerateViewConfigurationViews = nullptr;
    PFN_xrEndFrame EndFrame = nullptr;
    PFN_xrEnumerateSwapchainFormats EnumerateSwapchainFormats = nullptr;
    PFN_xrCreateSwapchain CreateSwapchain = nullptr;
    PFN_xrDestroySwapchain DestroySwapchain = nullptr;
    PFN_xrEnumerateSwapchainImages EnumerateSwapchainImages = nullptr;
    PFN_xrAcquireSwapchainImage AcquireSwapchainImage = nullptr;
    PFN_xrWaitSwapchainImage WaitSwapchainImage = nullptr;
    PFN_xrReleaseSwapchainImage ReleaseSwapchainImage = nullptr;
    PFN_xrCreateHandTrackerEXT CreateHandTrackerEXT = nullptr;
    PFN_xrDestroyHandTrackerEXT DestroyHandTrackerEXT = nullptr;
    PFN_xrLocateHandJointsEXT LocateHandJointsEXT = nullptr;
};

// Throws std::runtime_error when a core function the layer needs is missing.
NextDispatch make_next_dispatch(XrInstance instance, PFN_xrGetInstanceProcAddr next_gipa);

// dispatch.cpp
XRAPI_ATTR XrResult XRAPI_CALL GetInstanceProcAddr(XrInstance instance, const char* name,
                                                   PFN_xrVoidFunction* function);

// layer_negotiation.cpp
XRAPI_ATTR XrResult XRAPI_CALL DestroyInstance(XrInstance instance);

// sessions.cpp
XRAPI_ATTR XrResult XRAPI_CALL CreateSession(XrInstance instance,
                                             const XrSessionCreateInfo* createInfo,
                                             XrSession* session);
XRAPI_ATTR XrResult XRAPI_CALL DestroySession(XrSession session);

// frame_submit.cpp
XRAPI_ATTR XrResult XRAPI_CALL EndFrame(XrSession session, const XrFrameEndInfo* frameEndInfo);

// hand_tracking.cpp
XRAPI_ATTR XrResult XRAPI_CALL CreateHandTrackerEXT(XrSession session,
                                                    const XrHandTrackerCreateInfoEXT* createInfo,
                                                    XrHandTrackerEXT* handTracker);
XRAPI_ATTR XrResult XRAPI_CALL DestroyHandTrackerEXT(XrHandTrackerEXT handTracker);
XRAPI_ATTR XrResult XRAPI_CALL LocateHandJointsEXT(XrHandTrackerEXT handTracker,
                                                   const XrHandJointsLocateInfoEXT* locateInfo,
                                                   XrHandJointLocationsEXT* locations);

// colliders.cpp
XRAPI_ATTR XrResult XRAPI_CALL CreatePhysicalColliderPHYSHAND(
    XrSession session, const XrPhysicalColliderCreateInfoPHYSHAND* createInfo,
    XrPhysicalColliderPHYSHAND* collider);
XRAPI_ATTR XrResult XRAPI_CALL DestroyPhysicalColliderPHYSHAND(XrPhysicalColliderPHYSHAND collider);
XRAPI_ATTR XrResult XRAPI_CALL SetPhysicalColliderPosePHYSHAND(
    XrPhysicalColliderPHYSHAND collider, const XrPhysicalColliderPoseInfoPHYSHAND* poseInfo);
XRAPI_ATTR XrResult XRAPI_CALL LocatePhysicalCollidersPHYSHAND(
    XrSession session, const XrPhysicalCollidersLocateInfoPHYSHAND* locateInfo,
    XrPhysicalColliderLocationsPHYSHAND* locations);

// drive.cpp
XRAPI_ATTR XrResult XRAPI_CALL SetHandDrivePHYSHAND(XrSession session,
                                                    const XrHandDriveInfoPHYSHAND* driveInfo);
XRAPI_ATTR XrResult XRAPI_CALL SetPhysicalContactReportingPHYSHAND(
    XrSession session, const XrPhysicalContactReportingInfoPHYSHAND* reportingInfo);
XRAPI_ATTR XrResult XRAPI_CALL GetPhysicalContactEventsPHYSHAND(
    XrSession session, const XrPhysicalContactEventsGetInfoPHYSHAND* getInfo,
    XrPhysicalContactEventsPHYSHAND* events);

}  // namespace physhand::layer
