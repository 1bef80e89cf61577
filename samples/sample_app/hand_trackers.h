#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <cstdint>

#include "xr_handle.h"

namespace physhand::sample {

// What xrLocateHandJointsEXT, with the layer's physical state chained, says of one hand.
struct LocatedHand {
    std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT> joints{};  // the physical hand
    std::array<XrPosef, XR_HAND_JOINT_COUNT_EXT> ghost{};
    std::array<XrBool32, XR_HAND_JOINT_COUNT_EXT> in_contact{};
    std::array<float, XR_HAND_JOINT_COUNT_EXT> spring_force{};
    // The bodies the physical hand collides as (none without the layer).
    std::array<XrHandCollisionShapePHYSHAND, XR_HAND_JOINT_COUNT_EXT> shapes{};
    std::uint32_t shape_count = 0;
    bool active = false;
    bool ghost_active = false;
};

// A hand tracker for each hand, indexed like physhand::HandSide (left, right).
class HandTrackers {
  public:
    HandTrackers(XrInstance instance, XrSession session);

    // Locates the left then the right hand in `space` at `time`, and returns the wall time
    // both calls took in microseconds: the first locate of a new time steps the physics.
    double locate(XrSpace space, XrTime time, std::array<LocatedHand, 2>& hands) const;

  private:
    XrInstance instance_;
    PFN_xrLocateHandJointsEXT locate_ = nullptr;
    std::array<XrHandle<XrHandTrackerEXT>, 2> trackers_;
};

}  // namespace physhand::sample
