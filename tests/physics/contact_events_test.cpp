#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "simulation.h"
#include "test_scenes.h"

namespace physhand {
namespace {

constexpr double kCubeMass = 0.1;

// A palm-down right hand coming down at 0.3 m/s onto a free cube 3 cm below its palm, without
// gravity, for 0.35 s, then holding still while the cube drifts away. Returns the cube, and
// the hands' impulse on it summed over the frames.
ColliderHandle push_a_cube(Simulation& sim, HandImpulse* given = nullptr) {
    const Vec3 wrist(0.0, 1.10, -0.3);
    const Vec3 palm = testing::right_hand(wrist, 0.0)[Joint::Palm].position;
    const ColliderHandle cube =
        sim.add_collider(testing::dynamic_box("cube", palm - Vec3(0, 0.07, 0), 0.02, kCubeMass));
    if (given) sim.take_hand_impulse(cube);  // from now on
    for (int f = 1; f <= 90; ++f) {
        const double t = f / 90.0;
        const double down = 0.3 * std::min(t, 0.35);
        sim.step_to(t, {HandPose{}, testing::right_hand(wrist - Vec3(0, down, 0), 0.0)});
        if (given) {
            const HandImpulse frame = sim.take_hand_impulse(cube);
            given->linear += frame.linear;
            given->angular += frame.angular;
        }
    }
    return cube;
}

TEST(ContactEvents, NoneAreKeptUntilAskedFor) {
    Simulation sim(SimulationSettings{}, Vec3::Zero());
    push_a_cube(sim);
    EXPECT_FALSE(sim.contact_events().enabled());
    EXPECT_TRUE(sim.contact_events().events().empty());
}

TEST(ContactEvents, ImpulsesOfAPushAddUpToTheCubesMomentum) {
    Simulation sim(SimulationSettings{}, Vec3::Zero());
    sim.contact_events().enable(true, ContactEventLog::kMaxCapacity);
    const ColliderHandle cube = push_a_cube(sim);
    Vec3 pushed = Vec3::Zero();
    for (const ContactEvent& e : sim.contact_events().events()) {
        if (e.collider == cube) pushed += e.impulse_on_collider;
    }
    const Vec3 momentum = kCubeMass * sim.body_state(cube)->linear_velocity;
    ASSERT_GT(momentum.norm(), 0.02);  // it was pushed, at about the hand's speed
    EXPECT_LT((pushed - momentum).norm(), 0.1 * momentum.norm())
        << "events " << pushed.transpose() << " N·s, cube " << momentum.transpose() << " N·s";
    // The normal impulses alone, summed, about as large: friction gives the rest (13 %).
    double normal_only = 0.0;
    for (const ContactEvent& e : sim.contact_events().events()) normal_only += e.impulse;
    EXPECT_NEAR(normal_only, momentum.norm(), 0.2 * momentum.norm());
    EXPECT_EQ(sim.contact_events().lost(), 0u);
}

// Taken frame by frame, the hands' impulse on the cube is its momentum, and its moment the
// cube's spin.
TEST(HandImpulses, AddUpToTheCubesMomentumAndSpin) {
    Simulation sim(SimulationSettings{}, Vec3::Zero());
    HandImpulse given;
    const ColliderHandle cube = push_a_cube(sim, &given);
    const BodyState state = *sim.body_state(cube);
    const Vec3 momentum = kCubeMass * state.linear_velocity;
    EXPECT_LT((given.linear - momentum).norm(), 0.1 * momentum.norm());
    // A 4 cm cube's inertia about its centre: m (2 half)^2 / 6 on every axis.
    const double inertia = kCubeMass * 0.04 * 0.04 / 6.0;
    EXPECT_LT((given.angular - inertia * state.angular_velocity).norm(),
              0.1 * momentum.norm() * 0.02 + 1e-6)
        << given.angular.transpose() << " against "
        << (inertia * state.angular_velocity).transpose();
    EXPECT_EQ(sim.take_hand_impulse(cube).linear, Vec3::Zero()) << "taken already";
    EXPECT_EQ(sim.take_hand_impulse(12345).linear, Vec3::Zero());
}

// A hand pressed on a static table pushes it down, though nothing moves it; taken every
// tenth frame, nothing is lost in between.
TEST(HandImpulses, ReachStaticColliders) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    const ColliderHandle table =
        sim.add_collider(testing::static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
    double pressed = sim.take_hand_impulse(table).linear.y();
    for (int f = 1; f <= 90; ++f) {
        const double y = std::max(0.82 - 0.2 * f / 90.0, 0.73);
        sim.step_to(f / 90.0, {HandPose{}, testing::right_hand(Vec3(0.0, y, -0.3), 0.1)});
        if (f % 10 == 0) pressed += sim.take_hand_impulse(table).linear.y();
    }
    EXPECT_LT(pressed, -0.1);
}

TEST(ContactEvents, EachTouchBeginsOnceAndEndsWhenTheHandLetsGo) {
    Simulation sim(SimulationSettings{}, Vec3::Zero());
    sim.contact_events().enable(false, ContactEventLog::kDefaultCapacity);
    const ColliderHandle cube = push_a_cube(sim);
    const auto& events = sim.contact_events().events();
    ASSERT_FALSE(events.empty());
    std::map<std::tuple<HandSide, Joint, ColliderHandle>, bool> touching;
    double last_time = 0.0;
    for (const ContactEvent& e : events) {
        EXPECT_NE(e.kind, ContactEvent::Kind::Persist);  // not asked for
        EXPECT_EQ(e.collider, cube);
        EXPECT_GE(e.time_s, last_time);
        last_time = e.time_s;
        EXPECT_NEAR(e.normal.norm(), 1.0, 1e-6);
        bool& now = touching[{e.hand, e.joint, e.collider}];
        if (e.kind == ContactEvent::Kind::Begin) {
            EXPECT_FALSE(now) << "a second begin without an end";
            EXPECT_GE(e.impulse, 0.0);
            EXPECT_LT(e.approach_speed, 1.0);  // the hand came at 0.3 m/s
        } else {
            EXPECT_TRUE(now) << "an end without a begin";
            EXPECT_EQ(e.impulse, 0.0);
        }
        now = e.kind == ContactEvent::Kind::Begin;
    }
    EXPECT_GT(events.front().approach_speed, 0.1);  // the first touch is the hand's impact
    for (const auto& [key, now] : touching) EXPECT_FALSE(now) << "the cube drifted away";
}

// Colliders touching each other are reported only when asked for: a cube dropped 10 cm onto
// a table begins touching it at about the speed it fell with.
TEST(ContactEvents, BetweenCollidersOnlyWhenAskedFor) {
    for (const bool asked : {false, true}) {
        SCOPED_TRACE(asked);
        Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
        sim.contact_events().enable(false, ContactEventLog::kDefaultCapacity, asked);
        const ColliderHandle table = sim.add_collider(
            testing::static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
        const ColliderHandle cube =
            sim.add_collider(testing::dynamic_box("cube", Vec3(0, 0.87, -0.4), 0.02, kCubeMass));
        for (int f = 1; f <= 45; ++f) sim.step_to(f / 90.0, {HandPose{}, HandPose{}});
        const auto& events = sim.contact_events().events();
        if (!asked) {
            EXPECT_TRUE(events.empty());
            continue;
        }
        ASSERT_FALSE(events.empty());
        const ContactEvent& first = events.front();
        EXPECT_EQ(first.kind, ContactEvent::Kind::Begin);
        EXPECT_TRUE((first.collider == table && first.other == cube) ||
                    (first.collider == cube && first.other == table));
        EXPECT_NEAR(first.approach_speed, std::sqrt(2 * 9.81 * 0.1), 0.2);
        EXPECT_NEAR(std::abs(first.normal.y()), 1.0, 1e-3);
    }
}

TEST(ContactEvents, AFullQueueKeepsWhatItHasAndCountsWhatItDrops) {
    Simulation sim(SimulationSettings{}, Vec3::Zero());
    sim.contact_events().enable(true, 2);
    push_a_cube(sim);
    ContactEventLog& log = sim.contact_events();
    ASSERT_EQ(log.events().size(), 2u);
    EXPECT_EQ(log.events().front().kind, ContactEvent::Kind::Begin);
    EXPECT_GT(log.lost(), 0u);
    log.drop_oldest(1);
    EXPECT_EQ(log.events().size(), 1u);
    log.clear_lost();
    EXPECT_EQ(log.lost(), 0u);
    EXPECT_THROW(log.enable(true, 0), std::invalid_argument);
}

}  // namespace
}  // namespace physhand
