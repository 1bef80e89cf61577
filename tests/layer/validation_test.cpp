// Every invalid input answers the XrResult the extension header documents, and never
// crashes the app; afterwards the session works as before.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

template <typename Info>
struct Case {
    std::string name;
    std::function<void(Info&)> change;
    XrResult expected;
};

using CreateInfo = XrPhysicalColliderCreateInfoPHYSHAND;
using PoseInfo = XrPhysicalColliderPoseInfoPHYSHAND;
using DriveInfo = XrHandDriveInfoPHYSHAND;

// Writes a value a C app may put in an enum field, out of the C++ enum's range included
// (which C++ code may not even form as an enum value).
template <typename Enum>
void set_raw(Enum& field, std::int32_t value) {
    static_assert(sizeof(Enum) == sizeof(value));
    std::memcpy(&field, &value, sizeof(value));
}

CreateInfo with_shape(CreateInfo info, XrPhysicalColliderShapePHYSHAND shape) {
    const CreateInfo defaults = collider_info(shape, info.motion, info.space, info.pose, info.time);
    return defaults;
}

class Validation : public LayerTest {
  protected:
    void SetUp() override {
        LayerTest::SetUp();
        use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
        ASSERT_EQ(create_instance(), XR_SUCCESS);
        start_session();
        time_ = frame();
        box_ = create_collider(box_info());
        dynamic_ = create_collider(collider_info(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND,
                                                 XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND,
                                                 stage_, pose_at(0.5f, 1.5f, -1.0f), time_));
        kinematic_ = create_collider(collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                                                   XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND,
                                                   stage_, pose_at(-0.5f, 1.5f, -1.0f), time_));
        // A destroyed session of the same instance, and a live one with its own collider.
        dead_session_ = extra_session();
        EXPECT_EQ(xrDestroySession(dead_session_), XR_SUCCESS);
        other_session_ = extra_session();
        other_stage_ = reference_space(other_session_, XR_REFERENCE_SPACE_TYPE_STAGE);
        auto other = box_info();
        other.space = other_stage_;
        other_collider_ = create_collider(other, other_session_);
        dead_collider_ = create_collider(box_info());
        EXPECT_EQ(api().destroy_collider(dead_collider_), XR_SUCCESS);
    }

    void TearDown() override {
        // Every session still works after all that.
        if (session_ != XR_NULL_HANDLE && !HasFatalFailure()) expect_session_works();
        if (other_session_ != XR_NULL_HANDLE) {
            EXPECT_EQ(xrDestroySession(other_session_), XR_SUCCESS);
        }
        LayerTest::TearDown();
    }

    CreateInfo box_info() const {
        return collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                             XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND, stage_,
                             pose_at(0.0f, 1.0f, -1.0f), time_);
    }

    PoseInfo teleport_info() const {
        auto info = xr<PoseInfo>(XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND);
        info.space = stage_;
        info.time = time_;
        info.pose = pose_at(0.1f, 1.2f, -1.0f);
        info.teleport = XR_TRUE;
        return info;
    }

    void expect_create(const std::vector<Case<CreateInfo>>& cases) {
        for (const auto& c : cases) {
            SCOPED_TRACE(c.name);
            CreateInfo info = box_info();
            c.change(info);
            XrPhysicalColliderPHYSHAND collider = bogus_handle<XrPhysicalColliderPHYSHAND>();
            const XrResult result = api().create_collider(session_, &info, &collider);
            EXPECT_EQ(result, c.expected);
            if (XR_SUCCEEDED(result)) {
                EXPECT_EQ(api().destroy_collider(collider), XR_SUCCESS);
            }
        }
    }

    // The session takes valid calls as before: create, move, locate, step, drive.
    void expect_session_works() {
        const auto collider = create_collider(box_info());
        auto pose = teleport_info();
        pose.time = now();
        EXPECT_EQ(api().set_pose(collider, &pose), XR_SUCCESS);
        EXPECT_EQ(set_drive(XR_HAND_DRIVE_KIND_PAPER_PHYSHAND), XR_SUCCESS);
        const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
        HandJoints hand;
        EXPECT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
        EXPECT_TRUE(hand.locations.isActive);
        const auto located = locate_collider(collider, now());
        EXPECT_NEAR(located.pose.position.y, 1.2f, 1e-5);
        EXPECT_EQ(api().destroy_collider(collider), XR_SUCCESS);
    }

    XrTime time_ = 0;
    XrPhysicalColliderPHYSHAND box_ = XR_NULL_HANDLE;
    XrPhysicalColliderPHYSHAND dynamic_ = XR_NULL_HANDLE;
    XrPhysicalColliderPHYSHAND kinematic_ = XR_NULL_HANDLE;
    XrPhysicalColliderPHYSHAND dead_collider_ = XR_NULL_HANDLE;
    XrPhysicalColliderPHYSHAND other_collider_ = XR_NULL_HANDLE;
    XrSession dead_session_ = XR_NULL_HANDLE;
    XrSession other_session_ = XR_NULL_HANDLE;
    XrSpace other_stage_ = XR_NULL_HANDLE;
};

TEST_F(Validation, CreateColliderRejectsBadHandlesAndPointers) {
    CreateInfo info = box_info();
    XrPhysicalColliderPHYSHAND collider = XR_NULL_HANDLE;
    EXPECT_EQ(api().create_collider(XR_NULL_HANDLE, &info, &collider), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().create_collider(bogus_handle<XrSession>(), &info, &collider),
              XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().create_collider(dead_session_, &info, &collider), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().create_collider(session_, nullptr, &collider), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(api().create_collider(session_, &info, nullptr), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(collider, XR_NULL_HANDLE);
}

TEST_F(Validation, CreateColliderRejectsBadStructures) {
    const auto shape = [](XrPhysicalColliderShapePHYSHAND s) {
        return [s](CreateInfo& i) { i = with_shape(i, s); };
    };
    expect_create({
        {"wrong type", [](CreateInfo& i) { i.type = XR_TYPE_SESSION_CREATE_INFO; },
         XR_ERROR_VALIDATION_FAILURE},
        {"shape 0", [](CreateInfo& i) { i.shape = XrPhysicalColliderShapePHYSHAND(0); },
         XR_ERROR_VALIDATION_FAILURE},
        {"shape 8", [](CreateInfo& i) { i.shape = XrPhysicalColliderShapePHYSHAND(8); },
         XR_ERROR_VALIDATION_FAILURE},
        {"shape max", [](CreateInfo& i) { i.shape = XR_PHYSICAL_COLLIDER_SHAPE_MAX_ENUM_PHYSHAND; },
         XR_ERROR_VALIDATION_FAILURE},
        {"shape -1", [](CreateInfo& i) { set_raw(i.shape, -1); }, XR_ERROR_VALIDATION_FAILURE},
        {"motion -1", [](CreateInfo& i) { set_raw(i.motion, -1); }, XR_ERROR_VALIDATION_FAILURE},
        {"motion 0", [](CreateInfo& i) { i.motion = XrPhysicalColliderMotionPHYSHAND(0); },
         XR_ERROR_VALIDATION_FAILURE},
        {"motion 4", [](CreateInfo& i) { i.motion = XrPhysicalColliderMotionPHYSHAND(4); },
         XR_ERROR_VALIDATION_FAILURE},
        // Sizes.
        {"box zero", [](CreateInfo& i) { i.halfExtents.y = 0.0f; }, XR_ERROR_VALIDATION_FAILURE},
        {"box negative", [](CreateInfo& i) { i.halfExtents.x = -0.1f; },
         XR_ERROR_VALIDATION_FAILURE},
        {"box NaN", [](CreateInfo& i) { i.halfExtents.z = kNaN; }, XR_ERROR_VALIDATION_FAILURE},
        {"box infinite", [](CreateInfo& i) { i.halfExtents.z = kInf; },
         XR_ERROR_VALIDATION_FAILURE},
        {"sphere zero radius",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND)(i);
             i.radius = 0.0f;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"sphere NaN radius",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND)(i);
             i.radius = kNaN;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"capsule negative radius",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND)(i);
             i.radius = -0.05f;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"capsule zero half height (a sphere)",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND)(i);
             i.halfHeight = 0.0f;
         },
         XR_SUCCESS},
        {"capsule negative half height",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND)(i);
             i.halfHeight = -0.01f;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"cylinder zero half height",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_CYLINDER_PHYSHAND)(i);
             i.halfHeight = 0.0f;
         },
         XR_ERROR_VALIDATION_FAILURE},
        // Vertices and indices.
        {"convex of 3 vertices",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND)(i);
             i.vertexCount = 3;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"convex without vertices",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND)(i);
             i.vertices = nullptr;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"convex of no vertices",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND)(i);
             i.vertexCount = 0;
             i.vertices = nullptr;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"mesh index count not a multiple of 3",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND)(i);
             i.indexCount = 35;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"mesh without indices",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND)(i);
             i.indices = nullptr;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"mesh of no triangles",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND)(i);
             i.indexCount = 0;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"mesh index out of range",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND)(i);
             i.vertexCount = 7;  // the cube's triangles use vertex 7
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"mesh of 2 vertices",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND)(i);
             i.vertexCount = 2;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"dynamic mesh",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND)(i);
             i.motion = XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"kinematic mesh",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND)(i);
             i.motion = XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"dynamic plane",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND)(i);
             i.motion = XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"plane of zero normal",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND)(i);
             i.planeNormal = {0, 0, 0};
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"plane of NaN offset",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND)(i);
             i.planeOffset = kNaN;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"plane of a long normal (any length will do)",
         [&](CreateInfo& i) {
             shape(XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND)(i);
             i.planeNormal = {0, 3, 0};
         },
         XR_SUCCESS},
        // Material and mass.
        {"dynamic of zero mass",
         [](CreateInfo& i) {
             i.motion = XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND;
             i.mass = 0.0f;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"dynamic of negative mass",
         [](CreateInfo& i) {
             i.motion = XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND;
             i.mass = -1.0f;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"dynamic of NaN mass",
         [](CreateInfo& i) {
             i.motion = XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND;
             i.mass = kNaN;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"dynamic of infinite mass",
         [](CreateInfo& i) {
             i.motion = XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND;
             i.mass = kInf;
         },
         XR_ERROR_VALIDATION_FAILURE},
        {"static of zero mass (ignored)", [](CreateInfo& i) { i.mass = 0.0f; }, XR_SUCCESS},
        {"negative friction", [](CreateInfo& i) { i.friction = -0.1f; },
         XR_ERROR_VALIDATION_FAILURE},
        {"NaN friction", [](CreateInfo& i) { i.friction = kNaN; }, XR_ERROR_VALIDATION_FAILURE},
        {"negative restitution", [](CreateInfo& i) { i.restitution = -0.1f; },
         XR_ERROR_VALIDATION_FAILURE},
        {"restitution above 1", [](CreateInfo& i) { i.restitution = 1.1f; },
         XR_ERROR_VALIDATION_FAILURE},
    });
}

TEST_F(Validation, CreateColliderRejectsBadPosesSpacesAndTimes) {
    expect_create({
        {"NaN position", [](CreateInfo& i) { i.pose.position.x = kNaN; },
         XR_ERROR_VALIDATION_FAILURE},
        {"infinite position", [](CreateInfo& i) { i.pose.position.y = -kInf; },
         XR_ERROR_VALIDATION_FAILURE},
        {"NaN orientation", [](CreateInfo& i) { i.pose.orientation.w = kNaN; },
         XR_ERROR_VALIDATION_FAILURE},
        {"orientation of length 2",
         [](CreateInfo& i) {
             i.pose.orientation = {0, 0, 0, 2};
         },
         XR_ERROR_POSE_INVALID},
        {"zero orientation",
         [](CreateInfo& i) {
             i.pose.orientation = {0, 0, 0, 0};
         },
         XR_ERROR_POSE_INVALID},
        {"orientation off by float rounding",
         [](CreateInfo& i) {
             i.pose.orientation = {0, 0.70710677f, 0, 0.70710683f};
         },
         XR_SUCCESS},
        {"null space", [](CreateInfo& i) { i.space = XR_NULL_HANDLE; }, XR_ERROR_HANDLE_INVALID},
        {"zero time", [](CreateInfo& i) { i.time = 0; }, XR_ERROR_TIME_INVALID},
        {"negative time", [](CreateInfo& i) { i.time = -11111111; }, XR_ERROR_TIME_INVALID},
    });
}

// The layer locates the app's space through the runtime; the runtime's errors come back
// unchanged (core validation, beneath the layer, reports them too).
TEST_F(Validation, CreateColliderReturnsTheRuntimesAnswerForBadSpaces) {
    const XrSpace gone = reference_space(session_, XR_REFERENCE_SPACE_TYPE_VIEW);
    ASSERT_EQ(xrDestroySpace(gone), XR_SUCCESS);
    expect_create(
        {{"destroyed space", [&](CreateInfo& i) { i.space = gone; }, XR_ERROR_HANDLE_INVALID}});
    expect_validation_messages({"VUID-xrLocateSpace-space-parameter"});
    expect_create({{"space of another session", [&](CreateInfo& i) { i.space = other_stage_; },
                    XR_ERROR_VALIDATION_FAILURE}});
    expect_validation_messages({"xrLocateSpace"});
}

TEST_F(Validation, DestroyColliderRejectsUnknownHandles) {
    EXPECT_EQ(api().destroy_collider(XR_NULL_HANDLE), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().destroy_collider(bogus_handle<XrPhysicalColliderPHYSHAND>()),
              XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().destroy_collider(dead_collider_), XR_ERROR_HANDLE_INVALID);
    // Live ones are untouched by all that.
    EXPECT_NEAR(locate_collider(box_, time_).pose.position.y, 1.0f, 1e-6);
}

TEST_F(Validation, SetColliderPoseRejectsBadInput) {
    const PoseInfo valid = teleport_info();
    EXPECT_EQ(api().set_pose(XR_NULL_HANDLE, &valid), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().set_pose(bogus_handle<XrPhysicalColliderPHYSHAND>(), &valid),
              XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().set_pose(dead_collider_, &valid), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().set_pose(box_, nullptr), XR_ERROR_VALIDATION_FAILURE);

    const std::vector<Case<PoseInfo>> cases = {
        {"wrong type", [](PoseInfo& i) { i.type = XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND; },
         XR_ERROR_VALIDATION_FAILURE},
        {"NaN position", [](PoseInfo& i) { i.pose.position.z = kNaN; },
         XR_ERROR_VALIDATION_FAILURE},
        {"infinite orientation", [](PoseInfo& i) { i.pose.orientation.x = kInf; },
         XR_ERROR_VALIDATION_FAILURE},
        {"orientation of length 0.5",
         [](PoseInfo& i) {
             i.pose.orientation = {0, 0, 0, 0.5f};
         },
         XR_ERROR_POSE_INVALID},
        {"NaN linear velocity", [](PoseInfo& i) { i.linearVelocity.y = kNaN; },
         XR_ERROR_VALIDATION_FAILURE},
        {"infinite angular velocity", [](PoseInfo& i) { i.angularVelocity.x = kInf; },
         XR_ERROR_VALIDATION_FAILURE},
        {"null space", [](PoseInfo& i) { i.space = XR_NULL_HANDLE; }, XR_ERROR_HANDLE_INVALID},
        {"zero time", [](PoseInfo& i) { i.time = 0; }, XR_ERROR_TIME_INVALID},
    };
    for (const XrPhysicalColliderPHYSHAND collider : {box_, dynamic_, kinematic_}) {
        for (const auto& c : cases) {
            SCOPED_TRACE(c.name);
            PoseInfo info = valid;
            c.change(info);
            EXPECT_EQ(api().set_pose(collider, &info), c.expected);
        }
    }
    // Only kinematic colliders follow targets.
    PoseInfo target = valid;
    target.teleport = XR_FALSE;
    EXPECT_EQ(api().set_pose(box_, &target), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(api().set_pose(dynamic_, &target), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(api().set_pose(kinematic_, &target), XR_SUCCESS);
    // Nothing moved the static box.
    EXPECT_NEAR(locate_collider(box_, time_).pose.position.x, 0.0f, 1e-6);
}

TEST_F(Validation, LocateCollidersRejectsBadInputAndWritesNothing) {
    std::vector<XrPhysicalColliderLocationPHYSHAND> out;
    EXPECT_EQ(locate_colliders({box_}, stage_, time_, out, bogus_handle<XrSession>()),
              XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(locate_colliders({box_}, stage_, time_, out, dead_session_), XR_ERROR_HANDLE_INVALID);
    // A collider of another session, or destroyed, is unknown to this one; the others in
    // the list are left unwritten.
    EXPECT_EQ(locate_colliders({box_, other_collider_}, stage_, time_, out),
              XR_ERROR_HANDLE_INVALID);
    EXPECT_TRUE(std::isnan(out[0].pose.position.x));
    EXPECT_EQ(locate_colliders({box_, dead_collider_}, stage_, time_, out),
              XR_ERROR_HANDLE_INVALID);
    EXPECT_TRUE(std::isnan(out[0].pose.position.x));
    EXPECT_EQ(locate_colliders({XR_NULL_HANDLE}, stage_, time_, out), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(locate_colliders({box_}, XR_NULL_HANDLE, time_, out), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(locate_colliders({box_}, stage_, 0, out), XR_ERROR_TIME_INVALID);
    EXPECT_EQ(locate_colliders({}, stage_, time_, out), XR_SUCCESS);
    // And the other session's collider is its own.
    EXPECT_EQ(locate_colliders({other_collider_}, other_stage_, time_, out, other_session_),
              XR_SUCCESS);

    XrPhysicalColliderLocationPHYSHAND location{};
    auto info =
        xr<XrPhysicalCollidersLocateInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND);
    info.baseSpace = stage_;
    info.time = time_;
    info.colliderCount = 1;
    info.colliders = &box_;
    auto locations =
        xr<XrPhysicalColliderLocationsPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND);
    locations.locationCount = 1;
    locations.locations = &location;
    const auto call = [&](const XrPhysicalCollidersLocateInfoPHYSHAND* i,
                          XrPhysicalColliderLocationsPHYSHAND* l) {
        return api().locate_colliders(session_, i, l);
    };
    EXPECT_EQ(call(&info, &locations), XR_SUCCESS);
    EXPECT_EQ(call(nullptr, &locations), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(call(&info, nullptr), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(api().locate_colliders(XR_NULL_HANDLE, &info, &locations), XR_ERROR_HANDLE_INVALID);

    auto bad_info = info;
    bad_info.type = XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND;
    EXPECT_EQ(call(&bad_info, &locations), XR_ERROR_VALIDATION_FAILURE);
    bad_info = info;
    bad_info.colliders = nullptr;
    EXPECT_EQ(call(&bad_info, &locations), XR_ERROR_VALIDATION_FAILURE);
    bad_info = info;
    bad_info.colliderCount = 2;  // locationCount stays 1
    EXPECT_EQ(call(&bad_info, &locations), XR_ERROR_VALIDATION_FAILURE);

    auto bad_locations = locations;
    bad_locations.type = XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND;
    EXPECT_EQ(call(&info, &bad_locations), XR_ERROR_VALIDATION_FAILURE);
    bad_locations = locations;
    bad_locations.locations = nullptr;
    EXPECT_EQ(call(&info, &bad_locations), XR_ERROR_VALIDATION_FAILURE);
    bad_locations = locations;
    bad_locations.locationCount = 0;
    EXPECT_EQ(call(&info, &bad_locations), XR_ERROR_VALIDATION_FAILURE);
}

TEST_F(Validation, SetHandDriveRejectsBadInput) {
    auto valid = xr<DriveInfo>(XR_TYPE_HAND_DRIVE_INFO_PHYSHAND);
    EXPECT_EQ(api().set_drive(XR_NULL_HANDLE, &valid), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().set_drive(bogus_handle<XrSession>(), &valid), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().set_drive(dead_session_, &valid), XR_ERROR_HANDLE_INVALID);
    EXPECT_EQ(api().set_drive(session_, nullptr), XR_ERROR_VALIDATION_FAILURE);
    const std::vector<Case<DriveInfo>> cases = {
        {"wrong type", [](DriveInfo& i) { i.type = XR_TYPE_SESSION_BEGIN_INFO; },
         XR_ERROR_VALIDATION_FAILURE},
        {"drive kind 5", [](DriveInfo& i) { i.drive = XrHandDriveKindPHYSHAND(5); },
         XR_ERROR_VALIDATION_FAILURE},
        {"drive kind -1", [](DriveInfo& i) { set_raw(i.drive, -1); }, XR_ERROR_VALIDATION_FAILURE},
        {"drive kind max", [](DriveInfo& i) { i.drive = XR_HAND_DRIVE_KIND_MAX_ENUM_PHYSHAND; },
         XR_ERROR_VALIDATION_FAILURE},
        {"negative stiffness", [](DriveInfo& i) { i.stiffness = -1.0f; },
         XR_ERROR_VALIDATION_FAILURE},
        {"NaN stiffness", [](DriveInfo& i) { i.stiffness = kNaN; }, XR_ERROR_VALIDATION_FAILURE},
        {"infinite damping", [](DriveInfo& i) { i.damping = kInf; }, XR_ERROR_VALIDATION_FAILURE},
        {"negative force limit", [](DriveInfo& i) { i.forceLimit = -5.0f; },
         XR_ERROR_VALIDATION_FAILURE},
        {"65 substeps", [](DriveInfo& i) { i.substeps = 65; }, XR_ERROR_VALIDATION_FAILURE},
        {"huge substeps", [](DriveInfo& i) { i.substeps = 0xFFFFFFFFu; },
         XR_ERROR_VALIDATION_FAILURE},
        {"64 substeps", [](DriveInfo& i) { i.substeps = 64; }, XR_SUCCESS},
        {"paper", [](DriveInfo& i) { i.drive = XR_HAND_DRIVE_KIND_PAPER_PHYSHAND; }, XR_SUCCESS},
        {"implicit", [](DriveInfo& i) { i.drive = XR_HAND_DRIVE_KIND_IMPLICIT_PHYSHAND; },
         XR_SUCCESS},
        {"jointed", [](DriveInfo& i) { i.drive = XR_HAND_DRIVE_KIND_JOINTED_PHYSHAND; },
         XR_SUCCESS},
        {"bones with gains",
         [](DriveInfo& i) {
             i.drive = XR_HAND_DRIVE_KIND_BONES_PHYSHAND;
             i.stiffness = 5000.0f;
             i.damping = 50.0f;
             i.forceLimit = 10.0f;
             i.substeps = 3;
         },
         XR_SUCCESS},
        {"default", [](DriveInfo&) {}, XR_SUCCESS},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        DriveInfo info = valid;
        c.change(info);
        EXPECT_EQ(api().set_drive(session_, &info), c.expected);
    }
}

// The layer checks what it adds to xrLocateHandJointsEXT before anything reaches the
// runtime.
TEST_F(Validation, LocateHandJointsRejectsBadInput) {
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const auto locate_fn = function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT");
    HandJoints hand;
    ASSERT_EQ(locate(right, stage_, time_, hand), XR_SUCCESS);  // sets the chain up
    auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
    info.baseSpace = stage_;
    info.time = time_;
    const auto expect_result = [&](const char* what, XrResult expected, XrHandTrackerEXT tracker) {
        SCOPED_TRACE(what);
        EXPECT_EQ(locate_fn(tracker, &info, &hand.locations), expected);
        // Whatever happened, the app's chain is as it was.
        EXPECT_EQ(hand.locations.next, &hand.velocities);
        EXPECT_EQ(hand.velocities.next, &hand.physical);
    };
    expect_result("valid", XR_SUCCESS, right);
    expect_result("null tracker", XR_ERROR_HANDLE_INVALID, XR_NULL_HANDLE);
    expect_result("bogus tracker", XR_ERROR_HANDLE_INVALID, bogus_handle<XrHandTrackerEXT>());

    hand.locations.jointCount = 25;
    expect_result("25 joints", XR_ERROR_VALIDATION_FAILURE, right);
    hand.locations.jointCount = kJointCount;
    hand.locations.jointLocations = nullptr;
    expect_result("no joint array", XR_ERROR_VALIDATION_FAILURE, right);
    hand.locations.jointLocations = hand.joints.data();
    hand.locations.type = XR_TYPE_HAND_JOINT_VELOCITIES_EXT;
    expect_result("wrong locations type", XR_ERROR_VALIDATION_FAILURE, right);
    hand.locations.type = XR_TYPE_HAND_JOINT_LOCATIONS_EXT;
    info.type = XR_TYPE_HAND_JOINT_LOCATIONS_EXT;
    expect_result("wrong info type", XR_ERROR_VALIDATION_FAILURE, right);
    info.type = XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT;
    hand.velocities.jointCount = 25;
    expect_result("25 velocities", XR_ERROR_VALIDATION_FAILURE, right);
    hand.velocities.jointCount = kJointCount;
    hand.velocities.jointVelocities = nullptr;
    expect_result("no velocity array", XR_ERROR_VALIDATION_FAILURE, right);
    hand.velocities.jointVelocities = hand.joint_velocities.data();
    hand.physical.jointCount = 25;
    expect_result("25 physical joints", XR_ERROR_VALIDATION_FAILURE, right);
    hand.physical.jointCount = 27;
    expect_result("27 physical joints", XR_ERROR_VALIDATION_FAILURE, right);
    hand.physical.jointCount = kJointCount;
    // Its arrays are optional.
    hand.physical.ghostPoses = nullptr;
    hand.physical.inContact = nullptr;
    hand.physical.springForce = nullptr;
    expect_result("physical state without arrays", XR_SUCCESS, right);
    EXPECT_EQ(locate_fn(right, nullptr, &hand.locations), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(locate_fn(right, &info, nullptr), XR_ERROR_VALIDATION_FAILURE);

    // A tracker of another session is the other session's: its hand is located there.
    const XrHandTrackerEXT other = hand_tracker(XR_HAND_RIGHT_EXT, other_session_);
    HandJoints other_hand;
    EXPECT_EQ(locate(other, other_stage_, time_, other_hand), XR_SUCCESS);
    EXPECT_TRUE(other_hand.locations.isActive);
}

}  // namespace
}  // namespace physhand::layer_test
