#pragma once

#include <openxr/openxr.h>

#include "drive.h"

namespace physhand::sample {

// Gives both hands of `session` the builtin drive named by `drive`, with its substeps, through
// xrSetHandDrivePHYSHAND, so that the drive the sample reports is the one that ran whatever
// the layer's config says. Throws XrCallError for a failed call, std::runtime_error for a
// drive the extension cannot name.
void set_hand_drive(XrInstance instance, XrSession session, const DriveSettings& drive);

}  // namespace physhand::sample
