#include "predicates.h"

#include <cmath>
#include <cstdio>
#include <set>

namespace physhand {

namespace {

constexpr double kStackedMaxSpeed = 0.05;  // docs/scene-format.md: stacked bodies at rest

std::string fmt(const char* format, double a, double b = 0.0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, format, a, b);
    return buf;
}

PredicateTime at_of(const Predicate& p) {
    return std::visit(
        [](const auto& v) -> PredicateTime {
            if constexpr (requires { v.at; }) {
                return v.at;
            } else {
                return std::nullopt;
            }
        },
        p);
}

std::set<std::string> bodies_of(const Predicate& p) {
    return std::visit(
        [](const auto& v) -> std::set<std::string> {
            if constexpr (requires { v.bodies; }) {
                return {v.bodies.begin(), v.bodies.end()};
            } else {
                return {v.body};
            }
        },
        p);
}

PredicateResult judge(const Predicate& predicate, const Scene& scene,
                      const PredicateEvaluator::BodyLookup& bodies) {
    PredicateResult r;
    auto missing = [&r](const std::string& id) {
        r.detail = "body \"" + id + "\" not found";
        return r;
    };
    std::visit(
        [&](const auto& p) {
            using T = std::decay_t<decltype(p)>;
            if constexpr (std::is_same_v<T, AbovePredicate>) {
                r.type = "above";
                r.subject = p.body;
                const auto s = bodies(p.body);
                if (!s) return void(missing(p.body));
                r.passed = s->pose.position.y() >= p.min_y;
                r.detail = fmt("y %.4f m (min %.4f)", s->pose.position.y(), p.min_y);
            } else if constexpr (std::is_same_v<T, InsidePredicate>) {
                r.type = "inside";
                r.subject = p.body;
                const auto s = bodies(p.body);
                if (!s) return void(missing(p.body));
                const Vec3 d = (s->pose.position - p.center).cwiseAbs();
                r.passed = (d.array() <= p.half_extents.array()).all();
                r.detail =
                    fmt("%.4f m from the region's centre", (s->pose.position - p.center).norm());
            } else if constexpr (std::is_same_v<T, DisplacedPredicate>) {
                r.type = "displaced";
                r.subject = p.body;
                const auto s = bodies(p.body);
                const Collider* c = scene.find_collider(p.body);
                if (!s || !c) return void(missing(p.body));
                const double d = (s->pose.position - c->pose.position).norm();
                r.passed = d >= p.min_distance;
                r.detail = fmt("moved %.4f m (min %.4f)", d, p.min_distance);
            } else if constexpr (std::is_same_v<T, StackedPredicate>) {
                r.type = "stacked";
                r.passed = true;
                for (std::size_t i = 0; i < p.bodies.size(); ++i) {
                    r.subject += (i ? "+" : "") + p.bodies[i];
                    const auto s = bodies(p.bodies[i]);
                    if (!s) return void(missing(p.bodies[i]));
                    r.passed = r.passed && s->linear_velocity.norm() < kStackedMaxSpeed;
                    if (i == 0) continue;
                    const auto below = bodies(p.bodies[i - 1]);
                    const Vec3 d = s->pose.position - below->pose.position;
                    const double horizontal = std::hypot(d.x(), d.z());
                    r.passed = r.passed && d.y() > 0 && horizontal <= p.tolerance;
                    r.detail +=
                        (i > 1 ? ", " : "") + fmt("level %.0f: %.4f m off", double(i), horizontal);
                }
            } else if constexpr (std::is_same_v<T, AtRestPredicate>) {
                r.type = "at_rest";
                r.subject = p.body;
                const auto s = bodies(p.body);
                if (!s) return void(missing(p.body));
                const double v = s->linear_velocity.norm();
                r.passed = v <= p.max_speed;
                r.detail = fmt("speed %.4f m/s (max %.4f)", v, p.max_speed);
            } else {
                r.type = "held";
                r.subject = p.body;
            }
        },
        predicate);
    return r;
}

}  // namespace

PredicateEvaluator::PredicateEvaluator(const Scene& scene)
    : scene_(scene), done_(scene.success.size()), held_(scene.success.size()) {}

void PredicateEvaluator::add_frame(double t, const BodyLookup& bodies,
                                   const std::array<std::optional<Pose>, 2>& wrists) {
    for (std::size_t i = 0; i < scene_.success.size(); ++i) {
        const Predicate& p = scene_.success[i];
        if (std::holds_alternative<HeldPredicate>(p)) {
            observe_held(i, t, bodies, wrists);
            continue;
        }
        const PredicateTime at = at_of(p);
        if (at && !done_[i] && t >= *at - 1e-9) done_[i] = judge(p, scene_, bodies);
        for (const std::string& id : bodies_of(p)) {
            if (auto s = bodies(id)) last_[id] = *s;
        }
    }
}

void PredicateEvaluator::observe_held(std::size_t i, double t, const BodyLookup& bodies,
                                      const std::array<std::optional<Pose>, 2>& wrists) {
    const auto& p = std::get<HeldPredicate>(scene_.success[i]);
    HeldState& h = held_[i];
    if (t < p.from_s - 1e-9 || t > p.to_s + 1e-9) return;
    const auto s = bodies(p.body);
    if (!s) {
        h.failed = true;
        return;
    }
    const Vec3 c = s->pose.position;
    h.min_seen_y = std::min(h.min_seen_y, c.y());
    if (c.y() < p.min_y) h.failed = true;
    if (!h.seen) {
        h.seen = true;
        // The hand holding it: the nearer physical wrist when the hold starts.
        double best = std::numeric_limits<double>::infinity();
        for (int side = 0; side < 2; ++side) {
            if (!wrists[side]) continue;
            const double d = (wrists[side]->position - c).norm();
            if (d < best) {
                best = d;
                h.hand = side;
            }
        }
        if (h.hand >= 0) {
            h.in_wrist = wrists[h.hand]->inverse() * c;
            h.slip_known = true;
        }
        return;
    }
    if (h.hand >= 0 && wrists[h.hand]) {
        h.slip = std::max(h.slip, (wrists[h.hand]->inverse() * c - h.in_wrist).norm());
    }
}

std::vector<PredicateResult> PredicateEvaluator::finish() const {
    std::vector<PredicateResult> out;
    const BodyLookup last = [this](const std::string& id) -> std::optional<BodyState> {
        auto it = last_.find(id);
        return it == last_.end() ? std::nullopt : std::optional<BodyState>(it->second);
    };
    for (std::size_t i = 0; i < scene_.success.size(); ++i) {
        const Predicate& p = scene_.success[i];
        if (const auto* held = std::get_if<HeldPredicate>(&p)) {
            const HeldState& h = held_[i];
            PredicateResult r{"held", held->body, h.seen && !h.failed, "", std::nullopt};
            r.detail = h.seen ? fmt("lowest y %.4f m (min %.4f)", h.min_seen_y, held->min_y)
                              : "interval never reached";
            if (h.slip_known) r.slip_mm = h.slip * 1000.0;
            out.push_back(r);
        } else if (done_[i]) {
            out.push_back(*done_[i]);
        } else {
            out.push_back(judge(p, scene_, last));  // "end", or a time past the last frame
        }
    }
    return out;
}

}  // namespace physhand
