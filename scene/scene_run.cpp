#include "scene_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "app_engine.h"
#include "float_transport.h"
#include "frame_clock.h"
#include "tracking.h"

namespace physhand {

SimulationSettings settings_for(const RunOptions& options) {
    SimulationSettings settings;
    if (options.drive) {
        const auto drive = find_drive(*options.drive);
        if (!drive) throw std::invalid_argument("unknown drive \"" + *options.drive + "\"");
        settings.drive = *drive;
    }
    if (options.substeps) {
        if (*options.substeps < 1) throw std::invalid_argument("substeps must be >= 1");
        settings.drive.substeps = *options.substeps;
    }
    settings.gating = options.gating;
    settings.sleeping = options.sleeping;
    return settings;
}

void check_display_timing(const DisplayTiming& display) {
    if (!(display.rate_hz >= kMinDisplayHz && display.rate_hz <= kMaxDisplayHz))
        throw std::invalid_argument("display rate must be from 20 to 240 Hz");
    if (!(display.jitter_ms >= 0.0 && display.jitter_ms < max_frame_jitter_ms(display.rate_hz)))
        throw std::invalid_argument("frame jitter must be >= 0 and under a third of a frame");
}

namespace {

// The fastest any hand part touching `collider` moved in the last frame, at its contact point.
double touching_part_speed(const Simulation& sim, ColliderHandle collider) {
    double fastest = 0.0;
    for (const ContactInfo& c : sim.contacts()) {
        if (c.collider != collider || c.other != 0) continue;
        const PhysicalHandState& hand = sim.hand(c.hand);
        const std::size_t j = index_of(c.joint);
        const Vec3 at_point =
            hand.linear_velocity[j] +
            hand.angular_velocity[j].cross(c.point - hand.joints.joints[j].position);
        fastest = std::max(fastest, at_point.norm());
    }
    return fastest;
}

}  // namespace

RunResult run_scene(const Scene& scene, const RunOptions& options) {
    return run_scene(scene, settings_for(options), options.seed, options.display,
                     options.measure_shown_depth);
}

RunResult run_scene(const Scene& input, const SimulationSettings& settings,
                    std::optional<std::uint64_t> seed, const DisplayTiming& display,
                    bool measure_shown_depth) {
    check_display_timing(display);
    Scene scene = input;
    if (seed) scene.tracking.seed = *seed;
    Simulation sim(settings, scene.gravity);

    AppEngine engine(scene);
    std::vector<ColliderHandle> handles;
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
        handles.push_back(sim.add_collider(round_to_float(as_declared(scene, i))));
        if (engine.simulates(i)) sim.take_hand_impulse(handles[i]);  // counted from now on
    }
    // The app's objects are judged where the hands' simulation has them (each frame, where
    // the app's engine put them), as an app reading them back through the layer sees them.
    auto handle_of = [&](const std::string& id) -> std::optional<ColliderHandle> {
        for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
            if (scene.colliders[i].id == id) return handles[i];
        }
        return std::nullopt;
    };
    const PredicateEvaluator::BodyLookup lookup = [&](const std::string& id) {
        const auto h = handle_of(id);
        return h ? sim.body_state(*h) : std::nullopt;
    };

    const TrackedHands tracked(scene);
    PredicateEvaluator predicates(scene);
    RunMetrics metrics;
    const std::int64_t period_ns = frame_period_ns(display.rate_hz);
    const auto jitter_ns = std::llround(display.jitter_ms * 1e6);
    double previous_t = 0.0;
    for (int f = 1;; ++f) {
        const double t =
            clock_seconds(f * period_ns + frame_jitter_ns(f, jitter_ns, display.jitter_seed));
        engine.step(t - previous_t);
        previous_t = t;
        for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
            if (!scene.colliders[i].path.empty()) {
                sim.set_kinematic_target(handles[i], round_to_float(scene.colliders[i].pose_at(t)),
                                         t);
            } else if (engine.simulates(i)) {
                sim.set_kinematic_target(handles[i], round_to_float(engine.state(i).pose), t);
            }
        }
        // As a runtime reports them: in floats, at any time asked for.
        const auto ghosts_at = [&](double time) {
            return std::array<HandPose, 2>{round_to_float(tracked.ghost(HandSide::Left, time)),
                                           round_to_float(tracked.ghost(HandSide::Right, time))};
        };
        const std::array<HandPose, 2> ghosts = ghosts_at(t);
        const auto start = std::chrono::steady_clock::now();
        sim.step_sampling(t, ghosts_at);
        const double step_us =
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                .count();

        for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
            if (!engine.simulates(i)) continue;
            const HandImpulse given = sim.take_hand_impulse(handles[i]);
            engine.apply(i, round_to_float(given.linear), round_to_float(given.angular));
        }

        std::array<std::optional<Pose>, 2> wrists;
        for (HandSide side : kHandSides) {
            const PhysicalHandState& hand = sim.hand(side);
            metrics.add_hand(t, side, ghosts[static_cast<int>(side)], hand.joints, hand.in_contact);
            if (hand.joints.active) wrists[static_cast<int>(side)] = hand.joints[Joint::Wrist];
        }
        for (std::size_t i = 0, body = 0; i < scene.colliders.size(); ++i) {
            if (scene.colliders[i].motion == Motion::Dynamic)
                metrics.add_body(t, body++, *sim.body_state(handles[i]),
                                 touching_part_speed(sim, handles[i]));
        }
        metrics.add_frame({.step_us = step_us,
                           .max_penetration_m = sim.last_max_penetration(),
                           .max_shown_depth_m = measure_shown_depth
                                                    ? std::max(sim.shown_depth(HandSide::Left),
                                                               sim.shown_depth(HandSide::Right))
                                                    : 0.0,
                           .max_joint_gap_m = std::max(sim.hand(HandSide::Left).max_joint_gap,
                                                       sim.hand(HandSide::Right).max_joint_gap),
                           .max_body_speed = sim.last_max_body_speed(),
                           .max_requested_speed = sim.last_max_requested_speed(),
                           .nonfinite = !sim.state_is_finite()});
        predicates.add_frame(t, lookup, wrists);
        if (scene_over(t, scene.duration_s)) break;
    }

    RunResult result;
    result.scene = scene.name;
    result.drive = settings.drive.name;
    result.substeps = settings.drive.substeps;
    result.display_hz = display.rate_hz;
    result.predicates = predicates.finish();
    result.success = std::all_of(result.predicates.begin(), result.predicates.end(),
                                 [](const PredicateResult& p) { return p.passed; });
    result.metrics = metrics.summary();
    result.guards = sim.guard_counters();
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
        if (scene.colliders[i].motion == Motion::Dynamic) {
            result.bodies.emplace_back(scene.colliders[i].id, sim.body_state(handles[i])->pose);
        }
    }
    return result;
}

}  // namespace physhand
