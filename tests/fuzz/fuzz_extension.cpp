// XR_PHYSHAND_physical_hands from the application's side, through the real loader, the
// layer and the simulated runtime. One instance and one running headless session serve
// every input (creating them per input would leave little time for the calls). Each input
// decodes into a sequence of extension calls: colliders created with any shape, motion,
// size, pose and mass (NaN, Inf, huge and zero included), moved, teleported, located and
// destroyed through live, stale and made-up handles, their impulses read; hand drives set;
// hands located; contact reporting set and contact events read. Every
// answer must be a result the extension documents, and all a successful locate returns
// must be finite. Each input starts from the default drive and destroys what it created,
// so that a crashing input replays on its own; only the simulation's clock and hands carry
// over. The runtime plays hands.json: both hands held still where the seed inputs aim.

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

#include "sim_app.h"

namespace {

using physhand::test::SimApp;
using physhand::test::xr;

constexpr int kMaxCallsPerInput = 64;
constexpr std::size_t kMaxVertices = 32;
constexpr std::size_t kMaxIndices = 48;
constexpr std::size_t kMaxLocated = 8;
constexpr std::uint32_t kJoints = XR_HAND_JOINT_COUNT_EXT;
// Upper ends of the plausible values: metres, m/s, rad/s, N/m, N*s/m, N.
constexpr float kReach = 2.0f, kSpeed = 5.0f, kSpin = 20.0f;
constexpr float kStiffness = 5000.0f, kDamping = 100.0f, kForce = 100.0f;
// A variant byte at or above this picks one of an operation's malformed calls.
constexpr std::uint8_t kFirstFlaw = 224;

constexpr std::array<float, 11> kSpecialFloats = {
    0.0f,
    -0.0f,
    std::numeric_limits<float>::quiet_NaN(),
    std::numeric_limits<float>::infinity(),
    -std::numeric_limits<float>::infinity(),
    std::numeric_limits<float>::max(),
    std::numeric_limits<float>::lowest(),
    std::numeric_limits<float>::min(),
    std::numeric_limits<float>::denorm_min(),
    1e-30f,
    1e30f,
};
constexpr std::array<XrTime, 3> kInvalidTimes = {0, -1, std::numeric_limits<XrTime>::min()};
constexpr std::array<XrPhysicalColliderShapePHYSHAND, 9> kShapes = {
    XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,      XR_PHYSICAL_COLLIDER_SHAPE_SPHERE_PHYSHAND,
    XR_PHYSICAL_COLLIDER_SHAPE_CAPSULE_PHYSHAND,  XR_PHYSICAL_COLLIDER_SHAPE_CYLINDER_PHYSHAND,
    XR_PHYSICAL_COLLIDER_SHAPE_CONVEX_PHYSHAND,   XR_PHYSICAL_COLLIDER_SHAPE_MESH_PHYSHAND,
    XR_PHYSICAL_COLLIDER_SHAPE_PLANE_PHYSHAND,    static_cast<XrPhysicalColliderShapePHYSHAND>(0),
    XR_PHYSICAL_COLLIDER_SHAPE_MAX_ENUM_PHYSHAND,
};
constexpr std::array<XrPhysicalColliderMotionPHYSHAND, 5> kMotions = {
    XR_PHYSICAL_COLLIDER_MOTION_STATIC_PHYSHAND,   XR_PHYSICAL_COLLIDER_MOTION_KINEMATIC_PHYSHAND,
    XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND,  static_cast<XrPhysicalColliderMotionPHYSHAND>(0),
    XR_PHYSICAL_COLLIDER_MOTION_MAX_ENUM_PHYSHAND,
};
constexpr std::array<XrHandDriveKindPHYSHAND, 7> kDrives = {
    XR_HAND_DRIVE_KIND_DEFAULT_PHYSHAND,  XR_HAND_DRIVE_KIND_PAPER_PHYSHAND,
    XR_HAND_DRIVE_KIND_IMPLICIT_PHYSHAND, XR_HAND_DRIVE_KIND_BONES_PHYSHAND,
    XR_HAND_DRIVE_KIND_JOINTED_PHYSHAND,  static_cast<XrHandDriveKindPHYSHAND>(5),
    XR_HAND_DRIVE_KIND_MAX_ENUM_PHYSHAND,
};

[[noreturn]] void fail(const char* call, const char* what, XrResult result) {
    std::fprintf(stderr, "fuzz_extension: %s: %s (XrResult %d)\n", call, what, result);
    std::abort();
}

// The results physhand_physical_hands.h documents; the runtime's own answers to the calls
// made here are among them. XR_ERROR_RUNTIME_FAILURE is left out on purpose: this session
// is set up, so it could only come from an exception inside the layer.
void expect_documented(XrResult result, const char* call) {
    switch (result) {
        case XR_SUCCESS:
        case XR_ERROR_VALIDATION_FAILURE:
        case XR_ERROR_POSE_INVALID:
        case XR_ERROR_TIME_INVALID:
        case XR_ERROR_HANDLE_INVALID:
        case XR_ERROR_SIZE_INSUFFICIENT:
            return;
        default:
            fail(call, "undocumented result", result);
    }
}

bool finite(float f) {
    return std::isfinite(f);
}
bool finite(const XrVector3f& v) {
    return finite(v.x) && finite(v.y) && finite(v.z);
}
bool finite(const XrPosef& p) {
    const XrQuaternionf& q = p.orientation;
    return finite(p.position) && finite(q.x) && finite(q.y) && finite(q.z) && finite(q.w);
}

// Reads an input front to back. Past its end every byte reads as zero, so any input
// decodes, and zero bytes decode to the plainest valid choice.
class Input {
  public:
    Input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    bool done() const { return at_ >= size_; }
    std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
    template <typename T>
    T raw() {
        std::array<std::uint8_t, sizeof(T)> bytes;
        for (std::uint8_t& b : bytes) b = byte();
        T value;
        std::memcpy(&value, bytes.data(), sizeof(T));
        return value;
    }
    template <typename T, std::size_t N>
    T pick(const std::array<T, N>& table) {
        return table[byte() % N];
    }
    // Mostly a plausible value up to `scale` (from -scale when `is_signed`), else a value
    // that breaks arithmetic (NaN, Inf, huge, zero, denormal), else any float at all.
    float real(float scale, bool is_signed) {
        const std::uint8_t kind = byte();
        if (kind < 192) {
            const std::uint8_t b = byte();
            return is_signed ? static_cast<std::int8_t>(b) / 128.0f * scale
                             : (b + 1) / 256.0f * scale;
        }
        if (kind < 240) return pick(kSpecialFloats);
        return raw<float>();
    }
    float length() { return real(1.0f, false); }
    XrVector3f vector(float scale) {
        return {real(scale, true), real(scale, true), real(scale, true)};
    }
    // Mostly identity or unit orientations; else the four numbers as they came.
    XrPosef pose() {
        XrPosef pose{};
        pose.position = vector(kReach);
        const std::uint8_t kind = byte();
        if (kind < 128) {
            pose.orientation.w = 1.0f;
            return pose;
        }
        XrQuaternionf& q = pose.orientation;
        q = {real(1.0f, true), real(1.0f, true), real(1.0f, true), real(1.0f, true)};
        const float norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
        if (kind < kFirstFlaw && std::isfinite(norm) && norm > 0.0f) {
            q = {q.x / norm, q.y / norm, q.z / norm, q.w / norm};
        }
        return pose;
    }
    // Which malformed call (0 .. count-1) the variant byte asks for; -1 for a well-formed one.
    int flaw(int count) {
        const std::uint8_t variant = byte();
        return variant < kFirstFlaw ? -1 : variant % count;
    }
    template <typename Handle>
    Handle made_up_handle() {
        return reinterpret_cast<Handle>(static_cast<std::uintptr_t>(raw<std::uint64_t>()));
    }

  private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t at_ = 0;
};

class Harness {
  public:
    Harness()
        : app_({.layer = true, .extension = true, .scene = PHYSHAND_FUZZ_SCENE}),
          create_(app_.function<PFN_xrCreatePhysicalColliderPHYSHAND>(
              "xrCreatePhysicalColliderPHYSHAND")),
          destroy_(app_.function<PFN_xrDestroyPhysicalColliderPHYSHAND>(
              "xrDestroyPhysicalColliderPHYSHAND")),
          set_pose_(app_.function<PFN_xrSetPhysicalColliderPosePHYSHAND>(
              "xrSetPhysicalColliderPosePHYSHAND")),
          locate_colliders_(app_.function<PFN_xrLocatePhysicalCollidersPHYSHAND>(
              "xrLocatePhysicalCollidersPHYSHAND")),
          set_drive_(app_.function<PFN_xrSetHandDrivePHYSHAND>("xrSetHandDrivePHYSHAND")),
          set_reporting_(app_.function<PFN_xrSetPhysicalContactReportingPHYSHAND>(
              "xrSetPhysicalContactReportingPHYSHAND")),
          get_events_(app_.function<PFN_xrGetPhysicalContactEventsPHYSHAND>(
              "xrGetPhysicalContactEventsPHYSHAND")),
          locate_hand_(app_.function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")) {
        const XrFrameState frame = app_.frame();
        now_ = frame.predictedDisplayTime;
        period_ = frame.predictedDisplayPeriod;
    }

    void run(Input& in) {
        reset_drive();
        for (int call = 0; call < kMaxCallsPerInput && !in.done(); ++call) {
            switch (in.byte() % 9) {
                case 0:
                    create(in);
                    break;
                case 1:
                    destroy(in);
                    break;
                case 2:
                    set_pose(in);
                    break;
                case 3:
                    locate_colliders(in);
                    break;
                case 4:
                    locate_hand(in);
                    break;
                case 5:
                    set_drive(in);
                    break;
                case 6:
                    set_reporting(in);
                    break;
                case 7:
                    get_events(in);
                    break;
                default:
                    now_ += period_;
                    break;
            }
        }
        for (const XrPhysicalColliderPHYSHAND collider : live_) {
            const XrResult result = destroy_(collider);
            if (result != XR_SUCCESS) fail("xrDestroyPhysicalColliderPHYSHAND", "live", result);
        }
        live_.clear();
        stale_.clear();
    }

  private:
    // ---- arguments that need the session's handles or clock -----------------------------

    XrSession session(Input& in) {
        const std::uint8_t kind = in.byte();
        if (kind < kFirstFlaw) return app_.session();
        return kind % 2 == 0 ? XR_NULL_HANDLE : in.made_up_handle<XrSession>();
    }

    XrSpace space(Input& in) {
        switch (in.byte() % 5) {
            case 0:
                return app_.space(XR_REFERENCE_SPACE_TYPE_STAGE);
            case 1:
                return app_.space(XR_REFERENCE_SPACE_TYPE_LOCAL);
            case 2:
                return app_.space(XR_REFERENCE_SPACE_TYPE_VIEW);
            case 3:
                return XR_NULL_HANDLE;
            default:
                return in.made_up_handle<XrSpace>();
        }
    }

    XrPhysicalColliderPHYSHAND collider_of(Input& in) {
        const std::uint8_t kind = in.byte() % 4;
        const std::uint8_t which = in.byte();
        if (kind == 0 && !live_.empty()) return live_[which % live_.size()];
        if (kind == 1 && !stale_.empty()) return stale_[which % stale_.size()];
        if (kind == 2) return in.made_up_handle<XrPhysicalColliderPHYSHAND>();
        return XR_NULL_HANDLE;
    }

    // A time for calls that only locate spaces at it: anything goes.
    XrTime any_time(Input& in) {
        switch (in.byte() % 3) {
            case 0:
                return now_;
            case 1:
                return in.pick(kInvalidTimes);
            default:
                return in.raw<XrTime>();
        }
    }

    // A time for calls that advance the simulation to it. Never more than a few seconds
    // ahead: one far-future time would stop the simulation for every later input.
    XrTime frame_time(Input& in) {
        XrTime time = now_;
        switch (in.byte() % 5) {
            case 0:
                time = now_ + period_;
                break;
            case 1:
                break;  // this frame again
            case 2:
                time = now_ + in.raw<std::uint32_t>();
                break;
            case 3:
                time = now_ - period_ * (1 + in.byte());  // the past, perhaps before time 0
                break;
            default:
                return in.pick(kInvalidTimes);
        }
        now_ = std::max(now_, time);
        return time;
    }

    bool is_live(XrPhysicalColliderPHYSHAND collider) const {
        return std::find(live_.begin(), live_.end(), collider) != live_.end();
    }

    // ---- the calls ----------------------------------------------------------------------

    void create(Input& in) {
        const int flaw = in.flaw(4);
        auto info = xr<XrPhysicalColliderCreateInfoPHYSHAND>(
            XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND);
        info.shape = in.pick(kShapes);
        info.motion = in.pick(kMotions);
        info.halfExtents = {in.length(), in.length(), in.length()};
        info.radius = in.length();
        info.halfHeight = in.length();
        std::vector<XrVector3f> vertices(in.byte() % (kMaxVertices + 1));
        for (XrVector3f& v : vertices) v = in.vector(kReach);
        std::vector<std::uint32_t> indices(in.byte() % (kMaxIndices + 1));
        for (std::uint32_t& index : indices) {
            const std::uint8_t b = in.byte();
            index = b < kFirstFlaw ? b % std::max<std::size_t>(vertices.size(), 1)
                                   : in.raw<std::uint32_t>();
        }
        info.vertexCount = static_cast<std::uint32_t>(vertices.size());
        info.vertices = flaw == 3 ? nullptr : vertices.data();
        info.indexCount = static_cast<std::uint32_t>(indices.size());
        info.indices = flaw == 3 ? nullptr : indices.data();
        info.planeNormal = in.vector(1.0f);
        info.planeOffset = in.real(kReach, true);
        info.mass = in.length();
        info.friction = in.length();
        info.restitution = in.length();
        info.space = space(in);
        info.pose = in.pose();
        info.time = any_time(in);
        if (flaw == 0) info.type = XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND;
        XrPhysicalColliderPHYSHAND collider = XR_NULL_HANDLE;
        const XrResult result =
            create_(session(in), flaw == 1 ? nullptr : &info, flaw == 2 ? nullptr : &collider);
        expect_documented(result, "xrCreatePhysicalColliderPHYSHAND");
        if (result != XR_SUCCESS) return;
        if (collider == XR_NULL_HANDLE || is_live(collider)) {
            fail("xrCreatePhysicalColliderPHYSHAND", "no new handle", result);
        }
        live_.push_back(collider);
    }

    void destroy(Input& in) {
        const XrPhysicalColliderPHYSHAND collider = collider_of(in);
        const XrResult result = destroy_(collider);
        expect_documented(result, "xrDestroyPhysicalColliderPHYSHAND");
        // Live handles, and only they, are destroyed.
        if ((result == XR_SUCCESS) != is_live(collider)) {
            fail("xrDestroyPhysicalColliderPHYSHAND", "live handles only", result);
        }
        if (result != XR_SUCCESS) return;
        std::erase(live_, collider);
        stale_.push_back(collider);
    }

    void set_pose(Input& in) {
        const int flaw = in.flaw(2);
        const XrPhysicalColliderPHYSHAND target = collider_of(in);
        auto info =
            xr<XrPhysicalColliderPoseInfoPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND);
        info.space = space(in);
        info.time = any_time(in);
        info.pose = in.pose();
        info.teleport = in.byte() % 2;
        info.linearVelocity = in.vector(kSpeed);
        info.angularVelocity = in.vector(kSpin);
        if (flaw == 0) info.type = XR_TYPE_PHYSICAL_COLLIDER_CREATE_INFO_PHYSHAND;
        expect_documented(set_pose_(target, flaw == 1 ? nullptr : &info),
                          "xrSetPhysicalColliderPosePHYSHAND");
    }

    void locate_colliders(Input& in) {
        const int flaw = in.flaw(4);
        std::vector<XrPhysicalColliderPHYSHAND> colliders(in.byte() % (kMaxLocated + 1));
        for (XrPhysicalColliderPHYSHAND& c : colliders) c = collider_of(in);
        auto info = xr<XrPhysicalCollidersLocateInfoPHYSHAND>(
            XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND);
        info.baseSpace = space(in);
        info.time = frame_time(in);
        info.colliderCount = static_cast<std::uint32_t>(colliders.size());
        info.colliders = flaw == 1 ? nullptr : colliders.data();
        // One spare, so that a count one too large still points at enough memory.
        std::vector<XrPhysicalColliderLocationPHYSHAND> out(colliders.size() + 1);
        auto locations =
            xr<XrPhysicalColliderLocationsPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND);
        locations.locationCount = info.colliderCount + (flaw == 2 ? 1 : 0);
        locations.locations = flaw == 1 ? nullptr : out.data();
        if (flaw == 0) info.type = XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND;
        if (flaw == 3) locations.type = XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND;
        // Bit 0: the impulses chained; bit 1: one too many of them; bit 2: no array.
        const std::uint8_t chain = in.byte();
        std::vector<XrPhysicalColliderImpulsePHYSHAND> impulse_array(colliders.size() + 1);
        auto impulses =
            xr<XrPhysicalColliderImpulsesPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_IMPULSES_PHYSHAND);
        impulses.impulseCount = info.colliderCount + (chain & 2 ? 1 : 0);
        impulses.impulses = chain & 4 ? nullptr : impulse_array.data();
        if (chain & 1) locations.next = &impulses;
        const XrResult result = locate_colliders_(session(in), &info, &locations);
        expect_documented(result, "xrLocatePhysicalCollidersPHYSHAND");
        if (result != XR_SUCCESS) return;
        for (const XrPhysicalColliderLocationPHYSHAND& location : out) {
            if (!finite(location.pose) || !finite(location.linearVelocity) ||
                !finite(location.angularVelocity)) {
                fail("xrLocatePhysicalCollidersPHYSHAND", "non-finite location", result);
            }
        }
        for (const XrPhysicalColliderImpulsePHYSHAND& impulse : impulse_array) {
            if (!finite(impulse.linearImpulse) || !finite(impulse.angularImpulse)) {
                fail("xrLocatePhysicalCollidersPHYSHAND", "non-finite impulse", result);
            }
        }
    }

    void set_reporting(Input& in) {
        const int flaw = in.flaw(2);
        auto info = xr<XrPhysicalContactReportingInfoPHYSHAND>(
            XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND);
        info.persistEvents = in.byte() % 2;
        info.colliderContacts = in.byte() % 2;
        // Mostly small buffers, some over the limit of 65536.
        info.eventCapacity = in.byte() < kFirstFlaw ? in.byte() : in.raw<std::uint32_t>();
        if (flaw == 0) info.type = XR_TYPE_HAND_DRIVE_INFO_PHYSHAND;
        expect_documented(set_reporting_(session(in), flaw == 1 ? nullptr : &info),
                          "xrSetPhysicalContactReportingPHYSHAND");
    }

    void get_events(Input& in) {
        const int flaw = in.flaw(4);
        auto info = xr<XrPhysicalContactEventsGetInfoPHYSHAND>(
            XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND);
        info.baseSpace = space(in);
        info.time = any_time(in);
        std::vector<XrPhysicalContactEventPHYSHAND> event_array(in.byte() % 64);
        auto events = xr<XrPhysicalContactEventsPHYSHAND>(XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND);
        events.eventCapacityInput = static_cast<std::uint32_t>(event_array.size());
        events.events = flaw == 2 ? nullptr : event_array.data();
        if (flaw == 0) info.type = XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND;
        if (flaw == 3) events.type = XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND;
        const XrResult result = get_events_(session(in), flaw == 1 ? nullptr : &info, &events);
        expect_documented(result, "xrGetPhysicalContactEventsPHYSHAND");
        if (result != XR_SUCCESS || events.eventCapacityInput == 0) return;
        if (events.eventCountOutput > events.eventCapacityInput) {
            fail("xrGetPhysicalContactEventsPHYSHAND", "more events than room", result);
        }
        for (std::uint32_t i = 0; i < events.eventCountOutput; ++i) {
            const XrPhysicalContactEventPHYSHAND& e = event_array[i];
            if (!finite(e.point) || !finite(e.normal) || !finite(e.linearImpulse) ||
                !finite(e.impulse) || !finite(e.approachSpeed)) {
                fail("xrGetPhysicalContactEventsPHYSHAND", "non-finite event", result);
            }
        }
    }

    void locate_hand(Input& in) {
        const XrHandEXT hand = in.byte() % 2 == 0 ? XR_HAND_RIGHT_EXT : XR_HAND_LEFT_EXT;
        const std::uint8_t chain = in.byte();
        auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
        info.baseSpace = space(in);
        info.time = frame_time(in);

        std::array<XrHandJointLocationEXT, kJoints> joints{};
        std::array<XrHandJointVelocityEXT, kJoints> joint_velocities{};
        std::array<XrPosef, kJoints> ghosts{};
        std::array<XrBool32, kJoints> contacts{};
        std::array<float, kJoints> forces{};
        std::array<XrHandCollisionShapePHYSHAND, kJoints> shape_array{};
        auto locations = xr<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
        locations.jointCount = kJoints;
        locations.jointLocations = joints.data();
        auto velocities = xr<XrHandJointVelocitiesEXT>(XR_TYPE_HAND_JOINT_VELOCITIES_EXT);
        velocities.jointCount = kJoints;
        velocities.jointVelocities = joint_velocities.data();
        auto physical =
            xr<XrHandJointsPhysicalStatePHYSHAND>(XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND);
        physical.jointCount = chain & 4 ? kJoints - 1 : kJoints;
        const bool arrays = (chain & 8) == 0;
        physical.ghostPoses = arrays ? ghosts.data() : nullptr;
        physical.inContact = arrays ? contacts.data() : nullptr;
        physical.springForce = arrays ? forces.data() : nullptr;
        auto shapes = xr<XrHandCollisionShapesPHYSHAND>(XR_TYPE_HAND_COLLISION_SHAPES_PHYSHAND);
        // Bits 5 and 6: a capacity of none, too few, all, or all with no array.
        const std::uint8_t capacity = (chain >> 5) & 3;
        shapes.shapeCapacityInput = capacity == 0 ? 0 : capacity == 1 ? 5 : kJoints;
        shapes.shapes = capacity == 3 ? nullptr : shape_array.data();
        // Bit 0 chains the velocities, bit 1 the layer's physical state, bit 4 its shapes, in
        // front of them.
        void* next = nullptr;
        if (chain & 1) next = &velocities;
        if (chain & 2) {
            physical.next = next;
            next = &physical;
        }
        if (chain & 16) {
            shapes.next = next;
            next = &shapes;
        }
        locations.next = next;

        const XrResult result = locate_hand_(app_.hand_tracker(hand), &info, &locations);
        expect_documented(result, "xrLocateHandJointsEXT");
        if (result != XR_SUCCESS) return;
        for (std::uint32_t i = 0; i < kJoints; ++i) {
            if (!finite(joints[i].pose) || !finite(joints[i].radius) ||
                !finite(joint_velocities[i].linearVelocity) ||
                !finite(joint_velocities[i].angularVelocity) || !finite(ghosts[i]) ||
                !finite(forces[i])) {
                fail("xrLocateHandJointsEXT", "non-finite joint", result);
            }
        }
        if ((chain & 16) == 0 || shapes.shapeCapacityInput == 0) return;
        if (shapes.shapeCountOutput > shapes.shapeCapacityInput) {
            fail("xrLocateHandJointsEXT", "more shapes than room", result);
        }
        for (std::uint32_t i = 0; i < shapes.shapeCountOutput; ++i) {
            const XrHandCollisionShapePHYSHAND& shape = shape_array[i];
            if (!finite(shape.pose) || !finite(shape.size)) {
                fail("xrLocateHandJointsEXT", "non-finite shape", result);
            }
        }
    }

    void set_drive(Input& in) {
        const int flaw = in.flaw(2);
        auto info = xr<XrHandDriveInfoPHYSHAND>(XR_TYPE_HAND_DRIVE_INFO_PHYSHAND);
        info.drive = in.pick(kDrives);
        info.stiffness = in.real(kStiffness, false);
        info.damping = in.real(kDamping, false);
        info.forceLimit = in.real(kForce, false);
        // Mostly 0 (the drive's own) to a little over the limit of 64.
        info.substeps = in.byte() < kFirstFlaw ? in.byte() % 80 : in.raw<std::uint32_t>();
        if (flaw == 0) info.type = XR_TYPE_PHYSICAL_COLLIDER_POSE_INFO_PHYSHAND;
        expect_documented(set_drive_(session(in), flaw == 1 ? nullptr : &info),
                          "xrSetHandDrivePHYSHAND");
    }

    void reset_drive() {
        auto info = xr<XrHandDriveInfoPHYSHAND>(XR_TYPE_HAND_DRIVE_INFO_PHYSHAND);
        info.drive = XR_HAND_DRIVE_KIND_DEFAULT_PHYSHAND;
        const XrResult result = set_drive_(app_.session(), &info);
        if (result != XR_SUCCESS) fail("xrSetHandDrivePHYSHAND", "default drive", result);
    }

    const SimApp app_;
    const PFN_xrCreatePhysicalColliderPHYSHAND create_;
    const PFN_xrDestroyPhysicalColliderPHYSHAND destroy_;
    const PFN_xrSetPhysicalColliderPosePHYSHAND set_pose_;
    const PFN_xrLocatePhysicalCollidersPHYSHAND locate_colliders_;
    const PFN_xrSetHandDrivePHYSHAND set_drive_;
    const PFN_xrSetPhysicalContactReportingPHYSHAND set_reporting_;
    const PFN_xrGetPhysicalContactEventsPHYSHAND get_events_;
    const PFN_xrLocateHandJointsEXT locate_hand_;
    XrTime now_ = 0;  // the latest time the simulation was advanced to, or the first frame's
    XrTime period_ = 0;
    std::vector<XrPhysicalColliderPHYSHAND> live_;   // created by this input, not destroyed
    std::vector<XrPhysicalColliderPHYSHAND> stale_;  // destroyed by this input
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static Harness harness;
    Input input(data, size);
    harness.run(input);
    return 0;
}
