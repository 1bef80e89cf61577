#include <algorithm>
#include <bitset>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <utility>

#include "collider_shape.h"
#include "scene.h"

namespace physhand {

const Collider* Scene::find_collider(const std::string& id) const {
    const auto it = std::find_if(colliders.begin(), colliders.end(),
                                 [&](const Collider& c) { return c.id == id; });
    return it == colliders.end() ? nullptr : &*it;
}

namespace {

using nlohmann::json;
namespace fs = std::filesystem;
using Keys = std::span<const std::string_view>;

constexpr std::string_view kFormat = "physhand-scene/1";
// Below this norm a quaternion or plane normal has no usable direction.
constexpr double kMinNorm = 1e-9;

std::string str(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

std::string in_quotes(std::string_view s) {
    return '"' + std::string(s) + '"';
}

std::string key_path(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + '.' + std::string(key);
}

std::string index_path(const std::string& path, std::size_t i) {
    return path + '[' + std::to_string(i) + ']';
}

[[noreturn]] void fail_at(const std::string& path, std::string_view what) {
    throw SceneError(path.empty() ? std::string(what) : path + ": " + std::string(what));
}

// "a, b or c"
template <class Table>
std::string names_of(const Table& table) {
    std::string names;
    for (std::size_t i = 0; i < table.size(); ++i) {
        if (i > 0) names += i + 1 == table.size() ? " or " : ", ";
        names += table[i].name;
    }
    return names;
}

std::optional<Quat> unit_quaternion(double x, double y, double z, double w) {
    const Quat q(w, x, y, z);
    if (!(q.norm() >= kMinNorm)) return std::nullopt;
    return q.normalized();
}

// A JSON value and its path in the scene file; every check fails with that path.
class Node {
  public:
    Node(const json& value, std::string path) : value_(&value), path_(std::move(path)) {}

    const json& value() const { return *value_; }
    const std::string& path() const { return path_; }
    [[noreturn]] void fail(std::string_view what) const { fail_at(path_, what); }

    double number() const {
        if (!value_->is_number()) fail("expected a number");
        const double v = value_->get<double>();
        if (!std::isfinite(v)) fail("expected a finite number");
        return v;
    }
    double positive() const {
        const double v = number();
        if (!(v > 0)) fail("expected a number > 0");
        return v;
    }
    double non_negative() const {
        const double v = number();
        if (!(v >= 0)) fail("expected a number >= 0");
        return v;
    }
    double in_range(double lo, double hi) const {
        const double v = number();
        if (!(v >= lo && v <= hi)) fail("expected a number in [" + str(lo) + ", " + str(hi) + "]");
        return v;
    }
    std::uint64_t unsigned_integer() const {
        if (!value_->is_number_unsigned()) fail("expected a non-negative integer");
        return value_->get<std::uint64_t>();
    }
    // An index into a list of `count` items.
    int index(std::size_t count) const {
        if (!value_->is_number_integer() || value_->get<std::int64_t>() < 0 ||
            value_->get<std::uint64_t>() >= count) {
            fail("expected an integer index in [0, " + std::to_string(count - 1) + "]");
        }
        return value_->get<int>();
    }
    std::string string() const {
        if (!value_->is_string()) fail("expected a string");
        return value_->get<std::string>();
    }
    std::string non_empty_string() const {
        std::string s = string();
        if (s.empty()) fail("expected a non-empty string");
        return s;
    }

    std::vector<Node> array(std::size_t min_size = 0,
                            std::string_view what = "expected an array") const {
        if (!value_->is_array() || value_->size() < min_size) fail(what);
        std::vector<Node> items;
        for (std::size_t i = 0; i < value_->size(); ++i) {
            items.emplace_back((*value_)[i], index_path(path_, i));
        }
        return items;
    }
    // Exactly `n` numbers, returned as nodes so that each can be range-checked at its path.
    std::vector<Node> numbers(std::size_t n) const {
        const std::string what = "expected an array of " + std::to_string(n) + " numbers";
        std::vector<Node> items = array(n, what);
        if (items.size() != n || !std::all_of(items.begin(), items.end(), [](const Node& e) {
                return e.value().is_number();
            })) {
            fail(what);
        }
        return items;
    }
    Vec3 vec3() const {
        const auto e = numbers(3);
        return {e[0].number(), e[1].number(), e[2].number()};
    }

    // The entry of `table` (entries with a `name`) that this string names.
    template <class Table>
    const auto& choice(const Table& table, std::string_view noun) const {
        const std::string s = string();
        for (const auto& entry : table) {
            if (entry.name == s) return entry;
        }
        fail("unknown " + std::string(noun) + ' ' + in_quotes(s) + " (expected " + names_of(table) +
             ')');
    }

  private:
    const json* value_;
    std::string path_;
};

class Object {
  public:
    explicit Object(Node node) : node_(std::move(node)) {
        if (!node_.value().is_object()) node_.fail("expected an object");
    }

    // Every key must be one of `keys` or `more`.
    void allow(Keys keys, Keys more = {}) const {
        for (const auto& item : node_.value().items()) {
            const auto known = [&](Keys list) {
                return std::find(list.begin(), list.end(), item.key()) != list.end();
            };
            if (!known(keys) && !known(more)) fail_at(path_of(item.key()), "unknown key");
        }
    }
    std::optional<Node> find(std::string_view key) const {
        const auto it = node_.value().find(key);
        if (it == node_.value().end()) return std::nullopt;
        return Node(*it, path_of(key));
    }
    Node at(std::string_view key) const {
        auto node = find(key);
        if (!node) fail_at(path_of(key), "required");
        return *node;
    }
    void forbid(std::string_view key, std::string_view why) const {
        if (const auto node = find(key)) node->fail(why);
    }
    // `read` (a function of a Node) applied to the key's value, or `fallback` when absent.
    template <class Read, class T>
    T get_or(std::string_view key, Read read, T fallback) const {
        const auto node = find(key);
        return node ? T(std::invoke(read, *node)) : fallback;
    }
    std::string path_of(std::string_view key) const { return key_path(node_.path(), key); }

  private:
    Node node_;
};

template <class T>
struct Named {
    std::string_view name;
    T value;
};

constexpr std::array<Named<Motion>, 3> kMotions = {{
    {"static", Motion::Static},
    {"kinematic", Motion::Kinematic},
    {"dynamic", Motion::Dynamic},
}};
constexpr std::array<Named<Interpolation>, 2> kInterpolations = {{
    {"linear", Interpolation::Linear},
    {"smooth", Interpolation::Smooth},
}};
constexpr std::array<Named<HandSide>, 2> kSides = {{
    {"left", HandSide::Left},
    {"right", HandSide::Right},
}};

constexpr std::string_view kSceneKeys[] = {"format",     "name",     "description",
                                           "duration_s", "gravity",  "colliders",
                                           "hands",      "tracking", "success"};
constexpr std::string_view kColliderKeys[] = {"id",       "shape",       "motion", "mass",
                                              "friction", "restitution", "pose",   "path"};
constexpr std::string_view kPoseKeys[] = {"position", "orientation"};
constexpr std::string_view kPathEntryKeys[] = {"t", "pose"};
constexpr std::string_view kHandsKeys[] = {"left", "right"};
constexpr std::string_view kHandKeys[] = {"keyframes", "interpolation", "scale", "track"};
constexpr std::string_view kKeyframeKeys[] = {"t", "wrist", "curl", "spread"};
constexpr std::string_view kTrackingKeys[] = {"rate_hz", "noise_mm", "seed", "dropouts"};
constexpr std::string_view kDropoutKeys[] = {"hand", "from_s", "to_s"};
constexpr std::string_view kPredicateKeys[] = {"type"};
constexpr std::string_view kRegionKeys[] = {"center", "half_extents"};

// nlohmann::json keeps the last of duplicate keys; in a scene file they are an error.
// Tracks the path of the value being parsed, for the message.
class DuplicateKeyCheck {
  public:
    bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
        using Event = json::parse_event_t;
        switch (event) {
            case Event::object_start:
            case Event::array_start:
                frames_.emplace_back();
                frames_.back().array = event == Event::array_start;
                break;
            case Event::key: {
                Frame& frame = frames_.back();
                frame.key = parsed.get<std::string>();
                if (!frame.keys.insert(frame.key).second) fail_at(path(), "duplicate key");
                break;
            }
            case Event::object_end:
            case Event::array_end:
                frames_.pop_back();
                [[fallthrough]];
            case Event::value:
                if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
                break;
        }
        return true;
    }

  private:
    struct Frame {
        bool array = false;
        std::size_t index = 0;
        std::string key;
        std::set<std::string> keys;
    };

    std::string path() const {
        std::string path;
        for (const Frame& frame : frames_) {
            path = frame.array ? index_path(path, frame.index) : key_path(path, frame.key);
        }
        return path;
    }

    std::vector<Frame> frames_;
};

// ---- Geometry -------------------------------------------------------------------------

Quat read_quaternion(const Node& node) {
    const auto e = node.numbers(4);
    const auto q = unit_quaternion(e[0].number(), e[1].number(), e[2].number(), e[3].number());
    if (!q) node.fail("expected a non-zero quaternion [x, y, z, w]");
    return *q;
}

Pose read_pose(const Node& node) {
    const Object obj(node);
    obj.allow(kPoseKeys);
    return {obj.at("position").vec3(),
            obj.get_or("orientation", read_quaternion, Quat::Identity())};
}

Vec3 read_half_extents(const Node& node) {
    const auto e = node.numbers(3);
    return {e[0].positive(), e[1].positive(), e[2].positive()};
}

Vec3 read_direction(const Node& node) {
    const Vec3 v = node.vec3();
    if (!(v.norm() >= kMinNorm)) node.fail("expected a non-zero vector");
    return v.normalized();
}

std::vector<Vec3> read_points(const Node& node, std::size_t min_count) {
    std::vector<Vec3> points;
    for (const Node& item : node.array(
             min_count, "expected an array of at least " + std::to_string(min_count) + " points")) {
        points.push_back(item.vec3());
    }
    return points;
}

std::vector<std::array<int, 3>> read_triangles(const Node& node, std::size_t vertex_count) {
    std::vector<std::array<int, 3>> triangles;
    for (const Node& item : node.array(1, "expected a non-empty array of triangles")) {
        const auto corners = item.numbers(3);
        triangles.push_back({corners[0].index(vertex_count), corners[1].index(vertex_count),
                             corners[2].index(vertex_count)});
    }
    return triangles;
}

// The last entry's time, for lists that must be strictly increasing in time.
template <class List>
std::optional<double> last_time(const List& list) {
    return list.empty() ? std::nullopt : std::optional(list.back().t);
}

double read_time_after(const Object& entry, std::optional<double> previous) {
    const Node node = entry.at("t");
    const double t = node.number();
    if (previous && !(t > *previous)) {
        node.fail("expected a time after the previous entry's (" + str(*previous) + ")");
    }
    return t;
}

// `to_s` after `from_s`.
std::pair<double, double> read_interval(const Object& obj) {
    const double from = obj.at("from_s").number();
    const Node to_node = obj.at("to_s");
    const double to = to_node.number();
    if (!(to > from)) to_node.fail("expected a time after from_s (" + str(from) + ")");
    return {from, to};
}

// ---- Colliders ------------------------------------------------------------------------

struct ShapeType {
    std::string_view name;
    ShapeKind kind;
    std::vector<std::string_view> keys;  // the size keys read by `read`
    bool static_only;
    void (*read)(const Object&, Shape&);
};

const std::array<ShapeType, 7> kShapeTypes = {{
    {"box",
     ShapeKind::Box,
     {"half_extents"},
     false,
     [](const Object& o, Shape& s) { s.half_extents = read_half_extents(o.at("half_extents")); }},
    {"sphere",
     ShapeKind::Sphere,
     {"radius"},
     false,
     [](const Object& o, Shape& s) { s.radius = o.at("radius").positive(); }},
    {"capsule",
     ShapeKind::Capsule,
     {"radius", "half_height"},
     false,
     [](const Object& o, Shape& s) {
         s.radius = o.at("radius").positive();
         s.half_height = o.at("half_height").non_negative();
     }},
    {"cylinder",
     ShapeKind::Cylinder,
     {"radius", "half_height"},
     false,
     [](const Object& o, Shape& s) {
         s.radius = o.at("radius").positive();
         s.half_height = o.at("half_height").positive();
     }},
    {"convex",
     ShapeKind::Convex,
     {"vertices"},
     false,
     [](const Object& o, Shape& s) { s.vertices = read_points(o.at("vertices"), 4); }},
    {"mesh",
     ShapeKind::Mesh,
     {"vertices", "indices"},
     true,
     [](const Object& o, Shape& s) {
         s.vertices = read_points(o.at("vertices"), 3);
         s.indices = read_triangles(o.at("indices"), s.vertices.size());
     }},
    {"plane",
     ShapeKind::Plane,
     {"normal", "offset"},
     true,
     [](const Object& o, Shape& s) {
         s.normal = read_direction(o.at("normal"));
         s.offset = o.at("offset").number();
     }},
}};

std::vector<TimedPose> read_path(const Node& node) {
    std::vector<TimedPose> path;
    for (const Node& item : node.array(1, "expected a non-empty array")) {
        const Object entry(item);
        entry.allow(kPathEntryKeys);
        const double t = read_time_after(entry, last_time(path));
        path.push_back({t, read_pose(entry.at("pose"))});
    }
    return path;
}

Collider read_collider(const Node& node, const Scene& scene) {
    const Object obj(node);
    const ShapeType& type = obj.at("shape").choice(kShapeTypes, "shape");
    obj.allow(kColliderKeys, type.keys);

    Collider c;
    const Node id = obj.at("id");
    c.id = id.non_empty_string();
    if (scene.find_collider(c.id)) id.fail("duplicate id " + in_quotes(c.id));

    c.shape.kind = type.kind;
    type.read(obj, c.shape);

    const Node motion = obj.at("motion");
    c.motion = motion.choice(kMotions, "motion").value;
    if (type.static_only && c.motion != Motion::Static) {
        motion.fail("a " + std::string(type.name) + " collider must be static");
    }
    if (c.motion == Motion::Dynamic) {
        constexpr std::string_view kMassRule = "required and > 0 for a dynamic collider";
        const auto mass = obj.find("mass");
        if (!mass) fail_at(obj.path_of("mass"), kMassRule);
        c.mass = mass->number();
        if (!(c.mass > 0)) mass->fail(kMassRule);
    } else {
        obj.forbid("mass", "only allowed for a dynamic collider");
    }
    c.friction = obj.get_or("friction", &Node::non_negative, c.friction);
    c.restitution = obj.get_or(
        "restitution", [](const Node& n) { return n.in_range(0, 1); }, c.restitution);
    // A plane is placed by its normal and offset; a pose is optional for it.
    c.pose = type.kind == ShapeKind::Plane ? obj.get_or("pose", read_pose, c.pose)
                                           : read_pose(obj.at("pose"));
    if (c.motion == Motion::Kinematic) {
        c.path = obj.get_or("path", read_path, c.path);
    } else {
        obj.forbid("path", "only allowed for a kinematic collider");
    }
    // What the simulation would refuse (a hull with no volume, sizes out of float's reach)
    // is refused here, where the message can say which collider.
    try {
        validate_collider(c);
    } catch (const std::invalid_argument& e) {
        node.fail(e.what());
    }
    return c;
}

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
        scene.colliders.push_back(read_collider(item, scene));
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
    json root;
    try {
        root = json::parse(json_text, DuplicateKeyCheck());
    } catch (const json::exception& e) {
        // Drop nlohmann's "[json.exception.parse_error.101] " tag; keep line and column.
        const std::string_view what = e.what();
        const std::size_t tag_end = what.find("] ");
        throw SceneError("invalid JSON: " + std::string(tag_end == std::string_view::npos
                                                            ? what
                                                            : what.substr(tag_end + 2)));
    }
    return read_scene(Node(root, ""), base_dir);
}

Scene load_scene(const fs::path& file) {
    const auto error = [&](std::string_view what) {
        return SceneError(file.string() + ": " + std::string(what));
    };
    std::ifstream in(file, std::ios::binary);
    if (!in) throw error("cannot open");
    std::ostringstream text;
    text << in.rdbuf();
    try {
        return parse_scene(text.str(), file.parent_path());
    } catch (const SceneError& e) {
        throw error(e.what());
    }
}

}  // namespace physhand
