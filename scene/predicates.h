#pragma once

#include <array>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene.h"
#include "simulation.h"

namespace physhand {

struct PredicateResult {
    std::string type;
    std::string subject;  // body id, or ids joined by '+'
    bool passed = false;
    std::string detail;             // what was measured, for people
    std::optional<double> slip_mm;  // held predicates
};

// Evaluates a scene's success predicates from per-frame observations, so the
// physics-only runner and the app through the layer judge a run the same way.
class PredicateEvaluator {
  public:
    explicit PredicateEvaluator(const Scene& scene);

    using BodyLookup = std::function<std::optional<BodyState>(const std::string& id)>;
    // Physical wrists of both hands (nullopt: not tracked).
    void add_frame(double t, const BodyLookup& bodies,
                   const std::array<std::optional<Pose>, 2>& wrists);
    std::vector<PredicateResult> finish() const;

  private:
    void evaluate_at(std::size_t i, const BodyLookup& bodies);
    void observe_held(std::size_t i, double t, const BodyLookup& bodies,
                      const std::array<std::optional<Pose>, 2>& wrists);

    const Scene& scene_;
    std::vector<std::optional<PredicateResult>> done_;  // decided at an `at` time
    std::map<std::string, BodyState> last_;             // bodies at the latest frame
    struct HeldState {
        bool seen = false;
        bool failed = false;
        double min_seen_y = std::numeric_limits<double>::infinity();
        int hand = -1;
        Vec3 in_wrist = Vec3::Zero();
        double slip = 0.0;
        bool slip_known = false;
    };
    std::vector<HeldState> held_;
};

}  // namespace physhand
