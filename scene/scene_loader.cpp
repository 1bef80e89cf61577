#include <algorithm>
#include <bitset>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <utility>

#include "collider_syntax.h"
#include "scene.h"

namespace physhand {

const Collider* Scene::find_collider(const std::string& id) const {
    const auto it = std::find_if(colliders.begin(), colliders.end(),
                                 [&](const Collider& c) { return c.id == id; });
    return it == colliders.end() ? nullptr : &*it;
}

namespace {

using namespace syntax;
namespace fs = std::filesystem;

constexpr std::string_view kFormat = "physhand-scene/1";

constexpr std::array<Named<Interpolation>, 2> kInterpolations = {{
    {"linear", Interpolation::Linear},
    {"smooth", Interpolation::Smooth},
}};
constexpr std::array<Named<HandSide>, 2> kSides = {{
    {"left", HandSide::Left},
    {"right", HandSide::Right},
}};

constexpr std::string_view kSceneKeys[] = {"format",  "name",      "description", "duration_s",
                                           "gravity", "colliders", "hands",       "tracking",
                                           "success", "app_engine"};
constexpr std::string_view kHandsKeys[] = {"left", "right"};
constexpr std::string_view kHandKeys[] = {"keyframes", "interpolation", "scale", "track"};
constexpr std::string_view kKeyframeKeys[] = {"t", "wrist", "curl", "spread"};
constexpr std::string_view kTrackingKeys[] = {"rate_hz", "noise_mm", "seed", "dropouts"};
constexpr std::string_view kDropoutKeys[] = {"hand", "from_s", "to_s"};
constexpr std::string_view kPredicateKeys[] = {"type"};
constexpr std::string_view kRegionKeys[] = {"center", "half_extents"};

// ---- Hands ----------------------------------------------------------------------------

std::vector<Keyframe> read_keyframes(const Node& node) {
    std::vector<Keyframe> keyframes;
    for (const Node& item : node.array(1, "expected a non-empty array")) {
        const Object obj(item);
        obj.allow(kKeyframeKeys);
        // Absent keys repeat the previous keyframe (the first defaults to an open hand).
        Keyframe k = keyframes.empty() ? Keyframe{} : keyframes.back();
        k.t = read_time_after(obj, last_time(keyframes));
        if (const auto wrist = obj.find("wrist")) {
            k.wrist = read_pose(*wrist);
        } else if (keyframes.empty()) {
            fail_at(obj.path_of("wrist"), "required in the first keyframe");
        }
        if (const auto curl = obj.find("curl")) {
            const auto e = curl->numbers(kFingerCount);
            for (std::size_t i = 0; i < kFingerCount; ++i) {
                k.articulation.curl[i] = e[i].in_range(0, 1);
            }
        }
        k.articulation.spread = obj.get_or(
            "spread", [](const Node& n) { return n.in_range(-1, 1); }, k.articulation.spread);
        keyframes.push_back(k);
    }
    return keyframes;
}

// ---- Recorded tracks ------------------------------------------------------------------

constexpr std::string_view kTrackHeader = "t,joint,px,py,pz,qx,qy,qz,qw,radius,valid";

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    for (std::size_t start = 0;;) {
        const std::size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end - start));
        if (end == std::string_view::npos) return parts;
        start = end + 1;
    }
}

// Recordings may come from Windows tools.
std::string_view without_cr(std::string_view line) {
    return line.ends_with('\r') ? line.substr(0, line.size() - 1) : line;
}

struct TrackRow {
    double t = 0.0;
    std::size_t joint = 0;
    Pose pose;
    double radius = 0.0;
    bool valid = false;
};

// A track CSV; errors read "<track path>: <file>:<line>: <what>".
class TrackFile {
  public:
    TrackFile(const Node& node, std::string name) : node_(node), name_(std::move(name)) {}

    [[noreturn]] void fail(std::size_t line, std::string_view what) const {
        node_.fail(name_ + ':' + std::to_string(line) + ": " + std::string(what));
    }

    TrackRow parse_row(std::size_t line, std::string_view text) const {
        static const std::vector<std::string_view> columns = split(kTrackHeader, ',');
        const auto fields = split(text, ',');
        if (fields.size() != columns.size()) {
            fail(line, "expected " + std::to_string(columns.size()) + " fields, got " +
                           std::to_string(fields.size()));
        }
        std::vector<double> v(fields.size());
        for (std::size_t i = 0; i < fields.size(); ++i) {
            const auto [end, error] =
                std::from_chars(fields[i].data(), fields[i].data() + fields[i].size(), v[i]);
            if (error != std::errc() || end != fields[i].data() + fields[i].size() ||
                !std::isfinite(v[i])) {
                fail(line, std::string(columns[i]) + ": expected a finite number, got " +
                               in_quotes(fields[i]));
            }
        }
        TrackRow row;
        row.t = v[0];
        if (!(v[1] >= 0 && v[1] < kJointCount && v[1] == std::floor(v[1]))) {
            fail(line,
                 "joint: expected an integer in [0, " + std::to_string(kJointCount - 1) + "]");
        }
        row.joint = static_cast<std::size_t>(v[1]);
        if (v[10] != 0 && v[10] != 1) fail(line, "valid: expected 0 or 1");
        row.valid = v[10] == 1;
        row.pose.position = {v[2], v[3], v[4]};
        const auto q = unit_quaternion(v[5], v[6], v[7], v[8]);
        // Runtimes may zero the pose of a joint they do not track.
        if (!q && row.valid) fail(line, "zero quaternion on a valid row");
        row.pose.orientation = q.value_or(Quat::Identity());
        if (!(v[9] >= 0)) fail(line, "radius: expected a number >= 0");
        row.radius = v[9];
        return row;
    }

  private:
    const Node& node_;
    std::string name_;
};

std::vector<RecordedSample> read_track(const Node& node, const fs::path& base_dir) {
    const std::string name = node.non_empty_string();
    const fs::path file = base_dir / name;
    std::ifstream in(file);
    if (!in) node.fail("cannot open " + file.string());
    const TrackFile track(node, name);

    std::string text;
    if (!std::getline(in, text) || without_cr(text) != kTrackHeader) {
        track.fail(1, "expected the header " + in_quotes(kTrackHeader));
    }
    std::vector<RecordedSample> samples;
    std::bitset<kJointCount> seen;  // joints of samples.back()
    std::size_t sample_line = 0;    // where samples.back() starts
    const auto check_complete = [&] {
        if (!seen.all()) {
            track.fail(sample_line, "the sample at t=" + str(samples.back().t) + " has " +
                                        std::to_string(seen.count()) + " joints (expected " +
                                        std::to_string(kJointCount) + ")");
        }
    };
    for (std::size_t line = 2; std::getline(in, text); ++line) {
        const TrackRow row = track.parse_row(line, without_cr(text));
        if (samples.empty() || row.t != samples.back().t) {
            if (!samples.empty()) {
                check_complete();
                if (row.t < samples.back().t) {
                    track.fail(line, "t=" + str(row.t) + " is before the previous sample's t=" +
                                         str(samples.back().t));
                }
            }
            samples.push_back({row.t, {}});
            samples.back().hand.active = true;
            seen.reset();
            sample_line = line;
        }
        if (seen[row.joint]) {
            track.fail(line,
                       "joint " + std::to_string(row.joint) + " appears twice at t=" + str(row.t));
        }
        seen.set(row.joint);
        HandPose& hand = samples.back().hand;
        hand.joints[row.joint] = row.pose;
        hand.radii[row.joint] = row.radius;
        hand.active = hand.active && row.valid;
    }
    if (samples.empty()) track.fail(1, "no samples after the header");
    check_complete();
    return samples;
}

HandScript read_hand(const Node& node, const fs::path& base_dir) {
    const Object obj(node);
    obj.allow(kHandKeys);
    const auto keyframes = obj.find("keyframes");
    const auto track = obj.find("track");
    if (keyframes && track) node.fail("expected either keyframes or track, not both");
    if (!keyframes && !track) node.fail("expected keyframes or track");

    HandScript hand;
    if (track) {
        for (const std::string_view key : {"interpolation", "scale"}) {
            obj.forbid(key, "only allowed with keyframes");
        }
        hand.recorded = read_track(*track, base_dir);
        return hand;
    }
    hand.keyframes = read_keyframes(*keyframes);
    hand.interpolation = obj.get_or(
        "interpolation",
        [](const Node& n) { return n.choice(kInterpolations, "interpolation").value; },
        hand.interpolation);
    hand.scale = obj.get_or("scale", &Node::positive, hand.scale);
    return hand;
}

// ---- Tracking -------------------------------------------------------------------------

Dropout read_dropout(const Node& node) {
    const Object obj(node);
    obj.allow(kDropoutKeys);
    Dropout d;
    d.hand = obj.at("hand").choice(kSides, "hand").value;
    std::tie(d.from_s, d.to_s) = read_interval(obj);
    return d;
}

Tracking read_tracking(const Node& node) {
    const Object obj(node);
    obj.allow(kTrackingKeys);
    Tracking t;
    t.rate_hz = obj.get_or("rate_hz", &Node::positive, t.rate_hz);
    t.noise_mm = obj.get_or("noise_mm", &Node::non_negative, t.noise_mm);
    t.seed = obj.get_or("seed", &Node::unsigned_integer, t.seed);
    if (const auto dropouts = obj.find("dropouts")) {
        for (const Node& item : dropouts->array()) t.dropouts.push_back(read_dropout(item));
    }
    return t;
}

// ---- Success predicates ---------------------------------------------------------------

std::string read_body(const Node& node, const Scene& scene) {
    std::string id = node.non_empty_string();
    if (!scene.find_collider(id)) node.fail("no collider with id " + in_quotes(id));
    return id;
}

PredicateTime read_at(const Object& obj) {
    const auto at = obj.find("at");
    if (!at || at->value() == "end") return std::nullopt;
    if (at->value().is_number()) {
        const double t = at->value().get<double>();
        if (std::isfinite(t) && t >= 0) return t;
    }
    at->fail(R"(expected a time >= 0 or "end")");
}

struct PredicateType {
    std::string_view name;
    std::vector<std::string_view> keys;  // besides "type"
    Predicate (*read)(const Object&, const Scene&);
};

const std::array<PredicateType, 6> kPredicateTypes = {{
    {"above",
     {"body", "min_y", "at"},
     [](const Object& o, const Scene& s) -> Predicate {
         return AbovePredicate{read_body(o.at("body"), s), o.at("min_y").number(), read_at(o)};
     }},
    {"inside",
     {"body", "region", "at"},
     [](const Object& o, const Scene& s) -> Predicate {
         std::string body = read_body(o.at("body"), s);
         const Object region(o.at("region"));
         region.allow(kRegionKeys);
         return InsidePredicate{std::move(body), region.at("center").vec3(),
                                read_half_extents(region.at("half_extents")), read_at(o)};
     }},
    {"displaced",
     {"body", "min_distance", "at"},
     [](const Object& o, const Scene& s) -> Predicate {
         return DisplacedPredicate{read_body(o.at("body"), s), o.at("min_distance").positive(),
                                   read_at(o)};
     }},
    {"stacked",
     {"bodies", "tolerance", "at"},
     [](const Object& o, const Scene& s) -> Predicate {
         StackedPredicate p;
         for (const Node& item : o.at("bodies").array(2, "expected an array of at least 2 ids")) {
             p.bodies.push_back(read_body(item, s));
         }
         p.tolerance = o.at("tolerance").positive();
         p.at = read_at(o);
         return p;
     }},
    {"held",
     {"body", "min_y", "from_s", "to_s"},
     [](const Object& o, const Scene& s) -> Predicate {
         HeldPredicate p{read_body(o.at("body"), s), o.at("min_y").number()};
         std::tie(p.from_s, p.to_s) = read_interval(o);
         return p;
     }},
    {"at_rest",
     {"body", "max_speed", "at"},
     [](const Object& o, const Scene& s) -> Predicate {
         AtRestPredicate p;
         p.body = read_body(o.at("body"), s);
         p.max_speed = o.get_or("max_speed", &Node::positive, p.max_speed);
         p.at = read_at(o);
         return p;
     }},
}};

Predicate read_predicate(const Node& node, const Scene& scene) {
    const Object obj(node);
    const PredicateType& type = obj.at("type").choice(kPredicateTypes, "predicate type");
    obj.allow(kPredicateKeys, type.keys);
    return type.read(obj, scene);
}

// ---- Scene ----------------------------------------------------------------------------

Scene read_scene(const Node& root, const fs::path& base_dir) {
    const Object obj(root);
    obj.allow(kSceneKeys);
    const Node format = obj.at("format");
    if (format.string() != kFormat) {
        format.fail("expected " + in_quotes(kFormat) + ", got " + in_quotes(format.string()));
    }

    Scene scene;
    scene.name = obj.at("name").non_empty_string();
    scene.description = obj.get_or("description", &Node::string, scene.description);
    scene.duration_s = obj.at("duration_s").positive();
    scene.gravity = obj.get_or("gravity", &Node::vec3, scene.gravity);
    for (const Node& item : obj.at("colliders").array()) {
        scene.colliders.push_back(read_collider(item, scene.colliders));
    }
    if (const auto engine = obj.find("app_engine")) {
        for (const Node& item : engine->array()) {
            const std::string id = item.non_empty_string();
            const Collider* c = scene.find_collider(id);
            if (c == nullptr || c->motion != Motion::Dynamic) {
                item.fail("expected the id of a dynamic collider, got " + in_quotes(id));
            }
            if (std::find(scene.app_engine.begin(), scene.app_engine.end(), id) !=
                scene.app_engine.end()) {
                item.fail("duplicate id " + in_quotes(id));
            }
            scene.app_engine.push_back(id);
        }
    }
    if (const auto hands_node = obj.find("hands")) {
        const Object hands(*hands_node);
        hands.allow(kHandsKeys);
        for (const auto& side : kSides) {
            if (const auto hand = hands.find(side.name)) {
                scene.hands[static_cast<std::size_t>(side.value)] = read_hand(*hand, base_dir);
            }
        }
    }
    scene.tracking = obj.get_or("tracking", read_tracking, scene.tracking);
    if (const auto success = obj.find("success")) {
        for (const Node& item : success->array()) {
            scene.success.push_back(read_predicate(item, scene));
        }
    }
    return scene;
}

}  // namespace

Scene parse_scene(const std::string& json_text, const fs::path& base_dir) {
    const json root = parse_json(json_text);
    return read_scene(Node(root, ""), base_dir);
}

Scene load_scene(const fs::path& file) {
    const auto error = [&](std::string_view what) {
        return FormatError(file.string() + ": " + std::string(what));
    };
    std::ifstream in(file, std::ios::binary);
    if (!in) throw error("cannot open");
    std::ostringstream text;
    text << in.rdbuf();
    try {
        return parse_scene(text.str(), file.parent_path());
    } catch (const FormatError& e) {
        throw error(e.what());
    }
}

}  // namespace physhand
