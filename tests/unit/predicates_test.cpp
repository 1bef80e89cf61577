#include "predicates.h"

#include <gtest/gtest.h>

#include <map>

#include "quantile.h"
#include "run_metrics.h"

namespace physhand {
namespace {

Collider box_at(const std::string& id, const Vec3& p) {
    Collider c;
    c.id = id;
    c.shape.half_extents = Vec3::Constant(0.02);
    c.motion = Motion::Dynamic;
    c.mass = 0.1;
    c.pose.position = p;
    return c;
}

struct Bodies {
    std::map<std::string, BodyState> states;
    PredicateEvaluator::BodyLookup lookup() const {
        return [this](const std::string& id) -> std::optional<BodyState> {
            auto it = states.find(id);
            return it == states.end() ? std::nullopt : std::optional<BodyState>(it->second);
        };
    }
    void place(const std::string& id, const Vec3& p, const Vec3& v = Vec3::Zero()) {
        states[id].pose.position = p;
        states[id].linear_velocity = v;
    }
};

TEST(Predicates, EndAndTimedPredicatesUseTheRightFrame) {
    Scene s;
    s.colliders = {box_at("a", Vec3(0, 1, 0)), box_at("b", Vec3(0, 1, 0))};
    s.success = {AbovePredicate{"a", 0.9, std::nullopt}, AbovePredicate{"a", 0.9, 0.5},
                 DisplacedPredicate{"b", 0.1, std::nullopt},
                 InsidePredicate{"a", Vec3(0, 0.5, 0), Vec3::Constant(0.1), std::nullopt},
                 AtRestPredicate{"b", 0.05, std::nullopt}};
    PredicateEvaluator eval(s);
    Bodies bodies;
    bodies.place("a", Vec3(0, 1, 0));
    bodies.place("b", Vec3(0, 1, 0));
    eval.add_frame(0.5, bodies.lookup(), {});
    bodies.place("a", Vec3(0, 0.5, 0));
    bodies.place("b", Vec3(0.2, 1, 0), Vec3(0.01, 0, 0));
    eval.add_frame(1.0, bodies.lookup(), {});
    const auto r = eval.finish();
    ASSERT_EQ(r.size(), 5u);
    EXPECT_FALSE(r[0].passed);  // at the end a is at 0.5
    EXPECT_TRUE(r[1].passed);   // at 0.5 s it was still up
    EXPECT_TRUE(r[2].passed);   // b moved 0.2 m from its scene pose
    EXPECT_TRUE(r[3].passed);
    EXPECT_TRUE(r[4].passed);
    EXPECT_EQ(r[2].type, "displaced");
}

TEST(Predicates, StackedNeedsOrderAlignmentAndRest) {
    Scene s;
    s.colliders = {box_at("a", Vec3::Zero()), box_at("b", Vec3::Zero()), box_at("c", Vec3::Zero())};
    s.success = {StackedPredicate{{"a", "b", "c"}, 0.02, std::nullopt}};
    auto judge = [&](const Vec3& pb, const Vec3& pc, const Vec3& vc) {
        PredicateEvaluator eval(s);
        Bodies bodies;
        bodies.place("a", Vec3(0, 0.77, 0));
        bodies.place("b", pb);
        bodies.place("c", pc, vc);
        eval.add_frame(1.0, bodies.lookup(), {});
        return eval.finish()[0].passed;
    };
    EXPECT_TRUE(judge(Vec3(0.01, 0.81, 0), Vec3(0.02, 0.85, 0), Vec3::Zero()));
    EXPECT_FALSE(judge(Vec3(0.03, 0.81, 0), Vec3(0.03, 0.85, 0), Vec3::Zero()));   // b off a
    EXPECT_FALSE(judge(Vec3(0.0, 0.81, 0), Vec3(0.0, 0.80, 0), Vec3::Zero()));     // c below b
    EXPECT_FALSE(judge(Vec3(0.0, 0.81, 0), Vec3(0.0, 0.85, 0), Vec3(0.1, 0, 0)));  // c moving
}

TEST(Predicates, HeldMeasuresSlipInTheWristFrame) {
    Scene s;
    s.colliders = {box_at("cube", Vec3::Zero())};
    s.success = {HeldPredicate{"cube", 0.9, 1.0, 2.0}};
    PredicateEvaluator eval(s);
    Bodies bodies;
    for (int f = 0; f <= 30; ++f) {
        const double t = 0.9 + f * 0.05;
        // The wrist turns and rises; the cube turns with it but slides 4 mm along its x.
        const Pose wrist{Vec3(0, 1.0 + 0.01 * f, 0),
                         Quat(Eigen::AngleAxisd(0.05 * f, Vec3::UnitY()))};
        const double slide = t >= 1.0 ? std::min(0.004, (t - 1.0) * 0.004) : 0.0;
        bodies.place("cube", wrist * Vec3(0.05 + slide, -0.05, 0));
        eval.add_frame(t, bodies.lookup(), {std::nullopt, wrist});
    }
    const auto r = eval.finish();
    EXPECT_TRUE(r[0].passed);
    ASSERT_TRUE(r[0].slip_mm.has_value());
    EXPECT_NEAR(*r[0].slip_mm, 4.0, 1e-6);
}

TEST(Predicates, HeldFailsWhenTheBodyDrops) {
    Scene s;
    s.colliders = {box_at("cube", Vec3::Zero())};
    s.success = {HeldPredicate{"cube", 0.9, 1.0, 2.0}};
    PredicateEvaluator eval(s);
    Bodies bodies;
    for (int f = 0; f <= 30; ++f) {
        bodies.place("cube", Vec3(0, f == 15 ? 0.85 : 1.0, 0));
        eval.add_frame(0.9 + f * 0.05, bodies.lookup(), {});
    }
    EXPECT_FALSE(eval.finish()[0].passed);
}

TEST(RunMetrics, QuantileIsNearestRank) {
    EXPECT_DOUBLE_EQ(quantile({5, 1, 4, 2, 3}, 0.5), 3);
    EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4}, 0.99), 4);
    EXPECT_DOUBLE_EQ(quantile({}, 0.5), 0);
}

TEST(RunMetrics, TrackingErrorSkipsJointsInRecentContact) {
    RunMetrics m;
    HandPose ghost = pose_hand(HandSide::Right, Pose{}, HandArticulation{});
    HandPose phys = ghost;
    phys.joints[index_of(Joint::IndexTip)].position.x() += 0.010;  // 10 mm off
    std::array<bool, kJointCount> contact{};
    contact[index_of(Joint::IndexTip)] = true;
    m.add_hand(0.0, HandSide::Right, ghost, phys, contact);  // in contact: not counted
    contact = {};
    m.add_hand(0.2, HandSide::Right, ghost, phys, contact);  // released 0.2 s ago: not counted
    m.add_hand(0.3, HandSide::Right, ghost, phys, contact);  // counted: 1 of 26 joints at 10 mm
    m.add_frame({.step_us = 5.0, .max_penetration_m = 0.002, .max_body_speed = 1.0});
    m.add_frame({.step_us = 7.0,
                 .max_penetration_m = 0.001,
                 .max_body_speed = 2.0,
                 .max_requested_speed = 25.0,
                 .nonfinite = true});
    const MetricsSummary s = m.summary();
    const double counted = 25 * 3 + 1;  // frames 1-3 for 25 joints, frame 3 for the tip
    EXPECT_NEAR(s.tracking_error_rms_mm, std::sqrt(100.0 / counted), 1e-9);
    EXPECT_NEAR(s.tracking_error_p99_mm, 10.0, 1e-9);
    EXPECT_NEAR(s.max_penetration_mm, 2.0, 1e-12);
    EXPECT_EQ(s.nonfinite_count, 1);
    EXPECT_EQ(s.frames, 2);
    EXPECT_DOUBLE_EQ(s.max_body_speed, 2.0);
    EXPECT_DOUBLE_EQ(s.max_requested_speed, 25.0);
}

// A hand that returns the previous frame's pose while its ghost moves judders: counted unless
// the ghost stood still or the hand touched something.
TEST(RunMetrics, RepeatedPoseFramesCountAHandThatDidNotMoveWithItsGhost) {
    RunMetrics m;
    const HandPose start = pose_hand(HandSide::Right, Pose{}, HandArticulation{});
    auto moved = [&](double x) {
        HandPose hand = start;
        for (Pose& joint : hand.joints) joint.position.x() += x;
        return hand;
    };
    std::array<bool, kJointCount> none{}, touching{};
    touching[index_of(Joint::IndexTip)] = true;
    m.add_hand(0.00, HandSide::Right, moved(0.000), moved(0.000), none);
    m.add_hand(0.01, HandSide::Right, moved(0.001), moved(0.001), none);
    m.add_hand(0.02, HandSide::Right, moved(0.002), moved(0.001), none);      // repeated
    m.add_hand(0.03, HandSide::Right, moved(0.003), moved(0.001), touching);  // touching
    m.add_hand(0.04, HandSide::Right, moved(0.00305), moved(0.001), none);    // ghost still
    m.add_hand(0.05, HandSide::Right, moved(0.004), moved(0.001), none);      // repeated
    EXPECT_EQ(m.summary().repeated_pose_frames, 2);
}

// Jerk is the third derivative of the wrist's and fingertips' paths: a path x = j t^3 / 6
// has jerk j, at any frame times.
TEST(RunMetrics, JerkOfACubicPathIsItsThirdDerivative) {
    RunMetrics m;
    const HandPose start = pose_hand(HandSide::Right, Pose{}, HandArticulation{});
    const std::array<bool, kJointCount> none{};
    const double jerk = 50.0, ghost_jerk = 20.0;
    for (const double t : {0.0, 0.011, 0.019, 0.031, 0.040, 0.056, 0.060}) {
        HandPose ghost = start, physical = start;
        for (std::size_t j = 0; j < kJointCount; ++j) {
            ghost.joints[j].position.y() += ghost_jerk * t * t * t / 6.0;
            physical.joints[j].position.z() += jerk * t * t * t / 6.0;
        }
        m.add_hand(t, HandSide::Right, ghost, physical, none);
    }
    const MetricsSummary s = m.summary();
    EXPECT_NEAR(s.jerk_rms, jerk, 1e-3);
    EXPECT_NEAR(s.ghost_jerk_rms, ghost_jerk, 1e-3);
    EXPECT_EQ(s.repeated_pose_frames, 0);
}

// A body's speed as it leaves the hand over the fastest part that touched it last, the
// contact counted as the last once 50 ms pass without another (docs/metrics.md); only a
// release at throwing speed counts as a throw.
TEST(RunMetrics, ReleaseSpeedRatioOfTheFastestThrow) {
    RunMetrics m;
    const HandPose still = pose_hand(HandSide::Right, Pose{}, HandArticulation{});
    const std::array<bool, kJointCount> none{};
    auto frame = [&](int f, double palm_speed, const Vec3& cube_velocity, bool touched) {
        const double t = f / 100.0;
        HandPose ghost = still;
        // The palm has moved palm_speed / 100 since the previous frame.
        ghost.joints[index_of(Joint::Palm)].position.x() = palm_speed * t;
        m.add_hand(t, HandSide::Right, ghost, ghost, none);
        BodyState cube;
        cube.linear_velocity = cube_velocity;
        cube.touched_by[static_cast<int>(HandSide::Right)] = touched;
        m.add_body(t, 0, cube, touched ? 2.4 : 0.0);  // a fingertip flicking at 2.4 m/s
        m.add_frame({.step_us = 1.0});
    };
    for (int f = 0; f <= 10; ++f) frame(f, 2.0, Vec3::Zero(), true);  // carried at 2 m/s
    frame(11, 2.0, Vec3(3, 0, 0), false);                             // let go at 0.10 s
    for (int f = 12; f <= 20; ++f) frame(f, 2.0, Vec3(2.5, 0, 0), false);
    const MetricsSummary s = m.summary();
    ASSERT_TRUE(s.throw_release);
    EXPECT_EQ(s.throw_release->body, 0u);
    EXPECT_DOUBLE_EQ(s.throw_release->time_s, 0.10);
    EXPECT_NEAR(s.throw_release->hand_speed, 2.0, 1e-9);
    EXPECT_NEAR(s.throw_release->part_speed, 2.4, 1e-9);
    EXPECT_NEAR(s.throw_release->leaving_speed, 3.0, 1e-9);
    EXPECT_NEAR(s.throw_release->body_speed, 2.5, 1e-9);  // at 0.15 s
    EXPECT_NEAR(s.throw_release->palm_speed, 2.0, 1e-9);
    ASSERT_TRUE(s.throw_release->ratio());
    EXPECT_NEAR(*s.throw_release->ratio(), 1.25, 1e-9);
    EXPECT_EQ(s.frames_touching_bodies[static_cast<int>(HandSide::Right)], 11);

    RunMetrics placing;  // the same, with the palm at 0.2 m/s: a body set down, not thrown
    for (int f = 0; f <= 20; ++f) {
        const double t = f / 100.0;
        HandPose ghost = still;
        ghost.joints[index_of(Joint::Palm)].position.x() = 0.2 * t;
        placing.add_hand(t, HandSide::Right, ghost, ghost, none);
        BodyState cube;
        cube.touched_by[static_cast<int>(HandSide::Right)] = f <= 10;
        placing.add_body(t, 0, cube);
        placing.add_frame({.step_us = 1.0});
    }
    EXPECT_FALSE(placing.summary().throw_release);
}

}  // namespace
}  // namespace physhand
