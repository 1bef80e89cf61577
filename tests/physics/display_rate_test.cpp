#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "frame_clock.h"
#include "scene_run.h"
#include "simulation.h"
#include "test_scenes.h"

namespace physhand {
namespace {

using testing::static_box;

// A right hand sweeping over a table, curling as it goes; `height` above the table top.
std::array<HandPose, 2> sweeping_hand(double t, double height) {
    return {HandPose{}, testing::right_hand(Vec3(0.15 * std::sin(2.0 * t), 0.75 + height, -0.35),
                                            0.2 + 0.2 * std::sin(3.0 * t))};
}

// Steps a simulation with the hand `height` above a table at `rate_hz` displays for a
// second; `check` sees each frame's shown hand and ghost.
template <typename Check>
void play_at(double rate_hz, double height, Check check) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
    const auto ghosts_at = [&](double t) { return sweeping_hand(t, height); };
    const std::int64_t period_ns = frame_period_ns(rate_hz);
    for (int f = 1; f <= static_cast<int>(rate_hz); ++f) {
        const double t = clock_seconds(f * period_ns);
        sim.step_sampling(t, ghosts_at);
        check(sim.hand(HandSide::Right), ghosts_at(t)[1]);
    }
}

TEST(DisplayRate, EveryDisplayTimeGetsAPoseOfItsOwn) {
    // Gated (far from the table) and simulated (near it, touching nothing).
    for (const double height : {0.4, 0.06}) {
        std::map<double, double> worst_error;  // by rate
        for (const double rate : {90.0, 72.0, 120.0, 144.0}) {
            std::optional<Pose> previous;
            int frames = 0, simulated = 0;
            play_at(rate, height, [&](const PhysicalHandState& hand, const HandPose& ghost) {
                ASSERT_TRUE(hand.joints.active);
                const Pose& tip = hand.joints[Joint::IndexTip];
                if (previous) {
                    EXPECT_GT((tip.position - previous->position).norm(), 1e-6);
                }
                previous = tip;
                simulated += hand.simulated ? 1 : 0;
                worst_error[rate] = std::max(
                    worst_error[rate], (tip.position - ghost[Joint::IndexTip].position).norm());
                ++frames;
            });
            EXPECT_EQ(frames, static_cast<int>(rate));
            EXPECT_EQ(simulated, height < 0.1 ? frames : 0) << rate << " Hz, " << height << " m";
            // Shown where the ghost is at the display time, as on the physics' own frames:
            // a pose a frame old would be up to 1.3 mm behind.
            EXPECT_LT(worst_error[rate], worst_error[90.0] + 0.05e-3)
                << rate << " Hz, " << height << " m above";
        }
    }
}

TEST(DisplayRate, TheSameOrAnEarlierTimeChangesNothing) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
    int samples = 0;
    const auto ghosts_at = [&](double t) {
        ++samples;
        return sweeping_hand(t, 0.06);
    };
    for (int f = 1; f <= 20; ++f) sim.step_sampling(f / 144.0, ghosts_at);
    const PhysicalHandState shown = sim.hand(HandSide::Right);
    const double physics_time = sim.time();
    samples = 0;
    sim.step_sampling(20 / 144.0, ghosts_at);
    sim.step_sampling(19.5 / 144.0, ghosts_at);
    sim.step_to(10 / 144.0, sweeping_hand(0.0, 0.3));
    EXPECT_EQ(samples, 0);
    EXPECT_EQ(sim.time(), physics_time);
    for (std::size_t j = 0; j < kJointCount; ++j) {
        EXPECT_EQ(sim.hand(HandSide::Right).joints.joints[j].position,
                  shown.joints.joints[j].position);
    }
}

// The sample at a display time between frames is the runtime's like any other: a NaN or a
// jump across the room there shows the hand moved on at its own velocities, never the bad
// sample.
TEST(DisplayRate, ABadSampleBetweenFramesIsNotShown) {
    for (const double height : {0.4, 0.06}) {  // gated and simulated
        const auto clean = [&](double t) { return sweeping_hand(t, height); };
        std::array<HandPose, 2> nan = clean(0.0), far = clean(0.0);
        nan[1].joints[3].position.x() = NAN;
        for (Pose& joint : far[1].joints) joint.position.x() += 2.0;
        const double between = frame_time_s(30) + 0.004;
        for (const auto& bad : {nan, far}) {
            Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
            sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
            for (int f = 1; f <= 30; ++f) sim.step_sampling(frame_time_s(f), clean);
            const Vec3 at_frame = sim.hand(HandSide::Right).joints[Joint::Wrist].position;
            sim.step_sampling(between, [&](double t) { return t == between ? bad : clean(t); });
            const PhysicalHandState& shown = sim.hand(HandSide::Right);
            for (const Pose& joint : shown.joints.joints) EXPECT_TRUE(is_finite(joint));
            EXPECT_LT((shown.joints[Joint::Wrist].position - at_frame).norm(), 0.01) << height;
        }
    }
}

TEST(DisplayRate, AHitchIsSteppedFrameByFrameALongGapOnlyUpToMaxStep) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    sim.add_collider(static_box("table", Vec3(0, 0.725, -0.4), Vec3(0.4, 0.025, 0.3)));
    std::vector<double> sampled;
    const auto ghosts_at = [&](double t) {
        sampled.push_back(t);
        return sweeping_hand(t, 0.06);
    };
    sim.step_sampling(frame_time_s(1), ghosts_at);
    // 105 ms later: every 90 Hz frame between, each at its own time, then the display time.
    sampled.clear();
    sim.step_sampling(frame_time_s(1) + 0.105, ghosts_at);
    ASSERT_EQ(sampled.size(), 10u);
    for (std::size_t i = 0; i < 9; ++i) EXPECT_NEAR(sampled[i], frame_time_s(2 + i), 1e-9);
    EXPECT_NEAR(sampled.back(), frame_time_s(1) + 0.105, 1e-9);
    EXPECT_NEAR(sim.time(), frame_time_s(10), kSameTimeS);
    // 2 s later: the clock jumps, and only max_step_s of it is simulated.
    sampled.clear();
    sim.step_sampling(frame_time_s(190), ghosts_at);
    EXPECT_EQ(sampled.size(), 9u);
    EXPECT_NEAR(sampled.front(), frame_time_s(182), 1e-9);
    EXPECT_NEAR(sim.time(), frame_time_s(190), kSameTimeS);
    EXPECT_TRUE(sim.state_is_finite());
}

// The physics steps its own frames on ghosts sampled at their times: a display whose first
// frame falls after the first physics frame, as at 72 Hz or with jitter (the first frame is
// on time), steps the very same frames as 90 Hz; faster displays add one frame at time 0.
TEST(DisplayRate, ThePhysicsIsTheSameAtEveryRate) {
    const Scene scene = testing::sample_scene("lift_hold");
    RunOptions options;
    const RunResult at90 = run_scene(scene, options);
    ASSERT_TRUE(at90.success);
    for (const DisplayTiming display : {DisplayTiming{72.0, 0.0}, DisplayTiming{90.0, 2.0, 7},
                                        DisplayTiming{120.0, 0.0}, DisplayTiming{144.0, 2.0}}) {
        options.display = display;
        const RunResult run = run_scene(scene, options);
        EXPECT_TRUE(run.success) << display.rate_hz;
        EXPECT_EQ(run.display_hz, display.rate_hz);
        EXPECT_EQ(run.metrics.repeated_pose_frames, 0);
        if (display.rate_hz > 90.0) continue;
        ASSERT_EQ(run.bodies.size(), at90.bodies.size());
        // The same frames, but for the last: a display whose last frame falls before the
        // scene's end steps one frame fewer or more, in which a held cube may move by a float's
        // last bit (lift_hold: 3e-8 m).
        for (std::size_t i = 0; i < run.bodies.size(); ++i) {
            EXPECT_LT((run.bodies[i].second.position - at90.bodies[i].second.position).norm(), 1e-6)
                << display.rate_hz << " Hz, jitter " << display.jitter_ms << " ms";
        }
    }
}

// A tray carried up at 0.2 m/s, its targets set at 72 Hz display times: every physics frame
// moves it its share of the way, so it is on its path at every frame and carries what rests
// on it smoothly, as at 90 Hz; untimed, it would reach each target a frame early and stand
// still in between.
TEST(DisplayRate, KinematicTargetsAreReachedEvenlyOverThePhysicsFrames) {
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    Collider tray = static_box("tray", Vec3(0, 1, 0), Vec3(0.2, 0.01, 0.2));
    tray.motion = Motion::Kinematic;
    const ColliderHandle t = sim.add_collider(tray);
    const ColliderHandle c =
        sim.add_collider(testing::dynamic_box("cube", Vec3(0, 1.03, 0), 0.02, 0.1));
    const auto height_at = [](double time) { return 1.0 + 0.2 * time; };
    const auto no_hands = [](double) { return std::array<HandPose, 2>{}; };
    double worst_off_path = 0.0, slowest = 1.0, fastest = 0.0;
    for (int f = 1; f <= 72; ++f) {
        const double time = clock_seconds(f * frame_period_ns(72.0));
        EXPECT_TRUE(
            sim.set_kinematic_target(t, Pose{Vec3(0, height_at(time), 0), Quat::Identity()}, time));
        sim.step_sampling(time, no_hands);
        // The first target, set before the clock ran, is reached at once; the cube catches up.
        if (f < 5) continue;
        const BodyState tray_now = *sim.body_state(t);
        worst_off_path =
            std::max(worst_off_path, std::abs(tray_now.pose.position.y() - height_at(sim.time())));
        const double speed = sim.body_state(c)->linear_velocity.y();
        slowest = std::min(slowest, speed);
        fastest = std::max(fastest, speed);
    }
    EXPECT_LT(worst_off_path, 1e-6);
    EXPECT_GT(slowest, 0.15);
    EXPECT_LT(fastest, 0.25);
    EXPECT_NEAR(sim.body_state(c)->pose.position.y(), 1.23, 0.005);
    // Only kinematic colliders, finite poses and times.
    EXPECT_FALSE(sim.set_kinematic_target(c, Pose{Vec3::Zero(), Quat::Identity()}, 2.0));
    EXPECT_FALSE(sim.set_kinematic_target(t, Pose{Vec3::Zero(), Quat::Identity()}, NAN));
}

// Between physics frames a moving body is shown moved on at its velocities, as the hand is:
// shown where the last frame left it, the throw's projectile lagged the hand that held it
// (the hand as shown 14.2 mm into it at 72 Hz, 16.1 mm at 144 Hz; 1.0 mm on the 90 Hz frames).
TEST(DisplayRate, AHeldObjectIsShownWhereTheHandHoldingItIs) {
    const Scene scene = testing::sample_scene("throw");
    RunOptions options;
    for (const double rate : {72.0, 144.0}) {
        options.display = DisplayTiming{rate, 0.0};
        const RunResult run = run_scene(scene, options);
        EXPECT_TRUE(run.success) << rate;
        EXPECT_LT(run.metrics.max_shown_depth_mm, 2.5) << rate << " Hz";
    }
    // Fingers about to flick the sphere task's ball are shown no deeper into it than they can
    // go: moved as their ghosts moved, they were 3.2 mm into it at 120 Hz and 3.9 mm at 144 Hz.
    const Scene sphere = testing::sample_scene("sphere");
    for (const double rate : {120.0, 144.0}) {
        options.display = DisplayTiming{rate, 0.0};
        const RunResult run = run_scene(sphere, options);
        EXPECT_TRUE(run.success) << rate;
        EXPECT_LT(run.metrics.max_shown_depth_mm, 0.5) << rate << " Hz";
    }
    // A falling cube between frames: moved on from its frame at its velocity.
    Simulation sim(SimulationSettings{}, Vec3(0, -9.81, 0));
    const ColliderHandle cube =
        sim.add_collider(testing::dynamic_box("cube", Vec3(0, 2, 0), 0.02, 0.1));
    const auto no_hands = [](double) { return std::array<HandPose, 2>{}; };
    for (int f = 1; f <= 30; ++f) sim.step_sampling(frame_time_s(f), no_hands);
    const BodyState at_frame = *sim.body_state(cube);
    sim.step_sampling(frame_time_s(30) + 0.005, no_hands);
    const BodyState between = *sim.body_state(cube);
    EXPECT_NEAR((between.pose.position - at_frame.pose.position).y(),
                0.005 * at_frame.linear_velocity.y(), 1e-9);
}

TEST(DisplayRate, RunsRejectDisplayTimingOutOfRange) {
    const Scene scene = testing::sample_scene("free_motion");
    RunOptions options;
    for (const DisplayTiming display :
         {DisplayTiming{19.0, 0.0}, DisplayTiming{241.0, 0.0}, DisplayTiming{NAN, 0.0},
          DisplayTiming{90.0, -1.0}, DisplayTiming{144.0, 2.5}}) {
        options.display = display;
        EXPECT_THROW(run_scene(scene, options), std::invalid_argument)
            << display.rate_hz << " Hz, " << display.jitter_ms << " ms";
    }
}

}  // namespace
}  // namespace physhand
