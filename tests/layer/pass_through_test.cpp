// What the layer does not simulate gets the runtime's own answer: another joint set, a
// structure chained to the locate info or to a tracker's create info that the layer does not
// model. Structures chained to the output that the layer does not know are the runtime's to
// fill, beside the physical joints.

#include <string>

#include "layer_fixture.h"
#include "sim_joint_sets.h"

namespace physhand::layer_test {
namespace {

// XR_EXT_hand_tracking_data_source (newer than the 1.0.20 headers), as an app chains it to
// XrHandTrackerCreateInfoEXT: a hand source the layer does not model.
struct HandTrackingDataSourceInfo {
    XrStructureType type;
    const void* next;
    uint32_t requestedDataSourceCount;
    const int32_t* requestedDataSources;
};
constexpr auto kDataSourceInfoType = static_cast<XrStructureType>(1000428000);

class PassThrough : public LayerTest {
  protected:
    // A right hand pressed into the desk for a second: the physical palm stays on the desk,
    // the runtime's is in it.
    void press_into_desk(const std::vector<const char*>& extensions) {
        use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
        ASSERT_EQ(create_instance(extensions), XR_SUCCESS);
        start_session();
        frame();
        create_desk();
        right_ = hand_tracker(XR_HAND_RIGHT_EXT);
        HandJoints hand;
        for (int f = 0; f < 90; ++f) locate_ok(right_, frame(), hand);
        ASSERT_EQ(hand.physical.isSimulated, XR_TRUE);
        ASSERT_GT(hand.pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop);
        ASSERT_LT(hand.ghost_pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop - 0.01f);
    }

    XrResult create_tracker(const XrHandTrackerCreateInfoEXT& info, XrHandTrackerEXT& tracker) {
        return function<PFN_xrCreateHandTrackerEXT>("xrCreateHandTrackerEXT")(session_, &info,
                                                                              &tracker);
    }

    XrResult locate_raw(XrHandTrackerEXT tracker, const XrHandJointsLocateInfoEXT& info,
                        XrHandJointLocationsEXT& locations) {
        return function<PFN_xrLocateHandJointsEXT>("xrLocateHandJointsEXT")(tracker, &info,
                                                                            &locations);
    }

    XrHandJointsLocateInfoEXT locate_info(XrTime time, const void* next = nullptr) const {
        auto info = xr<XrHandJointsLocateInfoEXT>(XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
        info.next = next;
        info.baseSpace = stage_;
        info.time = time;
        return info;
    }

    XrHandTrackerEXT right_ = XR_NULL_HANDLE;
};

TEST_F(PassThrough, AnotherJointSetGetsTheRuntimesJointsWhileTheDefaultSetStaysPhysical) {
    // Core validation 1.0.20 knows no joint set but the default one.
    use_layer(LayerMode::Implicit, false);
    auto extensions = all_extensions();
    extensions.push_back(sim::kForearmExtensionName);
    press_into_desk(extensions);

    auto create = xr<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
    create.hand = XR_HAND_RIGHT_EXT;
    create.handJointSet = sim::kForearmJointSet;
    XrHandTrackerEXT forearm = XR_NULL_HANDLE;
    ASSERT_EQ(create_tracker(create, forearm), XR_SUCCESS);

    const XrTime time = frame();
    std::array<XrHandJointLocationEXT, sim::kForearmJointCount> joints{};
    auto locations = xr<XrHandJointLocationsEXT>(XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
    locations.jointCount = sim::kForearmJointCount;
    locations.jointLocations = joints.data();
    ASSERT_EQ(locate_raw(forearm, locate_info(time), locations), XR_SUCCESS);
    EXPECT_TRUE(locations.isActive);
    for (const XrHandJointLocationEXT& joint : joints) {
        EXPECT_TRUE(joint.locationFlags & XR_SPACE_LOCATION_POSITION_VALID_BIT);
    }
    // The runtime's hand, in the desk; its elbow behind the wrist.
    EXPECT_LT(joints[XR_HAND_JOINT_PALM_EXT].pose.position.y, kDeskTop - 0.01f);
    EXPECT_NEAR(
        distance(joints[kJointCount].pose.position, joints[XR_HAND_JOINT_WRIST_EXT].pose.position),
        0.25, 1e-4);

    // The default set's tracker of the same hand is still the physical hand, on the desk.
    HandJoints hand;
    locate_ok(right_, time, hand);
    EXPECT_EQ(hand.physical.isSimulated, XR_TRUE);
    EXPECT_GT(hand.pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop);
    EXPECT_FLOAT_EQ(hand.ghost_pose(XR_HAND_JOINT_PALM_EXT).position.y,
                    joints[XR_HAND_JOINT_PALM_EXT].pose.position.y);

    // A joint count that is neither set's is the runtime's to refuse.
    locations.jointCount = kJointCount;
    EXPECT_EQ(locate_raw(forearm, locate_info(time), locations), XR_ERROR_VALIDATION_FAILURE);
    hand.locations.jointCount = sim::kForearmJointCount;
    EXPECT_EQ(locate_raw(right_, locate_info(time), hand.locations), XR_ERROR_VALIDATION_FAILURE);
}

TEST_F(PassThrough, AMotionRangeOnTheLocateInfoGetsTheRuntimesAnswer) {
    auto extensions = all_extensions();
    extensions.push_back(XR_EXT_HAND_JOINTS_MOTION_RANGE_EXTENSION_NAME);
    press_into_desk(extensions);

    auto range = xr<XrHandJointsMotionRangeInfoEXT>(XR_TYPE_HAND_JOINTS_MOTION_RANGE_INFO_EXT);
    range.handJointsMotionRange = XR_HAND_JOINTS_MOTION_RANGE_CONFORMING_TO_CONTROLLER_EXT;
    const XrTime time = frame();
    HandJoints hand;
    locate_ok(right_, time, hand);
    hand.locations.next = nullptr;
    ASSERT_EQ(locate_raw(right_, locate_info(time, &range), hand.locations), XR_SUCCESS);
    EXPECT_LT(hand.pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop - 0.01f);

    // Without it, the same time is the physical hand again.
    locate_ok(right_, time, hand);
    EXPECT_GT(hand.pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop);
}

TEST_F(PassThrough, AnOutputStructureTheLayerDoesNotKnowIsTheRuntimesToFill) {
    // Core validation 1.0.20 takes XrHandTrackingAimStateFB for an input (its header's error).
    use_layer(LayerMode::Implicit, false);
    auto extensions = all_extensions();
    extensions.push_back(XR_FB_HAND_TRACKING_AIM_EXTENSION_NAME);
    press_into_desk(extensions);

    HandJoints hand;
    auto aim = xr<XrHandTrackingAimStateFB>(XR_TYPE_HAND_TRACKING_AIM_STATE_FB);
    const XrTime time = frame();
    locate_ok(right_, time, hand);
    hand.physical.next = &aim;
    auto info = locate_info(time);
    ASSERT_EQ(locate_raw(right_, info, hand.locations), XR_SUCCESS);
    EXPECT_TRUE(aim.status & XR_HAND_TRACKING_AIM_VALID_BIT_FB);
    // The runtime aims from its own hand, in the desk; the joints are the physical hand's.
    EXPECT_LT(aim.aimPose.position.y, kDeskTop);
    EXPECT_GT(hand.pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop);
    EXPECT_EQ(hand.physical.isSimulated, XR_TRUE);
    // The app's chain is as it was.
    EXPECT_EQ(hand.locations.next, &hand.velocities);
    EXPECT_EQ(hand.velocities.next, &hand.physical);
    EXPECT_EQ(hand.physical.next, &aim);
}

TEST_F(PassThrough, ATrackerCreatedWithAStructureTheLayerDoesNotModelIsTheRuntimes) {
    // Core validation 1.0.20 does not know the data source structure.
    use_layer(LayerMode::Implicit, false);
    press_into_desk(all_extensions());

    const int32_t unobstructed = 1;
    HandTrackingDataSourceInfo source{kDataSourceInfoType, nullptr, 1, &unobstructed};
    auto create = xr<XrHandTrackerCreateInfoEXT>(XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
    create.next = &source;
    create.hand = XR_HAND_RIGHT_EXT;
    create.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
    XrHandTrackerEXT sourced = XR_NULL_HANDLE;
    ASSERT_EQ(create_tracker(create, sourced), XR_SUCCESS);

    const XrTime time = frame();
    HandJoints hand;
    locate_ok(sourced, time, hand);
    EXPECT_EQ(hand.physical.isSimulated, XR_FALSE);
    EXPECT_TRUE(hand.locations.isActive);
    EXPECT_LT(hand.pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop - 0.01f);
    locate_ok(right_, time, hand);
    EXPECT_GT(hand.pose(XR_HAND_JOINT_PALM_EXT).position.y, kDeskTop);
}

}  // namespace
}  // namespace physhand::layer_test
