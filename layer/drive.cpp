#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "config.h"
#include "dispatch.h"
#include "layer_log.h"
#include "sessions.h"
#include "xr_util.h"

// xrSetHandDrivePHYSHAND: the app picks the hand drive, as the config file's "drive" does.
namespace physhand::layer {

namespace {

// 0 keeps the drive's own value.
std::optional<double> given(float value) {
    return value == 0.0f ? std::nullopt : std::optional<double>(value);
}

}  // namespace

XRAPI_ATTR XrResult XRAPI_CALL SetHandDrivePHYSHAND(XrSession session,
                                                    const XrHandDriveInfoPHYSHAND* driveInfo) {
    return guarded("xrSetHandDrivePHYSHAND", [&] {
        LockedSession locked = lock_session(find_session(session));
        if (XR_FAILED(locked.result)) return locked.result;
        if (driveInfo == nullptr || driveInfo->type != XR_TYPE_HAND_DRIVE_INFO_PHYSHAND) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        std::string_view name;
        switch (raw_enum(driveInfo->drive)) {
            case raw(XR_HAND_DRIVE_KIND_DEFAULT_PHYSHAND):
                break;  // "" is the default drive
            case raw(XR_HAND_DRIVE_KIND_PAPER_PHYSHAND):
                name = "paper";
                break;
            case raw(XR_HAND_DRIVE_KIND_IMPLICIT_PHYSHAND):
                name = "implicit";
                break;
            case raw(XR_HAND_DRIVE_KIND_BONES_PHYSHAND):
                name = "bones";
                break;
            case raw(XR_HAND_DRIVE_KIND_JOINTED_PHYSHAND):
                name = "jointed";
                break;
            default:
                return XR_ERROR_VALIDATION_FAILURE;
        }
        DriveOverrides overrides;
        overrides.stiffness = given(driveInfo->stiffness);
        overrides.damping = given(driveInfo->damping);
        overrides.force_limit = given(driveInfo->forceLimit);
        if (driveInfo->substeps > static_cast<std::uint32_t>(kMaxSubsteps)) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (driveInfo->substeps != 0) overrides.substeps = static_cast<int>(driveInfo->substeps);
        std::optional<DriveSettings> drive;
        try {
            drive = make_drive(name, overrides);
        } catch (const std::invalid_argument& e) {
            log_failure("xrSetHandDrivePHYSHAND", e.what());
            return XR_ERROR_VALIDATION_FAILURE;
        }
        if (!drive) {
            log_once("xrSetHandDrivePHYSHAND: the physics has no drive named \"" +
                     std::string(name) + "\"");
            return XR_ERROR_RUNTIME_FAILURE;
        }
        locked.state->simulation->set_drive(*drive);
        return XR_SUCCESS;
    });
}

}  // namespace physhand::layer
