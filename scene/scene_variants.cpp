#include "scene_variants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "tracking.h"

namespace physhand {

namespace {

constexpr double kDropoutLength = 0.3;  // s: the longest loss optical tracking has every session

std::string printed(const char* pattern, double value) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, pattern, value);
    return buffer;
}

// The time span of a hand's script, first to last sample.
std::pair<double, double> script_span(const HandScript& script) {
    if (!script.keyframes.empty()) return {script.keyframes.front().t, script.keyframes.back().t};
    if (!script.recorded.empty()) return {script.recorded.front().t, script.recorded.back().t};
    return {0.0, 0.0};
}

template <typename F>
void for_each_time(Scene& scene, F&& scale) {
    for (auto& hand : scene.hands) {
        if (!hand) continue;
        for (Keyframe& k : hand->keyframes) k.t = scale(k.t);
        for (RecordedSample& s : hand->recorded) s.t = scale(s.t);
    }
    for (Collider& c : scene.colliders) {
        for (TimedPose& p : c.path) p.t = scale(p.t);
    }
    for (Dropout& d : scene.tracking.dropouts) {
        d.from_s = scale(d.from_s);
        d.to_s = scale(d.to_s);
    }
    for (Predicate& p : scene.success) {
        std::visit(
            [&](auto& pred) {
                if constexpr (requires { pred.from_s; }) {
                    pred.from_s = scale(pred.from_s);
                    pred.to_s = scale(pred.to_s);
                } else {
                    if (pred.at) pred.at = scale(*pred.at);
                }
            },
            p);
    }
}

// Applies `move` to every pose in the scene: colliders and their paths, the hands' keyframed
// wrists and recorded joints.
template <typename F>
void for_each_pose(Scene& scene, F&& move) {
    for (Collider& c : scene.colliders) {
        move(c.pose);
        for (TimedPose& p : c.path) move(p.pose);
    }
    for (auto& hand : scene.hands) {
        if (!hand) continue;
        for (Keyframe& k : hand->keyframes) move(k.wrist);
        for (RecordedSample& s : hand->recorded) {
            for (Pose& j : s.hand.joints) move(j);
        }
    }
}

Vec3 mirror_point(const Vec3& p) {
    return Vec3(-p.x(), p.y(), p.z());
}

void mirror_shape(Shape& shape) {
    for (Vec3& v : shape.vertices) v = mirror_point(v);
    // A reflection turns every triangle inside out: swap two corners to keep it facing out.
    for (auto& tri : shape.indices) std::swap(tri[1], tri[2]);
    shape.normal = mirror_point(shape.normal);
}

}  // namespace

Scene mirrored(const Scene& input) {
    Scene scene = input;
    scene.gravity = mirror_point(scene.gravity);
    // Shapes are symmetric about their own axes except hulls and meshes, whose vertices are
    // reflected in the collider's frame; the frame itself is reflected as a pose.
    for_each_pose(scene, [](Pose& pose) { pose = mirror_x(pose); });
    for (Collider& c : scene.colliders) mirror_shape(c.shape);
    std::swap(scene.hands[0], scene.hands[1]);
    for (Dropout& d : scene.tracking.dropouts)
        d.hand = d.hand == HandSide::Left ? HandSide::Right : HandSide::Left;
    for (Predicate& p : scene.success) {
        if (auto* inside = std::get_if<InsidePredicate>(&p))
            inside->center = mirror_point(inside->center);
    }
    return scene;
}

Scene shifted(const Scene& input, const Vec3& offset) {
    Scene scene = input;
    for_each_pose(scene, [&](Pose& pose) { pose.position += offset; });
    for (Predicate& p : scene.success) {
        std::visit(
            [&](auto& predicate) {
                using T = std::decay_t<decltype(predicate)>;
                if constexpr (std::is_same_v<T, InsidePredicate>) {
                    predicate.center += offset;
                } else if constexpr (std::is_same_v<T, AbovePredicate> ||
                                     std::is_same_v<T, HeldPredicate>) {
                    predicate.min_y += offset.y();
                }
            },
            p);
    }
    return scene;
}

Scene turned(const Scene& input, double degrees) {
    const double quarters = degrees / 90.0;
    const bool quarter_turn = std::abs(quarters - std::round(quarters)) < 1e-9;
    const bool has_region =
        std::any_of(input.success.begin(), input.success.end(),
                    [](const Predicate& p) { return std::holds_alternative<InsidePredicate>(p); });
    if (has_region && !quarter_turn)
        throw std::invalid_argument(
            "turned: scene '" + input.name +
            "' has an 'inside' region, which turns only by multiples of 90 degrees");
    Scene scene = input;
    const Quat turn(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Vec3::UnitY()));
    for_each_pose(scene, [&](Pose& pose) {
        pose.position = turn * pose.position;
        pose.orientation = (turn * pose.orientation).normalized();
    });
    scene.gravity = turn * scene.gravity;
    for (Predicate& p : scene.success) {
        if (auto* inside = std::get_if<InsidePredicate>(&p)) {
            inside->center = turn * inside->center;
            if (std::lround(quarters) % 2 != 0)
                std::swap(inside->half_extents.x(), inside->half_extents.z());
        }
    }
    return scene;
}

Scene heavier(const Scene& input, double factor) {
    Scene scene = input;
    for (Collider& c : scene.colliders) {
        if (c.motion == Motion::Dynamic) c.mass *= factor;
    }
    scene.name = input.name + "/mass/" + printed("x%g", factor);
    return scene;
}

Scene sped_up(const Scene& input, double speed) {
    Scene scene = input;
    for_each_time(scene, [speed](double t) { return t / speed; });
    scene.duration_s = std::max(input.duration_s, input.duration_s / speed);
    return scene;
}

Scene sped_up_aiming(const Scene& input, double speed, std::string& adapted) {
    adapted.clear();
    std::vector<double> times;
    for (const auto& hand : input.hands) {
        if (!hand) continue;
        for (const Keyframe& k : hand->keyframes) times.push_back(k.t);
    }
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    // The time map, piecewise linear through the keyframe times: a stroke keeps its length.
    std::vector<double> mapped(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
        if (i == 0) {
            mapped[i] = times[i] / speed;
            continue;
        }
        const double length = times[i] - times[i - 1];
        bool stroke = false;
        for (HandSide side : kHandSides) {
            const auto& hand = input.hand(side);
            if (!hand || hand->keyframes.empty()) continue;
            const Vec3 from = evaluate_script(*hand, side, times[i - 1])[Joint::Wrist].position;
            const Vec3 to = evaluate_script(*hand, side, times[i])[Joint::Wrist].position;
            stroke = stroke || (to - from).norm() > kStrokeSpeed * length;
        }
        mapped[i] = mapped[i - 1] + (stroke ? length : length / speed);
        if (stroke) {
            adapted += (adapted.empty() ? "throw kept at its own pace: " : ", ") +
                       printed("%.2f", times[i - 1]) + printed("-%.2f s", times[i]);
        }
    }
    if (adapted.empty()) return sped_up(input, speed);
    Scene scene = input;
    const auto map_time = [&](double t) {
        if (t <= times.front()) return t / speed;
        const auto after = std::upper_bound(times.begin(), times.end(), t);
        if (after == times.end()) return mapped.back() + (t - times.back()) / speed;
        const std::size_t i = static_cast<std::size_t>(after - times.begin());
        const double u = (t - times[i - 1]) / (times[i] - times[i - 1]);
        return mapped[i - 1] + u * (mapped[i] - mapped[i - 1]);
    };
    for_each_time(scene, map_time);
    scene.duration_s = std::max(input.duration_s, map_time(input.duration_s));
    return scene;
}

Scene squeezed(const Scene& input, double curl) {
    Scene scene = input;
    for (auto& hand : scene.hands) {
        if (!hand || hand->keyframes.empty()) continue;
        auto& keys = hand->keyframes;
        const auto& final_curl = keys.back().articulation.curl;
        std::size_t first = keys.size() - 1;
        while (first > 0 && keys[first - 1].articulation.curl == final_curl) --first;
        for (std::size_t k = first; k < keys.size(); ++k) {
            for (std::size_t finger = 1; finger < kFingerCount; ++finger) {
                double& c = keys[k].articulation.curl[finger];
                c = std::max(c, curl);
            }
        }
    }
    scene.name = input.name + "/squeeze/" + printed("%g", curl);
    return scene;
}

std::vector<SceneVariant> scene_variants(const Scene& base, const VariantOptions& options) {
    std::vector<SceneVariant> out;
    auto add = [&](std::string family, std::string name, Scene scene, std::string adapted = {}) {
        scene.name = base.name + "/" + family + "/" + name;
        out.push_back({std::move(family), std::move(name), std::move(scene), std::move(adapted)});
    };

    for (double factor : {0.3, 3.0}) add("mass", printed("x%g", factor), heavier(base, factor));
    {
        Scene s = base;
        for (Collider& c : s.colliders) {
            if (c.motion == Motion::Dynamic) c.friction = 0.5;
        }
        add("friction", "0.5", std::move(s));
    }
    for (double speed : {0.7, 1.3}) {
        std::string adapted;
        Scene s = sped_up_aiming(base, speed, adapted);
        add("speed", printed("x%g", speed), std::move(s), std::move(adapted));
    }
    for (double scale : {0.75, 1.25}) {
        std::string adapted;
        Scene s = resized(base, scale, adapted);
        add("size", printed("x%g", scale), std::move(s), std::move(adapted));
    }
    for (int seed = 1; seed <= options.seeds; ++seed) {
        for (double rate : {30.0, 60.0}) {
            Scene s = base;
            s.tracking.rate_hz = rate;
            s.tracking.noise_mm = 2.0;
            s.tracking.seed = static_cast<std::uint64_t>(seed);
            add("tracking", printed("%ghz_2mm_seed", rate) + std::to_string(seed), std::move(s));
        }
        Scene noisy = base;
        noisy.tracking.noise_mm = 3.0;
        noisy.tracking.seed = static_cast<std::uint64_t>(seed);
        add("noise", "3mm_seed" + std::to_string(seed), std::move(noisy));

        std::mt19937_64 rng(static_cast<std::uint64_t>(seed) * 7919u);
        Scene dropped = base;
        std::string when;
        for (HandSide side : kHandSides) {
            const auto& hand = base.hand(side);
            if (!hand) continue;
            const auto [from, to] = script_span(*hand);
            const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
            const double start = from + u * std::max(0.0, to - from - kDropoutLength);
            dropped.tracking.dropouts.push_back({side, start, start + kDropoutLength});
            when += (when.empty() ? "" : "+") + printed("%.2fs", start);
        }
        add("dropout", "300ms_at_" + when, std::move(dropped));
    }
    add("mirror", "left", mirrored(base));
    return out;
}

}  // namespace physhand
