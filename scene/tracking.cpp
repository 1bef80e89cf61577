#include "tracking.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace physhand {

namespace {

// Fritsch–Carlson tangent: zero at extrema and flat stretches, so a hand that pauses at
// a keyframe never overshoots it (a grasp must not plunge through the table).
double monotone_tangent(double prev_slope, double next_slope) {
    if (prev_slope * next_slope <= 0.0) return 0.0;
    return 2.0 / (1.0 / prev_slope + 1.0 / next_slope);
}

double hermite(double p0, double p1, double m0, double m1, double dt, double s) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * dt * m0 + (-2 * s3 + 3 * s2) * p1 +
           (s3 - s2) * dt * m1;
}

// Monotone cubic through values[i] at times[i], evaluated in segment i at parameter s.
template <typename Get>
double smooth_value(const std::vector<Keyframe>& keys, std::size_t i, double s, Get get) {
    auto slope = [&](std::size_t a) {
        return (get(keys[a + 1]) - get(keys[a])) / (keys[a + 1].t - keys[a].t);
    };
    const double seg = slope(i);
    const double m0 = i == 0 ? 0.0 : monotone_tangent(slope(i - 1), seg);
    const double m1 = i + 2 >= keys.size() ? 0.0 : monotone_tangent(seg, slope(i + 1));
    return hermite(get(keys[i]), get(keys[i + 1]), m0, m1, keys[i + 1].t - keys[i].t, s);
}

HandPose evaluate_keyframes(const HandScript& script, HandSide side, double t) {
    const std::vector<Keyframe>& keys = script.keyframes;
    if (t <= keys.front().t || keys.size() == 1) {
        return pose_hand(side, keys.front().wrist, keys.front().articulation, script.scale);
    }
    if (t >= keys.back().t) {
        return pose_hand(side, keys.back().wrist, keys.back().articulation, script.scale);
    }
    const auto next = std::upper_bound(keys.begin(), keys.end(), t,
                                       [](double v, const Keyframe& k) { return v < k.t; });
    const std::size_t i = static_cast<std::size_t>(next - keys.begin()) - 1;
    const Keyframe& a = keys[i];
    const Keyframe& b = keys[i + 1];
    const double s = (t - a.t) / (b.t - a.t);

    Pose wrist;
    HandArticulation art;
    if (script.interpolation == Interpolation::Linear) {
        wrist = interpolate(a.wrist, b.wrist, s);
        for (std::size_t f = 0; f < kFingerCount; ++f) {
            art.curl[f] =
                a.articulation.curl[f] + (b.articulation.curl[f] - a.articulation.curl[f]) * s;
        }
        art.spread = a.articulation.spread + (b.articulation.spread - a.articulation.spread) * s;
    } else {
        for (int axis = 0; axis < 3; ++axis) {
            wrist.position[axis] = smooth_value(
                keys, i, s, [axis](const Keyframe& k) { return k.wrist.position[axis]; });
        }
        const double eased = s * s * (3 - 2 * s);
        wrist.orientation = a.wrist.orientation.slerp(eased, b.wrist.orientation);
        for (std::size_t f = 0; f < kFingerCount; ++f) {
            art.curl[f] = std::clamp(
                smooth_value(keys, i, s, [f](const Keyframe& k) { return k.articulation.curl[f]; }),
                0.0, 1.0);
        }
        art.spread = std::clamp(
            smooth_value(keys, i, s, [](const Keyframe& k) { return k.articulation.spread; }), -1.0,
            1.0);
    }
    return pose_hand(side, wrist, art, script.scale);
}

HandPose evaluate_recorded(const std::vector<RecordedSample>& samples, double t) {
    if (t <= samples.front().t) return samples.front().hand;
    if (t >= samples.back().t) return samples.back().hand;
    const auto next = std::upper_bound(samples.begin(), samples.end(), t,
                                       [](double v, const RecordedSample& r) { return v < r.t; });
    const RecordedSample& a = *(next - 1);
    const RecordedSample& b = *next;
    if (!a.hand.active || !b.hand.active) return a.hand;
    HandPose out = a.hand;
    const double s = (t - a.t) / (b.t - a.t);
    for (std::size_t j = 0; j < kJointCount; ++j) {
        out.joints[j] = interpolate(a.hand.joints[j], b.hand.joints[j], s);
        out.radii[j] = a.hand.radii[j] + (b.hand.radii[j] - a.hand.radii[j]) * s;
    }
    return out;
}

// Box–Muller on a fixed engine: the same seed gives the same noise on every platform.
class GaussianSource {
  public:
    explicit GaussianSource(std::uint64_t seed) : engine_(seed) {}
    double next() {
        const double u1 = (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53;
        const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
    }

  private:
    std::mt19937_64 engine_;
};

}  // namespace

HandPose evaluate_script(const HandScript& script, HandSide side, double t) {
    return script.keyframes.empty() ? evaluate_recorded(script.recorded, t)
                                    : evaluate_keyframes(script, side, t);
}

TrackedHands::TrackedHands(const Scene& scene)
    : rate_hz_(scene.tracking.rate_hz), dropouts_(scene.tracking.dropouts) {
    const std::size_t count = static_cast<std::size_t>(std::ceil(scene.duration_s * rate_hz_)) + 2;
    const double sigma = scene.tracking.noise_mm * 1e-3;
    for (HandSide side : kHandSides) {
        const std::optional<HandScript>& script = scene.hand(side);
        if (!script) continue;
        // One noise stream per hand, so adding a hand leaves the other's noise unchanged.
        GaussianSource noise(scene.tracking.seed * 2 + static_cast<std::uint64_t>(side));
        std::vector<HandPose>& out = samples_[static_cast<int>(side)];
        out.reserve(count);
        for (std::size_t k = 0; k < count; ++k) {
            HandPose hand = evaluate_script(*script, side, static_cast<double>(k) / rate_hz_);
            if (sigma > 0.0) {
                for (Pose& joint : hand.joints) {
                    joint.position += sigma * Vec3(noise.next(), noise.next(), noise.next());
                }
            }
            out.push_back(hand);
        }
    }
}

bool TrackedHands::dropped(HandSide side, double t) const {
    return std::any_of(dropouts_.begin(), dropouts_.end(), [&](const Dropout& d) {
        return d.hand == side && t >= d.from_s && t < d.to_s;
    });
}

HandPose TrackedHands::ghost(HandSide side, double t) const {
    const std::vector<HandPose>& samples = samples_[static_cast<int>(side)];
    if (samples.empty() || !std::isfinite(t)) return HandPose{};
    const double x = std::clamp(t * rate_hz_, 0.0, static_cast<double>(samples.size() - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(x), samples.size() - 2);
    const double s = x - static_cast<double>(i);
    HandPose out = samples[i];
    if (out.active && samples[i + 1].active) {
        for (std::size_t j = 0; j < kJointCount; ++j) {
            out.joints[j] = interpolate(samples[i].joints[j], samples[i + 1].joints[j], s);
        }
    }
    if (dropped(side, t)) out.active = false;
    return out;
}

}  // namespace physhand
