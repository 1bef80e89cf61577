#pragma once

#include <openxr/openxr.h>

#include <cstdint>

namespace physhand::sim {

// XR_ULTRALEAP_hand_tracking_forearm (newer than the 1.0.20 headers): a joint set of the 26
// joints and the elbow, which the simulated runtime offers beside the default one, as real
// runtimes offer joint sets of their own.
inline constexpr const char* kForearmExtensionName = "XR_ULTRALEAP_hand_tracking_forearm";
inline constexpr auto kForearmJointSet = static_cast<XrHandJointSetEXT>(1000149000);
inline constexpr std::uint32_t kForearmJointCount = XR_HAND_JOINT_COUNT_EXT + 1;  // elbow last

}  // namespace physhand::sim
