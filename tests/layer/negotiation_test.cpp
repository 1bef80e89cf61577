// The loader-layer negotiation as the loader specification defines it, called directly on
// the built layer: the 1.0.20 loader offers OpenXR 1.0, current loaders 1.0 up to any 1.x;
// the layer takes 1.0 and 1.1, and an app's 1.1 instance is made through it.

#include <dlfcn.h>

#include <array>
#include <cstring>

#include "layer_fixture.h"
#include "loader_negotiation.h"

namespace physhand::layer_test {
namespace {

constexpr const char* kName = "XR_APILAYER_PHYSHAND_physical_hands";

class Negotiation : public ::testing::Test {
  protected:
    void SetUp() override {
        library_ = dlopen(PHYSHAND_LAYER_LIBRARY, RTLD_NOW | RTLD_LOCAL);
        ASSERT_NE(library_, nullptr) << dlerror();
        negotiate_ = reinterpret_cast<PFN_xrNegotiateLoaderApiLayerInterface>(
            dlsym(library_, "xrNegotiateLoaderApiLayerInterface"));
        ASSERT_NE(negotiate_, nullptr);
    }
    void TearDown() override {
        if (library_ != nullptr) dlclose(library_);
    }

    // The loader's offer: interface 1, API versions [min, max].
    static XrNegotiateLoaderInfo offer(XrVersion min, XrVersion max) {
        XrNegotiateLoaderInfo info{};
        info.structType = XR_LOADER_INTERFACE_STRUCT_LOADER_INFO;
        info.structVersion = XR_LOADER_INFO_STRUCT_VERSION;
        info.structSize = sizeof(info);
        info.minInterfaceVersion = 1;
        info.maxInterfaceVersion = 1;
        info.minApiVersion = min;
        info.maxApiVersion = max;
        return info;
    }
    static XrNegotiateApiLayerRequest request() {
        XrNegotiateApiLayerRequest request{};
        request.structType = XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST;
        request.structVersion = XR_API_LAYER_INFO_STRUCT_VERSION;
        request.structSize = sizeof(request);
        return request;
    }

    void* library_ = nullptr;
    PFN_xrNegotiateLoaderApiLayerInterface negotiate_ = nullptr;
};

TEST_F(Negotiation, OpenXR10And11LoadersAreAnsweredWithTheirNewestVersionTheLayerServes) {
    struct Case {
        const char* what;
        XrVersion min, max;
        XrVersion answered;
    };
    const XrVersion newest_1_x = XR_MAKE_VERSION(1, 0x3ff, 0xfff);
    for (const Case& c : {
             Case{"1.0 only (loader 1.0.20)", XR_MAKE_VERSION(1, 0, 0), XR_MAKE_VERSION(1, 0, 20),
                  XR_MAKE_VERSION(1, 0, 20)},
             Case{"any 1.x (current loaders)", XR_MAKE_VERSION(1, 0, 0), newest_1_x,
                  XR_MAKE_VERSION(1, 1, 0xffffffffULL)},
             Case{"1.1 only", XR_MAKE_VERSION(1, 1, 0), XR_MAKE_VERSION(1, 1, 45),
                  XR_MAKE_VERSION(1, 1, 45)},
         }) {
        SCOPED_TRACE(c.what);
        const XrNegotiateLoaderInfo info = offer(c.min, c.max);
        XrNegotiateApiLayerRequest answer = request();
        ASSERT_EQ(negotiate_(&info, kName, &answer), XR_SUCCESS);
        EXPECT_EQ(answer.layerInterfaceVersion, 1u);
        EXPECT_EQ(answer.layerApiVersion, c.answered);
        EXPECT_GE(answer.layerApiVersion, c.min);
        EXPECT_LE(answer.layerApiVersion, c.max);
        EXPECT_NE(answer.getInstanceProcAddr, nullptr);
        EXPECT_NE(answer.createApiLayerInstance, nullptr);
    }
}

TEST_F(Negotiation, WhatTheLayerCannotServeIsRefused) {
    XrNegotiateApiLayerRequest answer = request();
    XrNegotiateLoaderInfo info = offer(XR_MAKE_VERSION(1, 2, 0), XR_MAKE_VERSION(1, 2, 9));
    EXPECT_EQ(negotiate_(&info, kName, &answer), XR_ERROR_INITIALIZATION_FAILED) << "1.2 only";
    info = offer(XR_MAKE_VERSION(2, 0, 0), XR_MAKE_VERSION(2, 0, 9));
    EXPECT_EQ(negotiate_(&info, kName, &answer), XR_ERROR_INITIALIZATION_FAILED) << "2.0";
    info = offer(XR_MAKE_VERSION(1, 0, 0), XR_MAKE_VERSION(1, 0, 9));
    info.minInterfaceVersion = info.maxInterfaceVersion = 2;
    EXPECT_EQ(negotiate_(&info, kName, &answer), XR_ERROR_INITIALIZATION_FAILED)
        << "loader interface 2";
    info = offer(XR_MAKE_VERSION(1, 0, 0), XR_MAKE_VERSION(1, 0, 9));
    EXPECT_EQ(negotiate_(&info, "XR_APILAYER_someone_else", &answer),
              XR_ERROR_INITIALIZATION_FAILED);
    info.structSize = sizeof(info) - 8;
    EXPECT_EQ(negotiate_(&info, kName, &answer), XR_ERROR_INITIALIZATION_FAILED);
    EXPECT_EQ(negotiate_(nullptr, kName, &answer), XR_ERROR_INITIALIZATION_FAILED);
}

// The loader's part of instance creation, played by the test: the layer's link of the chain,
// then the runtime (as the loader's terminator would call it), recording what reached it.
PFN_xrGetInstanceProcAddr g_runtime_gipa = nullptr;
XrVersion g_runtime_saw_version = 0;

XRAPI_ATTR XrResult XRAPI_CALL create_on_runtime(const XrInstanceCreateInfo* info,
                                                 const XrApiLayerCreateInfo*,
                                                 XrInstance* instance) {
    PFN_xrVoidFunction create = nullptr;
    if (XR_FAILED(g_runtime_gipa(XR_NULL_HANDLE, "xrCreateInstance", &create))) {
        return XR_ERROR_RUNTIME_FAILURE;
    }
    g_runtime_saw_version = info->applicationInfo.apiVersion;
    return reinterpret_cast<PFN_xrCreateInstance>(create)(info, instance);
}

// The 1.0.20 loader refuses apps asking for 1.1 ("Max supported version is 1.0"), so the
// chain a 1.1 loader builds is built here: an app's 1.1 instance through the layer, down
// to the simulated runtime.
TEST_F(Negotiation, AnOpenXR11InstanceIsMadeThroughTheLayer) {
    void* runtime = dlopen(PHYSHAND_SIM_RUNTIME_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(runtime, nullptr) << dlerror();
    const auto negotiate_runtime = reinterpret_cast<PFN_xrNegotiateLoaderRuntimeInterface>(
        dlsym(runtime, "xrNegotiateLoaderRuntimeInterface"));
    ASSERT_NE(negotiate_runtime, nullptr);
    const XrNegotiateLoaderInfo info =
        offer(XR_MAKE_VERSION(1, 0, 0), XR_MAKE_VERSION(1, 0x3ff, 0xfff));
    XrNegotiateRuntimeRequest runtime_answer{};
    runtime_answer.structType = XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST;
    runtime_answer.structVersion = XR_RUNTIME_INFO_STRUCT_VERSION;
    runtime_answer.structSize = sizeof(runtime_answer);
    ASSERT_EQ(negotiate_runtime(&info, &runtime_answer), XR_SUCCESS);
    g_runtime_gipa = runtime_answer.getInstanceProcAddr;
    XrNegotiateApiLayerRequest layer = request();
    ASSERT_EQ(negotiate_(&info, kName, &layer), XR_SUCCESS);

    XrApiLayerNextInfo link{};
    link.structType = XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO;
    link.structVersion = XR_API_LAYER_NEXT_INFO_STRUCT_VERSION;
    link.structSize = sizeof(link);
    std::strcpy(link.layerName, kName);
    link.nextGetInstanceProcAddr = g_runtime_gipa;
    link.nextCreateApiLayerInstance = &create_on_runtime;
    XrApiLayerCreateInfo chain{};
    chain.structType = XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO;
    chain.structVersion = XR_API_LAYER_CREATE_INFO_STRUCT_VERSION;
    chain.structSize = sizeof(chain);
    chain.nextInfo = &link;

    const std::array<const char*, 3> extensions = {XR_EXT_HAND_TRACKING_EXTENSION_NAME,
                                                   XR_MND_HEADLESS_EXTENSION_NAME,
                                                   XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME};
    XrInstanceCreateInfo create{};
    create.type = XR_TYPE_INSTANCE_CREATE_INFO;
    std::strcpy(create.applicationInfo.applicationName, "physhand 1.1 app");
    create.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 1, 0);
    create.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    create.enabledExtensionNames = extensions.data();
    XrInstance instance = XR_NULL_HANDLE;
    ASSERT_EQ(layer.createApiLayerInstance(&create, &chain, &instance), XR_SUCCESS);
    EXPECT_EQ(g_runtime_saw_version, XR_MAKE_VERSION(1, 1, 0)) << "passed down as asked";
    // The layer's own extension works in that instance, and the instance goes away.
    PFN_xrVoidFunction fn = nullptr;
    EXPECT_EQ(layer.getInstanceProcAddr(instance, "xrCreatePhysicalColliderPHYSHAND", &fn),
              XR_SUCCESS);
    EXPECT_NE(fn, nullptr);
    ASSERT_EQ(layer.getInstanceProcAddr(instance, "xrDestroyInstance", &fn), XR_SUCCESS);
    EXPECT_EQ(reinterpret_cast<PFN_xrDestroyInstance>(fn)(instance), XR_SUCCESS);
    dlclose(runtime);
}

}  // namespace
}  // namespace physhand::layer_test
