// Reference spaces and views. STAGE is the scene frame; the head never moves: it stands
// at eye height above the STAGE origin looking down -Z, and LOCAL starts there too.
// PHYSHAND_SIM_HEAD_POSITION=X,Y,Z (metres in STAGE, read once) puts it elsewhere, a seated
// viewer close to a table, say; PHYSHAND_SIM_HEAD_PITCH_DEG (read once) tilts the head, VIEW
// and the eyes (not LOCAL, which stays level) that many degrees up, or down when negative, so
// a scene on a table can be watched.

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <optional>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

constexpr auto kReferenceSpaces = std::to_array<XrReferenceSpaceType>(
    {XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL, XR_REFERENCE_SPACE_TYPE_STAGE});

constexpr double kHalfEyeDistance = 0.032;
constexpr float kHalfFov = static_cast<float>(std::numbers::pi / 4);  // a 90 degree field

bool is_supported_reference_space(XrReferenceSpaceType type) {
    return std::find(kReferenceSpaces.begin(), kReferenceSpaces.end(), type) !=
           kReferenceSpaces.end();
}

constexpr double kMaxHeadOffset = 100.0;  // metres from the STAGE origin, along each axis

// `text` as X,Y,Z, each a number within kMaxHeadOffset; nullopt for anything else.
std::optional<Vec3> parse_position(const char* text) {
    Vec3 position;
    const char* at = text;
    for (int i = 0; i < 3; ++i) {
        char* end = nullptr;
        position[i] = std::strtod(at, &end);
        if (end == at || !(std::abs(position[i]) <= kMaxHeadOffset)) return std::nullopt;
        if (*end != (i < 2 ? ',' : '\0')) return std::nullopt;
        at = end + 1;
    }
    return position;
}

Pose head_in_stage() {
    static const Vec3 position = [] {
        const Vec3 standing(0, kEyeHeight, 0);
        const char* text = std::getenv("PHYSHAND_SIM_HEAD_POSITION");
        if (text == nullptr) return standing;
        const std::optional<Vec3> parsed = parse_position(text);
        if (!parsed) {
            std::fprintf(stderr,
                         "physhand simulated runtime: PHYSHAND_SIM_HEAD_POSITION=%s is not X,Y,Z "
                         "(three numbers, metres from -%g to %g); the head stands at 0,%g,0\n",
                         text, kMaxHeadOffset, kMaxHeadOffset, kEyeHeight);
            return standing;
        }
        return *parsed;
    }();
    return {position, Quat::Identity()};
}

Pose view_in_stage() {
    static const Quat pitch = [] {
        const char* text = std::getenv("PHYSHAND_SIM_HEAD_PITCH_DEG");
        char* end = nullptr;
        const double degrees = text == nullptr ? 0.0 : std::strtod(text, &end);
        if (text != nullptr && (*text == '\0' || *end != '\0' || !(std::abs(degrees) <= 90))) {
            std::fprintf(stderr,
                         "physhand simulated runtime: PHYSHAND_SIM_HEAD_PITCH_DEG=%s is not an "
                         "angle from -90 to 90; the head looks straight ahead\n",
                         text);
            return Quat::Identity();
        }
        return Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180, Vec3::UnitX()));
    }();
    return {head_in_stage().position, pitch};
}

// The origin of each reference space in STAGE.
Pose reference_in_stage(XrReferenceSpaceType type) {
    if (type == XR_REFERENCE_SPACE_TYPE_STAGE) return Pose{};
    return type == XR_REFERENCE_SPACE_TYPE_VIEW ? view_in_stage() : head_in_stage();
}

// The space and base space of a locate call: both live, of one session.
XrResult check_space_pair(Runtime& rt, XrSpace space, XrSpace base, const SpaceData** located,
                          const SpaceData** base_data) {
    *located = rt.spaces.find(space);
    *base_data = rt.spaces.find(base);
    if (*located == nullptr || *base_data == nullptr) return XR_ERROR_HANDLE_INVALID;
    return (*located)->session == (*base_data)->session ? XR_SUCCESS : XR_ERROR_VALIDATION_FAILURE;
}

}  // namespace

std::optional<Pose> space_in_stage(const SpaceData& space) {
    if (!space.reference) return std::nullopt;
    return reference_in_stage(*space.reference) * space.pose_in_reference;
}

Pose eye_in_stage(std::uint32_t view) {
    return view_in_stage() *
           Pose{Vec3(view == 0 ? -kHalfEyeDistance : kHalfEyeDistance, 0, 0), Quat::Identity()};
}

XrFovf eye_fov() {
    return {-kHalfFov, kHalfFov, kHalfFov, -kHalfFov};
}

XrResult xrEnumerateReferenceSpaces(XrSession session, uint32_t spaceCapacityInput,
                                    uint32_t* spaceCountOutput, XrReferenceSpaceType* spaces) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        return fill_array(spaceCapacityInput, spaceCountOutput, spaces,
                          static_cast<uint32_t>(kReferenceSpaces.size()),
                          [](XrReferenceSpaceType& out, uint32_t i) {
                              out = kReferenceSpaces[i];
                              return XR_SUCCESS;
                          });
    });
}

XrResult xrCreateReferenceSpace(XrSession session, const XrReferenceSpaceCreateInfo* createInfo,
                                XrSpace* space) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(createInfo, XR_TYPE_REFERENCE_SPACE_CREATE_INFO) || space == nullptr) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!is_supported_reference_space(createInfo->referenceSpaceType)) {
            return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
        }
        if (!is_valid_pose(createInfo->poseInReferenceSpace)) return XR_ERROR_POSE_INVALID;
        *space = rt.spaces.add(
            {session, createInfo->referenceSpaceType, from_xr(createInfo->poseInReferenceSpace)});
        return XR_SUCCESS;
    });
}

XrResult xrGetReferenceSpaceBoundsRect(XrSession session, XrReferenceSpaceType referenceSpaceType,
                                       XrExtent2Df* bounds) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (bounds == nullptr) return XR_ERROR_VALIDATION_FAILURE;
        if (!is_supported_reference_space(referenceSpaceType)) {
            return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
        }
        *bounds = {0.0f, 0.0f};
        return XR_SPACE_BOUNDS_UNAVAILABLE;
    });
}

XrResult xrLocateSpace(XrSpace space, XrSpace baseSpace, XrTime time, XrSpaceLocation* location) {
    return guarded([&](Runtime& rt) {
        const SpaceData* located = nullptr;
        const SpaceData* base = nullptr;
        if (XrResult result = check_space_pair(rt, space, baseSpace, &located, &base);
            XR_FAILED(result)) {
            return result;
        }
        if (!has_type(location, XR_TYPE_SPACE_LOCATION)) return XR_ERROR_VALIDATION_FAILURE;
        if (time <= 0) return XR_ERROR_TIME_INVALID;
        std::optional<Pose> space_pose = space_in_stage(*located);
        std::optional<Pose> base_pose = space_in_stage(*base);
        bool locatable = space_pose && base_pose;
        location->locationFlags = locatable ? kLocatedFlags : 0;
        location->pose = to_xr(locatable ? base_pose->inverse() * *space_pose : Pose{});
        // Every locatable space is fixed in the scene.
        if (auto* velocity =
                find_in_chain<XrSpaceVelocity>(location->next, XR_TYPE_SPACE_VELOCITY)) {
            velocity->velocityFlags = locatable ? kVelocityFlags : 0;
            velocity->linearVelocity = {0, 0, 0};
            velocity->angularVelocity = {0, 0, 0};
        }
        return XR_SUCCESS;
    });
}

XrResult xrDestroySpace(XrSpace space) {
    return guarded([&](Runtime& rt) {
        if (rt.spaces.find(space) == nullptr) return XR_ERROR_HANDLE_INVALID;
        rt.spaces.erase(space);
        return XR_SUCCESS;
    });
}

XrResult xrLocateViews(XrSession session, const XrViewLocateInfo* viewLocateInfo,
                       XrViewState* viewState, uint32_t viewCapacityInput,
                       uint32_t* viewCountOutput, XrView* views) {
    return guarded([&](Runtime& rt) {
        if (rt.sessions.find(session) == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!has_type(viewLocateInfo, XR_TYPE_VIEW_LOCATE_INFO) ||
            !has_type(viewState, XR_TYPE_VIEW_STATE)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (viewLocateInfo->viewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) {
            return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
        }
        if (viewLocateInfo->displayTime <= 0) return XR_ERROR_TIME_INVALID;
        const SpaceData* base = rt.spaces.find(viewLocateInfo->space);
        if (base == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (base->session != session) return XR_ERROR_VALIDATION_FAILURE;
        std::optional<Pose> base_pose = space_in_stage(*base);
        viewState->viewStateFlags = base_pose ? XR_VIEW_STATE_ORIENTATION_VALID_BIT |
                                                    XR_VIEW_STATE_POSITION_VALID_BIT |
                                                    XR_VIEW_STATE_ORIENTATION_TRACKED_BIT |
                                                    XR_VIEW_STATE_POSITION_TRACKED_BIT
                                              : 0;
        return fill_array(
            viewCapacityInput, viewCountOutput, views, kViewCount, [&](XrView& out, uint32_t i) {
                if (out.type != XR_TYPE_VIEW) return XR_ERROR_VALIDATION_FAILURE;
                out.pose = to_xr(base_pose ? base_pose->inverse() * eye_in_stage(i) : Pose{});
                out.fov = eye_fov();
                return XR_SUCCESS;
            });
    });
}

}  // namespace physhand::sim
