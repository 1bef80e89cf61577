// The extension's contact feedback, read through the loader as an app reads it: contact
// events, and the hands' impulses on colliders chained to their locations.

#include <vector>

#include "layer_fixture.h"

namespace physhand::layer_test {
namespace {

class ContactEvents : public LayerTest {
  protected:
    void SetUp() override {
        LayerTest::SetUp();
        use_scene(scene_with_hands({{"right", pressing_hand(0.1)}}));
        ASSERT_EQ(create_instance(), XR_SUCCESS);
        start_session();
    }
    XrPhysicalContactEventsGetInfoPHYSHAND get_info() {
        auto info = xr<XrPhysicalContactEventsGetInfoPHYSHAND>(
            XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND);
        info.baseSpace = stage_;
        info.time = now();
        return info;
    }
    // Every event waiting, by the two-call idiom.
    std::vector<XrPhysicalContactEventPHYSHAND> read_events() {
        const auto info = get_info();
        auto events = xr<XrPhysicalContactEventsPHYSHAND>(XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND);
        EXPECT_EQ(api().get_contact_events(session_, &info, &events), XR_SUCCESS);
        std::vector<XrPhysicalContactEventPHYSHAND> out(events.eventCountOutput);
        if (out.empty()) return out;
        if (out.size() > 1) {  // too small a buffer reads nothing
            events.eventCapacityInput = events.eventCountOutput - 1;
            events.events = out.data();
            EXPECT_EQ(api().get_contact_events(session_, &info, &events),
                      XR_ERROR_SIZE_INSUFFICIENT);
            EXPECT_EQ(events.eventCountOutput, out.size());
        }
        events.eventCapacityInput = static_cast<std::uint32_t>(out.size());
        events.events = out.data();
        EXPECT_EQ(api().get_contact_events(session_, &info, &events), XR_SUCCESS);
        EXPECT_EQ(events.lostEventCount, 0u);
        return out;
    }
};

// A hand pressed on the desk begins touching it there, from above; the touches end when the
// desk is destroyed, naming no collider any more.
TEST_F(ContactEvents, APressBeginsOnTheDeskAndEndsWhenTheDeskIsGone) {
    auto reporting = xr<XrPhysicalContactReportingInfoPHYSHAND>(
        XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND);
    ASSERT_EQ(api().set_contact_reporting(session_, &reporting), XR_SUCCESS);
    const auto desk = create_desk();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    for (int f = 0; f < 150; ++f) locate_ok(right, frame(), hand);
    ASSERT_TRUE(hand.any_contact());

    const auto begun = read_events();
    ASSERT_FALSE(begun.empty());
    for (const XrPhysicalContactEventPHYSHAND& e : begun) {
        EXPECT_EQ(e.kind, XR_PHYSICAL_CONTACT_EVENT_KIND_BEGIN_PHYSHAND);
        EXPECT_EQ(e.hand, XR_HAND_RIGHT_EXT);
        EXPECT_LT(e.joint, XR_HAND_JOINT_COUNT_EXT);
        EXPECT_EQ(e.collider, desk);
        EXPECT_GT(e.time, 0);
        EXPECT_LE(e.time, now());
        EXPECT_NEAR(e.point.y, kDeskTop, 0.005);
        EXPECT_GT(e.normal.y, 0.99f);  // from the desk toward the hand
        EXPECT_GE(e.impulse, 0.0f);
        EXPECT_LE(e.linearImpulse.y, 0.0f);  // the hand pushes the desk down
        EXPECT_GE(e.approachSpeed, 0.0f);
        EXPECT_LT(e.approachSpeed, 1.0f);  // the ghost came down at 0.145 m/s
    }
    EXPECT_TRUE(read_events().empty()) << "a read takes the events it returns";

    ASSERT_EQ(api().destroy_collider(desk), XR_SUCCESS);
    for (int f = 0; f < 5; ++f) locate_ok(right, frame(), hand);
    const auto ended = read_events();
    EXPECT_EQ(ended.size(), begun.size());
    for (const XrPhysicalContactEventPHYSHAND& e : ended) {
        EXPECT_EQ(e.kind, XR_PHYSICAL_CONTACT_EVENT_KIND_END_PHYSHAND);
        EXPECT_EQ(e.collider, XR_NULL_HANDLE);
        EXPECT_EQ(e.impulse, 0.0f);
    }
}

// A buffer of one keeps the first event and counts the rest as lost, until a read; then the
// next frame's first persist event.
TEST_F(ContactEvents, AFullBufferCountsWhatItDrops) {
    auto reporting = xr<XrPhysicalContactReportingInfoPHYSHAND>(
        XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND);
    reporting.persistEvents = XR_TRUE;
    reporting.eventCapacity = 1;
    ASSERT_EQ(api().set_contact_reporting(session_, &reporting), XR_SUCCESS);
    create_desk();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    for (int f = 0; f < 150; ++f) locate_ok(right, frame(), hand);
    const auto info = get_info();
    XrPhysicalContactEventPHYSHAND event{};
    auto events = xr<XrPhysicalContactEventsPHYSHAND>(XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND);
    events.eventCapacityInput = 1;
    events.events = &event;
    ASSERT_EQ(api().get_contact_events(session_, &info, &events), XR_SUCCESS);
    EXPECT_EQ(events.eventCountOutput, 1u);
    EXPECT_EQ(event.kind, XR_PHYSICAL_CONTACT_EVENT_KIND_BEGIN_PHYSHAND);
    EXPECT_GT(events.lostEventCount, 0u);
    events.eventCapacityInput = 0;  // the read reset the count
    ASSERT_EQ(api().get_contact_events(session_, &info, &events), XR_SUCCESS);
    EXPECT_EQ(events.eventCountOutput, 0u);
    EXPECT_EQ(events.lostEventCount, 0u);
    locate_ok(right, frame(), hand);
    events.eventCapacityInput = 1;
    ASSERT_EQ(api().get_contact_events(session_, &info, &events), XR_SUCCESS);
    EXPECT_EQ(events.eventCountOutput, 1u);
    EXPECT_EQ(event.kind, XR_PHYSICAL_CONTACT_EVENT_KIND_PERSIST_PHYSHAND);
}

// Asked for, a box dropped on the desk begins touching it, naming both and no hand.
TEST_F(ContactEvents, CollidersTouchingEachOtherWhenAskedFor) {
    auto reporting = xr<XrPhysicalContactReportingInfoPHYSHAND>(
        XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND);
    reporting.colliderContacts = XR_TRUE;
    ASSERT_EQ(api().set_contact_reporting(session_, &reporting), XR_SUCCESS);
    const auto desk = create_desk();
    auto info = collider_info(XR_PHYSICAL_COLLIDER_SHAPE_BOX_PHYSHAND,
                              XR_PHYSICAL_COLLIDER_MOTION_DYNAMIC_PHYSHAND, stage_,
                              pose_at(0.3f, kDeskTop + 0.1f, -0.4f), frame());
    info.halfExtents = {0.02f, 0.02f, 0.02f};
    const auto box = create_collider(info);
    simulate_frames(45);
    const auto events = read_events();
    ASSERT_FALSE(events.empty());
    bool landed = false;
    for (const XrPhysicalContactEventPHYSHAND& e : events) {
        if (e.kind != XR_PHYSICAL_CONTACT_EVENT_KIND_BEGIN_PHYSHAND || e.hand != 0) continue;
        landed = landed || (e.collider == box && e.otherCollider == desk) ||
                 (e.collider == desk && e.otherCollider == box);
    }
    EXPECT_TRUE(landed);
}

TEST_F(ContactEvents, BadArgumentsAreRejected) {
    auto reporting = xr<XrPhysicalContactReportingInfoPHYSHAND>(
        XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND);
    EXPECT_EQ(api().set_contact_reporting(session_, nullptr), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(api().set_contact_reporting(bogus_handle<XrSession>(), &reporting),
              XR_ERROR_HANDLE_INVALID);
    reporting.eventCapacity = 65537;
    EXPECT_EQ(api().set_contact_reporting(session_, &reporting), XR_ERROR_VALIDATION_FAILURE);
    reporting.eventCapacity = 0;
    reporting.type = XR_TYPE_HAND_DRIVE_INFO_PHYSHAND;
    EXPECT_EQ(api().set_contact_reporting(session_, &reporting), XR_ERROR_VALIDATION_FAILURE);

    auto info = get_info();
    auto events = xr<XrPhysicalContactEventsPHYSHAND>(XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND);
    EXPECT_EQ(api().get_contact_events(session_, nullptr, &events), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(api().get_contact_events(session_, &info, nullptr), XR_ERROR_VALIDATION_FAILURE);
    EXPECT_EQ(api().get_contact_events(bogus_handle<XrSession>(), &info, &events),
              XR_ERROR_HANDLE_INVALID);
    events.eventCapacityInput = 4;  // and no array
    EXPECT_EQ(api().get_contact_events(session_, &info, &events), XR_ERROR_VALIDATION_FAILURE);
    events.eventCapacityInput = 0;
    events.type = XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND;
    EXPECT_EQ(api().get_contact_events(session_, &info, &events), XR_ERROR_VALIDATION_FAILURE);
    events.type = XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND;
    info.time = 0;
    EXPECT_EQ(api().get_contact_events(session_, &info, &events), XR_ERROR_TIME_INVALID);
    info = get_info();
    info.baseSpace = XR_NULL_HANDLE;
    EXPECT_EQ(api().get_contact_events(session_, &info, &events), XR_ERROR_HANDLE_INVALID);
}

// The desk a hand presses on is pushed down by it, frame after frame, and each frame's
// impulse is read once.
TEST_F(ContactEvents, TheDeskAHandPressesOnIsPushedDownAndEachImpulseIsReadOnce) {
    const auto desk = create_desk();
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    const auto read = [&](XrTime time, XrResult expected = XR_SUCCESS) {
        auto info = xr<XrPhysicalCollidersLocateInfoPHYSHAND>(
            XR_TYPE_PHYSICAL_COLLIDERS_LOCATE_INFO_PHYSHAND);
        info.baseSpace = stage_;
        info.time = time;
        info.colliderCount = 1;
        info.colliders = &desk;
        XrPhysicalColliderLocationPHYSHAND location{};
        XrPhysicalColliderImpulsePHYSHAND impulse{};
        auto impulses =
            xr<XrPhysicalColliderImpulsesPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_IMPULSES_PHYSHAND);
        impulses.impulseCount = expected == XR_SUCCESS ? 1 : 2;
        impulses.impulses = &impulse;
        auto locations =
            xr<XrPhysicalColliderLocationsPHYSHAND>(XR_TYPE_PHYSICAL_COLLIDER_LOCATIONS_PHYSHAND);
        locations.next = &impulses;
        locations.locationCount = 1;
        locations.locations = &location;
        EXPECT_EQ(api().locate_colliders(session_, &info, &locations), expected);
        return impulse;
    };
    read(frame());  // starts the count
    double pushed = 0.0;
    HandJoints hand;
    for (int f = 0; f < 150; ++f) {
        const XrTime time = frame();
        locate_ok(right, time, hand);
        const XrPhysicalColliderImpulsePHYSHAND impulse = read(time);
        EXPECT_TRUE(is_finite(impulse.linearImpulse) && is_finite(impulse.angularImpulse));
        EXPECT_LE(impulse.linearImpulse.y, 1e-6f);
        pushed += impulse.linearImpulse.y;
        const XrPhysicalColliderImpulsePHYSHAND again = read(time);
        EXPECT_EQ(again.linearImpulse.y, 0.0f) << "read twice";
    }
    ASSERT_TRUE(hand.any_contact());
    EXPECT_LT(pushed, -0.05);
    read(now(), XR_ERROR_VALIDATION_FAILURE);  // a count that is not the colliders'
}

}  // namespace
}  // namespace physhand::layer_test
