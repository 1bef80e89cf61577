// How the loader finds the layer (implicit, explicit, disabled), what it advertises, what
// reaches the runtime, and where core validation sits.

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

constexpr const char* kExtensionFunctions[] = {
    "xrCreatePhysicalColliderPHYSHAND", "xrDestroyPhysicalColliderPHYSHAND",
    "xrSetPhysicalColliderPosePHYSHAND", "xrLocatePhysicalCollidersPHYSHAND",
    "xrSetHandDrivePHYSHAND"};

std::vector<XrExtensionProperties> instance_extensions(const char* layer = nullptr) {
    std::uint32_t count = 0;
    const XrResult result = xrEnumerateInstanceExtensionProperties(layer, 0, &count, nullptr);
    EXPECT_EQ(result, XR_SUCCESS) << (layer ? layer : "(no layer)");
    if (XR_FAILED(result)) return {};
    std::vector<XrExtensionProperties> extensions(
        count, xr<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
    EXPECT_EQ(xrEnumerateInstanceExtensionProperties(layer, count, &count, extensions.data()),
              XR_SUCCESS);
    extensions.resize(count);
    return extensions;
}

std::optional<std::uint32_t> extension_version(const std::vector<XrExtensionProperties>& list,
                                               const char* name) {
    for (const XrExtensionProperties& e : list) {
        if (std::strcmp(e.extensionName, name) == 0) return e.extensionVersion;
    }
    return std::nullopt;
}

std::vector<std::string> api_layers() {
    std::uint32_t count = 0;
    EXPECT_EQ(xrEnumerateApiLayerProperties(0, &count, nullptr), XR_SUCCESS);
    std::vector<XrApiLayerProperties> layers(
        count, xr<XrApiLayerProperties>(XR_TYPE_API_LAYER_PROPERTIES));
    EXPECT_EQ(xrEnumerateApiLayerProperties(count, &count, layers.data()), XR_SUCCESS);
    std::vector<std::string> names;
    for (std::uint32_t i = 0; i < count; ++i) names.emplace_back(layers[i].layerName);
    return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

class LayerDiscovery : public LayerTest, public ::testing::WithParamInterface<LayerMode> {
  protected:
    void SetUp() override {
        LayerTest::SetUp();
        use_scene(still_hands_scene());
    }
};

// The layer is listed once, advertises its extension, and provides it, found either way.
TEST_P(LayerDiscovery, LayerIsFoundOnceAndProvidesItsExtension) {
    use_layer(GetParam());
    const std::vector<std::string> layers = api_layers();
    EXPECT_EQ(std::count(layers.begin(), layers.end(), kLayerName), 1);
    EXPECT_EQ(extension_version(instance_extensions(), XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME),
              XR_PHYSHAND_physical_hands_SPEC_VERSION);
    // Asked for by name, the layer has exactly its one extension.
    const auto own = instance_extensions(kLayerName);
    ASSERT_EQ(own.size(), 1u);
    EXPECT_STREQ(own[0].extensionName, XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME);

    ASSERT_EQ(create_instance(), XR_SUCCESS);
    for (const char* name : kExtensionFunctions) {
        PFN_xrVoidFunction fn = nullptr;
        EXPECT_EQ(xrGetInstanceProcAddr(instance_, name, &fn), XR_SUCCESS) << name;
        EXPECT_NE(fn, nullptr) << name;
    }
    // And it is in the call chain: its extension works.
    start_session();
    const XrTime time = frame();
    const auto sphere = create_collider(collider_info(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND,
                                                      XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND,
                                                      stage_, pose_at(0, 1, -1), time));
    EXPECT_NEAR(locate_collider(sphere, time).pose.position.y, 1.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Modes, LayerDiscovery,
                         ::testing::Values(LayerMode::Implicit, LayerMode::Explicit),
                         [](const auto& info) {
                             return info.param == LayerMode::Implicit ? "Implicit" : "Explicit";
                         });

using LayerDiscoveryTest = LayerDiscovery;

TEST_F(LayerDiscoveryTest, ExplicitLayerIsAbsentUnlessEnabled) {
    use_layer(LayerMode::Explicit);
    // Found on XR_API_LAYER_PATH, but only core validation enabled.
    if (validation_available()) {
        env_.set("XR_ENABLE_API_LAYERS", kCoreValidationName);
    } else {
        env_.unset("XR_ENABLE_API_LAYERS");
    }
    EXPECT_TRUE(contains(api_layers(), kLayerName));
    EXPECT_EQ(extension_version(instance_extensions(), XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME),
              std::nullopt);
    EXPECT_EQ(create_instance(), XR_ERROR_EXTENSION_NOT_PRESENT);
    EXPECT_EQ(create_instance(without_physhand()), XR_SUCCESS);
}

TEST_F(LayerDiscoveryTest, DisableVariableTurnsTheImplicitLayerOff) {
    use_layer(LayerMode::Disabled);
    EXPECT_EQ(extension_version(instance_extensions(), XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME),
              std::nullopt);
    EXPECT_EQ(create_instance(), XR_ERROR_EXTENSION_NOT_PRESENT);
    EXPECT_EQ(instance_, XR_NULL_HANDLE);
    // The app itself is unaffected.
    ASSERT_EQ(create_instance(without_physhand()), XR_SUCCESS);
    start_session();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints joints;
    EXPECT_EQ(locate(right, stage_, frame(), joints, Chain::Velocities), XR_SUCCESS);
    EXPECT_TRUE(joints.locations.isActive);
}

TEST_F(LayerDiscoveryTest, ExtensionFunctionsAreUnsupportedUnlessTheExtensionIsEnabled) {
    ASSERT_EQ(create_instance(without_physhand()), XR_SUCCESS);
    for (const char* name : kExtensionFunctions) {
        PFN_xrVoidFunction fn = reinterpret_cast<PFN_xrVoidFunction>(&xrGetInstanceProcAddr);
        EXPECT_EQ(xrGetInstanceProcAddr(instance_, name, &fn), XR_ERROR_FUNCTION_UNSUPPORTED)
            << name;
        EXPECT_EQ(fn, nullptr) << name;
    }
    // Hand tracking, which the layer intercepts, is there all the same.
    PFN_xrVoidFunction fn = nullptr;
    EXPECT_EQ(xrGetInstanceProcAddr(instance_, "xrLocateHandJointsEXT", &fn), XR_SUCCESS);
    EXPECT_NE(fn, nullptr);
}

// The runtime rejects extensions it does not know (XR_ERROR_EXTENSION_NOT_PRESENT), so an
// instance with the layer's extension enabled exists only if the layer took it out of the
// list; the app's other extensions must have reached the runtime.
TEST_F(LayerDiscoveryTest, AppExtensionsReachTheRuntimeWithoutTheLayersOwn) {
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    // XR_EXT_hand_tracking reached it: it fills the hand tracking properties only then.
    auto hand = xr<XrSystemHandTrackingPropertiesEXT>(XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT);
    auto properties = xr<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
    properties.next = &hand;
    EXPECT_EQ(xrGetSystemProperties(instance_, system(), &properties), XR_SUCCESS);
    EXPECT_EQ(hand.supportsHandTracking, XR_TRUE);
    // XR_MND_headless reached it: a session without a graphics binding exists.
    start_session();
    EXPECT_NE(session_, XR_NULL_HANDLE);
    end_session();
    destroy_instance();

    // Without XR_EXT_hand_tracking the runtime has no hand tracking, and the layer does
    // not pretend otherwise. (Core validation of OpenXR 1.0.20 answers with its own
    // function whatever the app enabled, so this is asked without it.)
    use_layer(LayerMode::Implicit, false);
    ASSERT_EQ(create_instance(
                  {XR_MND_HEADLESS_EXTENSION_NAME, XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME}),
              XR_SUCCESS);
    for (const char* name : {"xrCreateHandTrackerEXT", "xrLocateHandJointsEXT"}) {
        PFN_xrVoidFunction fn = reinterpret_cast<PFN_xrVoidFunction>(&xrGetInstanceProcAddr);
        EXPECT_EQ(xrGetInstanceProcAddr(instance_, name, &fn), XR_ERROR_FUNCTION_UNSUPPORTED)
            << name;
        EXPECT_EQ(fn, nullptr) << name;
    }
}

// Core validation is active and sits beneath the layer: it reports an invalid call the
// layer passes through, never sees the layer's own structure (the layer takes it out of
// the chain before calling down), but does see a foreign one the layer leaves in.
TEST_F(LayerDiscoveryTest, CoreValidationIsActiveBeneathTheLayer) {
    if (!validation_available()) GTEST_SKIP() << "core validation layer not installed";
    ASSERT_EQ(create_instance(), XR_SUCCESS);
    auto info = xr<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    info.formFactor = static_cast<XrFormFactor>(77);
    XrSystemId id = XR_NULL_SYSTEM_ID;
    EXPECT_EQ(xrGetSystem(instance_, &info, &id), XR_ERROR_VALIDATION_FAILURE);
    expect_validation_messages({"VUID-XrSystemGetInfo-formFactor-parameter"});

    start_session();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const XrTime time = frame();
    HandJoints joints;
    EXPECT_EQ(locate(right, stage_, time, joints, Chain::Physical), XR_SUCCESS);
    EXPECT_EQ(take_validation_output(), "");

    // An extension structure of nobody's: the layer passes it down, core validation sees it.
    struct Foreign {
        XrStructureType type;
        void* next;
    } foreign{static_cast<XrStructureType>(1010041999), nullptr};
    joints.physical.next = &foreign;
    auto locate_info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
    locate_info.baseSpace = stage_;
    locate_info.time = time;
    joints.locations.next = &joints.physical;
    EXPECT_EQ(function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")(right, &locate_info,
                                                                           &joints.locations),
              XR_ERROR_VALIDATION_FAILURE);
    // Core validation rejects any structure it does not know in that chain, the layer's
    // own included: that it stayed silent above means it never saw the layer's.
    expect_validation_messages({"VUID-XrHandJointLocationsEXT-next-next"});
}

}  // namespace
}  // namespace physhand::layer_test
