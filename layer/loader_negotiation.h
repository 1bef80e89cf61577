#pragma once

// The loader <-> runtime and loader <-> API layer negotiation interface of the OpenXR
// loader specification (specification/loader/runtime.adoc and api_layer.adoc, loader
// interface version 1). Newer SDKs ship these in openxr_loader_negotiation.h; Debian's
// 1.0.20 headers do not, so they are declared here, once, for the layer and for the
// simulated runtime. The guard macro is the SDK header's, so the two never clash.

#include <openxr/openxr.h>

#ifndef OPENXR_LOADER_NEGOTIATION_H_
#define OPENXR_LOADER_NEGOTIATION_H_ 1

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define XR_LOADER_VERSION_1_0 1

#define XR_CURRENT_LOADER_API_LAYER_VERSION 1
#define XR_CURRENT_LOADER_RUNTIME_VERSION 1

#define XR_LOADER_INFO_STRUCT_VERSION 1
#define XR_API_LAYER_INFO_STRUCT_VERSION 1
#define XR_RUNTIME_INFO_STRUCT_VERSION 1
#define XR_API_LAYER_NEXT_INFO_STRUCT_VERSION 1
#define XR_API_LAYER_CREATE_INFO_STRUCT_VERSION 1

#define XR_API_LAYER_MAX_SETTINGS_PATH_SIZE 512

// Tags the negotiation structs; "UNINTIALIZED" is the specification's own spelling.
typedef enum XrLoaderInterfaceStructs {
    XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,
    XR_LOADER_INTERFACE_STRUCT_LOADER_INFO = 1,
    XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST = 2,
    XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST = 3,
    XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO = 4,
    XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO = 5,
    XR_LOADER_INTERFACE_STRUCTS_MAX_ENUM = 0x7FFFFFFF
} XrLoaderInterfaceStructs;

// What the loader offers: the interface and API version ranges it can speak.
typedef struct XrNegotiateLoaderInfo {
    XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_LOADER_INFO
    uint32_t structVersion;               // XR_LOADER_INFO_STRUCT_VERSION
    size_t structSize;                    // sizeof(XrNegotiateLoaderInfo)
    uint32_t minInterfaceVersion;
    uint32_t maxInterfaceVersion;
    XrVersion minApiVersion;
    XrVersion maxApiVersion;
} XrNegotiateLoaderInfo;

// What a runtime answers: the versions it chose and its xrGetInstanceProcAddr.
typedef struct XrNegotiateRuntimeRequest {
    XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST
    uint32_t structVersion;               // XR_RUNTIME_INFO_STRUCT_VERSION
    size_t structSize;                    // sizeof(XrNegotiateRuntimeRequest)
    uint32_t runtimeInterfaceVersion;
    XrVersion runtimeApiVersion;
    PFN_xrGetInstanceProcAddr getInstanceProcAddr;
} XrNegotiateRuntimeRequest;

typedef struct XrApiLayerCreateInfo XrApiLayerCreateInfo;

// An API layer's replacement for xrCreateInstance: the loader calls the first layer's,
// each layer calls the next one's through XrApiLayerNextInfo.
typedef XrResult(XRAPI_PTR* PFN_xrCreateApiLayerInstance)(const XrInstanceCreateInfo* info,
                                                          const XrApiLayerCreateInfo* apiLayerInfo,
                                                          XrInstance* instance);

// What an API layer answers: the versions it chose and its two entry points.
typedef struct XrNegotiateApiLayerRequest {
    XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST
    uint32_t structVersion;               // XR_API_LAYER_INFO_STRUCT_VERSION
    size_t structSize;                    // sizeof(XrNegotiateApiLayerRequest)
    uint32_t layerInterfaceVersion;
    XrVersion layerApiVersion;
    PFN_xrGetInstanceProcAddr getInstanceProcAddr;
    PFN_xrCreateApiLayerInstance createApiLayerInstance;
} XrNegotiateApiLayerRequest;

// One link of the layer chain, outermost first; the last one's `next` is NULL and its
// functions are the loader's terminators (which reach the runtime).
typedef struct XrApiLayerNextInfo {
    XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO
    uint32_t structVersion;               // XR_API_LAYER_NEXT_INFO_STRUCT_VERSION
    size_t structSize;                    // sizeof(XrApiLayerNextInfo)
    char layerName[XR_MAX_API_LAYER_NAME_SIZE];
    PFN_xrGetInstanceProcAddr nextGetInstanceProcAddr;
    PFN_xrCreateApiLayerInstance nextCreateApiLayerInstance;
    struct XrApiLayerNextInfo* next;
} XrApiLayerNextInfo;

// Passed to xrCreateApiLayerInstance; a layer advances `nextInfo` by one link (in a copy)
// before calling down.
struct XrApiLayerCreateInfo {
    XrLoaderInterfaceStructs structType;  // XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO
    uint32_t structVersion;               // XR_API_LAYER_CREATE_INFO_STRUCT_VERSION
    size_t structSize;                    // sizeof(XrApiLayerCreateInfo)
    void* loaderInstance;                 // deprecated; ignore
    char settings_file_location[XR_API_LAYER_MAX_SETTINGS_PATH_SIZE];
    XrApiLayerNextInfo* nextInfo;
};

typedef XrResult(XRAPI_PTR* PFN_xrNegotiateLoaderRuntimeInterface)(
    const XrNegotiateLoaderInfo* loaderInfo, XrNegotiateRuntimeRequest* runtimeRequest);
typedef XrResult(XRAPI_PTR* PFN_xrNegotiateLoaderApiLayerInterface)(
    const XrNegotiateLoaderInfo* loaderInfo, const char* layerName,
    XrNegotiateApiLayerRequest* apiLayerRequest);

#ifndef XR_NO_PROTOTYPES
// What a runtime library, or an API layer library, exports for the loader to call first.
XRAPI_ATTR XrResult XRAPI_CALL xrNegotiateLoaderRuntimeInterface(
    const XrNegotiateLoaderInfo* loaderInfo, XrNegotiateRuntimeRequest* runtimeRequest);
XRAPI_ATTR XrResult XRAPI_CALL
xrNegotiateLoaderApiLayerInterface(const XrNegotiateLoaderInfo* loaderInfo, const char* layerName,
                                   XrNegotiateApiLayerRequest* apiLayerRequest);
#endif

#ifdef __cplusplus
}  // extern "C"
#endif

#endif  // OPENXR_LOADER_NEGOTIATION_H_
