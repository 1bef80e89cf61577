#include "hand_drive.h"

#include <openxr/physhand_physical_hands.h>

#include <stdexcept>

#include "xr_check.h"

namespace physhand::sample {

void set_hand_drive(XrInstance instance, XrSession session, const DriveSettings& drive) {
    XrHandDriveInfoPHYSHAND info{};
    info.type = XR_TYPE_HAND_DRIVE_INFO_PHYSHAND;
    if (drive.name == "paper") {
        info.drive = XR_HAND_DRIVE_KIND_PAPER_PHYSHAND;
    } else if (drive.name == "implicit") {
        info.drive = XR_HAND_DRIVE_KIND_IMPLICIT_PHYSHAND;
    } else if (drive.name == "bones") {
        info.drive = XR_HAND_DRIVE_KIND_BONES_PHYSHAND;
    } else {
        throw std::runtime_error("the extension has no drive kind for \"" + drive.name + "\"");
    }
    // Gains 0: the named drive's own, as in `drive` (a builtin).
    info.substeps = static_cast<std::uint32_t>(drive.substeps);
    xr_check(instance,
             load_function<PFN_xrSetHandDrivePHYSHAND>(instance, "xrSetHandDrivePHYSHAND")(session,
                                                                                           &info),
             "xrSetHandDrivePHYSHAND");
}

}  // namespace physhand::sample
