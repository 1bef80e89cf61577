#include "hand_trackers.h"

#include <chrono>

#include "xr_check.h"

namespace physhand::sample {

HandTrackers::HandTrackers(XrInstance instance, XrSession session)
    : instance_(instance),
      locate_(load_function<PFN_xrLocateHandJointsEXT>(instance, "xrLocateHandJointsEXT")) {
    const auto create =
        load_function<PFN_xrCreateHandTrackerEXT>(instance, "xrCreateHandTrackerEXT");
    const auto destroy =
        load_function<PFN_xrDestroyHandTrackerEXT>(instance, "xrDestroyHandTrackerEXT");
    const std::array<XrHandEXT, 2> sides = {XR_HAND_LEFT_EXT, XR_HAND_RIGHT_EXT};
    for (std::size_t i = 0; i < sides.size(); ++i) {
        XrHandTrackerCreateInfoEXT info{};
        info.type = XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT;
        info.hand = sides[i];
        info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
        XrHandTrackerEXT tracker = XR_NULL_HANDLE;
        xr_check(instance, create(session, &info, &tracker), "xrCreateHandTrackerEXT");
        trackers_[i] = XrHandle<XrHandTrackerEXT>(tracker, destroy);
    }
}

double HandTrackers::locate(XrSpace space, XrTime time, std::array<LocatedHand, 2>& hands) const {
    XrHandJointsLocateInfoEXT info{};
    info.type = XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT;
    info.baseSpace = space;
    info.time = time;
    // Everything is set up first, so that the clock times the two calls alone.
    std::array<XrHandJointsPhysicalStatePHYSHAND, 2> states{};
    std::array<XrHandCollisionShapesPHYSHAND, 2> shapes{};
    std::array<XrHandJointLocationsEXT, 2> locations{};
    for (std::size_t i = 0; i < hands.size(); ++i) {
        shapes[i].type = XR_TYPE_HAND_COLLISION_SHAPES_PHYSHAND;
        shapes[i].shapeCapacityInput = static_cast<std::uint32_t>(hands[i].shapes.size());
        shapes[i].shapes = hands[i].shapes.data();
        states[i].type = XR_TYPE_HAND_JOINTS_PHYSICAL_STATE_PHYSHAND;
        states[i].next = &shapes[i];
        states[i].jointCount = XR_HAND_JOINT_COUNT_EXT;
        states[i].ghostPoses = hands[i].ghost.data();
        states[i].inContact = hands[i].in_contact.data();
        states[i].springForce = hands[i].spring_force.data();
        locations[i].type = XR_TYPE_HAND_JOINT_LOCATIONS_EXT;
        locations[i].next = &states[i];
        locations[i].jointCount = XR_HAND_JOINT_COUNT_EXT;
        locations[i].jointLocations = hands[i].joints.data();
    }
    const auto start = std::chrono::steady_clock::now();
    xr_check(instance_, locate_(trackers_[0].get(), &info, &locations[0]),
             "xrLocateHandJointsEXT(left)");
    xr_check(instance_, locate_(trackers_[1].get(), &info, &locations[1]),
             "xrLocateHandJointsEXT(right)");
    const auto end = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < hands.size(); ++i) {
        hands[i].active = locations[i].isActive == XR_TRUE;
        hands[i].ghost_active = states[i].ghostIsActive == XR_TRUE;
        hands[i].shape_count = shapes[i].shapeCountOutput;
    }
    return std::chrono::duration<double, std::micro>(end - start).count();
}

}  // namespace physhand::sample
