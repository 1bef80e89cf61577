#include "collider_syntax.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "collider_shape.h"

namespace physhand::syntax {

namespace {

// Below this norm a quaternion or plane normal has no usable direction.
constexpr double kMinNorm = 1e-9;

constexpr std::array<Named<Motion>, 3> kMotions = {{
    {"static", Motion::Static},
    {"kinematic", Motion::Kinematic},
    {"dynamic", Motion::Dynamic},
}};

constexpr std::string_view kColliderKeys[] = {"id",       "shape",       "motion", "mass",
                                              "friction", "restitution", "pose",   "path"};
constexpr std::string_view kPoseKeys[] = {"position", "orientation"};
constexpr std::string_view kPathEntryKeys[] = {"t", "pose"};

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

}  // namespace

std::optional<Quat> unit_quaternion(double x, double y, double z, double w) {
    const Quat q(w, x, y, z);
    if (!(q.norm() >= kMinNorm)) return std::nullopt;
    return q.normalized();
}

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

namespace {

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

}  // namespace

Collider read_collider(const Node& node, std::span<const Collider> earlier) {
    const Object obj(node);
    const ShapeType& type = obj.at("shape").choice(kShapeTypes, "shape");
    obj.allow(kColliderKeys, type.keys);

    Collider c;
    const Node id = obj.at("id");
    c.id = id.non_empty_string();
    if (std::any_of(earlier.begin(), earlier.end(),
                    [&](const Collider& e) { return e.id == c.id; }))
        id.fail("duplicate id " + in_quotes(c.id));

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

}  // namespace physhand::syntax
