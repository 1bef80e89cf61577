#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "collider.h"
#include "format_error.h"
#include "hand_skeleton.h"
#include "pose.h"

namespace physhand {

// Scene file, format physhand-scene/1 (docs/scene-format.md).

enum class Interpolation { Linear, Smooth };

struct Keyframe {
    double t = 0.0;
    Pose wrist;
    HandArticulation articulation;
};

// One recorded sample: 26 joints at time t (docs/scene-format.md "Recorded").
struct RecordedSample {
    double t = 0.0;
    HandPose hand;  // active when every joint was valid
};

struct HandScript {
    std::vector<Keyframe> keyframes;  // keyframed scripts
    Interpolation interpolation = Interpolation::Smooth;
    double scale = 1.0;
    std::vector<RecordedSample> recorded;  // recorded tracks (keyframes empty)
};

struct Dropout {
    HandSide hand = HandSide::Right;
    double from_s = 0.0;
    double to_s = 0.0;
};

struct Tracking {
    double rate_hz = 90.0;
    double noise_mm = 0.0;
    std::uint64_t seed = 1;
    std::vector<Dropout> dropouts;
};

// `at`: a time in seconds, or nullopt for "end".
using PredicateTime = std::optional<double>;

struct AbovePredicate {
    std::string body;
    double min_y = 0.0;
    PredicateTime at;
};
struct InsidePredicate {
    std::string body;
    Vec3 center = Vec3::Zero();
    Vec3 half_extents = Vec3::Zero();
    PredicateTime at;
};
struct DisplacedPredicate {
    std::string body;
    double min_distance = 0.0;
    PredicateTime at;
};
struct StackedPredicate {
    std::vector<std::string> bodies;
    double tolerance = 0.0;
    PredicateTime at;
};
struct HeldPredicate {
    std::string body;
    double min_y = 0.0;
    double from_s = 0.0;
    double to_s = 0.0;
};
struct AtRestPredicate {
    std::string body;
    double max_speed = 0.05;
    PredicateTime at;
};
using Predicate = std::variant<AbovePredicate, InsidePredicate, DisplacedPredicate,
                               StackedPredicate, HeldPredicate, AtRestPredicate>;

struct Scene {
    std::string name;
    std::string description;
    double duration_s = 0.0;
    Vec3 gravity{0, -9.81, 0};
    std::vector<Collider> colliders;
    std::array<std::optional<HandScript>, 2> hands;  // indexed by HandSide
    Tracking tracking;
    std::vector<Predicate> success;
    // Ids of dynamic colliders the app keeps in an engine of its own (AppEngine), coupled to
    // the hands through their impulses.
    std::vector<std::string> app_engine;

    const std::optional<HandScript>& hand(HandSide side) const {
        return hands[static_cast<int>(side)];
    }
    const Collider* find_collider(const std::string& id) const;
};

// Both throw FormatError for a file that does not conform.
Scene load_scene(const std::filesystem::path& file);
// `base_dir` resolves recorded-track paths.
Scene parse_scene(const std::string& json_text, const std::filesystem::path& base_dir);

}  // namespace physhand
