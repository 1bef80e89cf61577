#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "scene.h"

namespace physhand {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Every shape, motion and predicate type. Collider indices:
// 0 floor (plane), 1 table (box, static), 2 cube1 (box, dynamic), 3 ball (sphere),
// 4 can (cylinder, kinematic with path), 5 handle (capsule, kinematic), 6 rock (convex),
// 7 ramp (mesh). Predicates: 0 above, 1 inside, 2 displaced, 3 stacked, 4 held, 5 at_rest.
constexpr const char* kScene = R"({
  "format": "physhand-scene/1",
  "name": "everything",
  "description": "one of each",
  "duration_s": 12.5,
  "gravity": [0, -9.0, 0.5],
  "colliders": [
    { "id": "floor", "shape": "plane", "normal": [0, 2, 0], "offset": 0.25, "motion": "static" },
    { "id": "table", "shape": "box", "half_extents": [0.5, 0.4, 0.3], "motion": "static",
      "friction": 0.6, "pose": { "position": [0, 0.4, -0.5] } },
    { "id": "cube1", "shape": "box", "half_extents": [0.03, 0.03, 0.03], "motion": "dynamic",
      "mass": 0.1, "friction": 0.9, "restitution": 0.05,
      "pose": { "position": [0, 0.83, -0.35], "orientation": [0, 0, 0, 2] } },
    { "id": "ball", "shape": "sphere", "radius": 0.03, "motion": "dynamic", "mass": 0.05,
      "pose": { "position": [0.1, 0.83, -0.35], "orientation": [0, 3, 0, 4] } },
    { "id": "can", "shape": "cylinder", "radius": 0.04, "half_height": 0.06,
      "motion": "kinematic", "pose": { "position": [0.2, 0.9, -0.4] },
      "path": [ { "t": 0, "pose": { "position": [0.2, 0.9, -0.4] } },
                { "t": 2, "pose": { "position": [0.2, 1.1, -0.4],
                                    "orientation": [1, 0, 0, 1] } } ] },
    { "id": "handle", "shape": "capsule", "radius": 0.02, "half_height": 0,
      "motion": "kinematic", "pose": { "position": [0, 1, 0] } },
    { "id": "rock", "shape": "convex",
      "vertices": [[0, 0, 0], [0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]],
      "motion": "dynamic", "mass": 0.2, "pose": { "position": [-0.2, 0.85, -0.3] } },
    { "id": "ramp", "shape": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 0.5, -1]],
      "indices": [[0, 1, 2]], "motion": "static", "pose": { "position": [1, 0, 0] } }
  ],
  "hands": {
    "left": {
      "keyframes": [
        { "t": 0, "wrist": { "position": [-0.2, 1.0, -0.3] },
          "curl": [0.1, 0.2, 0.3, 0.4, 0.5], "spread": 0.5 },
        { "t": 1.5, "curl": [0.7, 0.8, 0.8, 0.8, 0.9] },
        { "t": 2.5, "wrist": { "position": [0, 1.2, -0.3], "orientation": [0, 0, 3, 4] },
          "spread": -1 }
      ],
      "interpolation": "linear",
      "scale": 1.1
    }
  },
  "tracking": { "rate_hz": 72, "noise_mm": 1.5, "seed": 42,
                "dropouts": [ { "hand": "right", "from_s": 3.0, "to_s": 3.4 } ] },
  "success": [
    { "type": "above", "body": "cube1", "min_y": 0.9, "at": "end" },
    { "type": "inside", "body": "ball",
      "region": { "center": [0, 0.8, -0.3], "half_extents": [0.1, 0.05, 0.1] }, "at": 5.0 },
    { "type": "displaced", "body": "rock", "min_distance": 0.05 },
    { "type": "stacked", "bodies": ["table", "cube1"], "tolerance": 0.02, "at": "end" },
    { "type": "held", "body": "cube1", "min_y": 0.9, "from_s": 4.0, "to_s": 6.0 },
    { "type": "at_rest", "body": "ball" }
  ]
})";

json base_scene() {
    return json::parse(kScene);
}

constexpr const char* kMinimalScene =
    R"({ "format": "physhand-scene/1", "name": "empty", "duration_s": 1, "colliders": [] })";

// The message of the FormatError that parsing `text` throws ("" and a failure if none).
std::string error_of_text(const std::string& text, const fs::path& base_dir = {}) {
    try {
        parse_scene(text, base_dir);
    } catch (const FormatError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no FormatError for:\n" << text;
    return "";
}

std::string error_of(const json& scene, const fs::path& base_dir = {}) {
    return error_of_text(scene.dump(), base_dir);
}

// The tests' directories, removed when the test program ends.
struct TestDirs {
    std::vector<fs::path> made;
    ~TestDirs() {
        std::error_code ignored;
        for (const fs::path& dir : made) fs::remove_all(dir, ignored);
    }
};

// A fresh directory for the running test.
fs::path test_dir() {
    static TestDirs dirs;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    const fs::path dir = fs::path(::testing::TempDir()) / ("physhand_scene_loader_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    dirs.made.push_back(dir);
    return dir;
}

void write_file(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream out(file, std::ios::binary);
    out << text;
    ASSERT_TRUE(out.good()) << file;
}

// ---- Valid scenes ---------------------------------------------------------------------

TEST(SceneLoader, ParsesEveryShapeMotionAndPredicate) {
    const Scene scene = parse_scene(kScene, {});
    EXPECT_EQ(scene.name, "everything");
    EXPECT_EQ(scene.description, "one of each");
    EXPECT_DOUBLE_EQ(scene.duration_s, 12.5);
    EXPECT_TRUE(scene.gravity.isApprox(Vec3(0, -9.0, 0.5)));
    ASSERT_EQ(scene.colliders.size(), 8u);

    const Collider& floor = scene.colliders[0];
    EXPECT_EQ(floor.shape.kind, ShapeKind::Plane);
    EXPECT_EQ(floor.motion, Motion::Static);
    EXPECT_TRUE(floor.shape.normal.isApprox(Vec3::UnitY()));  // normalised from [0, 2, 0]
    EXPECT_DOUBLE_EQ(floor.shape.offset, 0.25);
    EXPECT_TRUE(floor.pose.position.isZero());
    EXPECT_TRUE(floor.pose.orientation.isApprox(Quat::Identity()));

    const Collider& table = scene.colliders[1];
    EXPECT_EQ(table.shape.kind, ShapeKind::Box);
    EXPECT_TRUE(table.shape.half_extents.isApprox(Vec3(0.5, 0.4, 0.3)));
    EXPECT_DOUBLE_EQ(table.friction, 0.6);
    EXPECT_DOUBLE_EQ(table.restitution, 0.0);  // default
    EXPECT_TRUE(table.pose.position.isApprox(Vec3(0, 0.4, -0.5)));
    EXPECT_TRUE(table.pose.orientation.isApprox(Quat::Identity()));  // default

    const Collider& cube = scene.colliders[2];
    EXPECT_EQ(cube.id, "cube1");
    EXPECT_EQ(cube.motion, Motion::Dynamic);
    EXPECT_DOUBLE_EQ(cube.mass, 0.1);
    EXPECT_DOUBLE_EQ(cube.friction, 0.9);
    EXPECT_DOUBLE_EQ(cube.restitution, 0.05);
    EXPECT_DOUBLE_EQ(cube.pose.orientation.w(), 1.0);  // [0, 0, 0, 2] normalised
    EXPECT_DOUBLE_EQ(cube.pose.orientation.norm(), 1.0);

    const Collider& ball = scene.colliders[3];
    EXPECT_EQ(ball.shape.kind, ShapeKind::Sphere);
    EXPECT_DOUBLE_EQ(ball.shape.radius, 0.03);
    EXPECT_DOUBLE_EQ(ball.friction, 0.8);  // default
    // [x, y, z, w] = [0, 3, 0, 4], normalised.
    EXPECT_DOUBLE_EQ(ball.pose.orientation.x(), 0.0);
    EXPECT_DOUBLE_EQ(ball.pose.orientation.y(), 0.6);
    EXPECT_DOUBLE_EQ(ball.pose.orientation.z(), 0.0);
    EXPECT_DOUBLE_EQ(ball.pose.orientation.w(), 0.8);

    const Collider& can = scene.colliders[4];
    EXPECT_EQ(can.shape.kind, ShapeKind::Cylinder);
    EXPECT_EQ(can.motion, Motion::Kinematic);
    EXPECT_DOUBLE_EQ(can.shape.radius, 0.04);
    EXPECT_DOUBLE_EQ(can.shape.half_height, 0.06);
    ASSERT_EQ(can.path.size(), 2u);
    EXPECT_DOUBLE_EQ(can.path[0].t, 0.0);
    EXPECT_DOUBLE_EQ(can.path[1].t, 2.0);
    EXPECT_TRUE(can.path[1].pose.position.isApprox(Vec3(0.2, 1.1, -0.4)));
    const Quat half_turn_x(Eigen::AngleAxisd(EIGEN_PI / 2, Vec3::UnitX()));
    EXPECT_TRUE(can.path[1].pose.orientation.isApprox(half_turn_x));

    const Collider& handle = scene.colliders[5];
    EXPECT_EQ(handle.shape.kind, ShapeKind::Capsule);
    EXPECT_DOUBLE_EQ(handle.shape.half_height, 0.0);  // a capsule may be a sphere
    EXPECT_TRUE(handle.path.empty());

    const Collider& rock = scene.colliders[6];
    EXPECT_EQ(rock.shape.kind, ShapeKind::Convex);
    ASSERT_EQ(rock.shape.vertices.size(), 4u);
    EXPECT_TRUE(rock.shape.vertices[3].isApprox(Vec3(0, 0, 0.1)));

    const Collider& ramp = scene.colliders[7];
    EXPECT_EQ(ramp.shape.kind, ShapeKind::Mesh);
    ASSERT_EQ(ramp.shape.vertices.size(), 3u);
    ASSERT_EQ(ramp.shape.indices.size(), 1u);
    EXPECT_EQ(ramp.shape.indices[0], (std::array<int, 3>{0, 1, 2}));

    EXPECT_FALSE(scene.hand(HandSide::Right).has_value());
    ASSERT_TRUE(scene.hand(HandSide::Left).has_value());
    const HandScript& left = *scene.hand(HandSide::Left);
    EXPECT_EQ(left.interpolation, Interpolation::Linear);
    EXPECT_DOUBLE_EQ(left.scale, 1.1);
    EXPECT_TRUE(left.recorded.empty());
    EXPECT_EQ(left.keyframes.size(), 3u);

    EXPECT_DOUBLE_EQ(scene.tracking.rate_hz, 72.0);
    EXPECT_DOUBLE_EQ(scene.tracking.noise_mm, 1.5);
    EXPECT_EQ(scene.tracking.seed, 42u);
    ASSERT_EQ(scene.tracking.dropouts.size(), 1u);
    EXPECT_EQ(scene.tracking.dropouts[0].hand, HandSide::Right);
    EXPECT_DOUBLE_EQ(scene.tracking.dropouts[0].from_s, 3.0);
    EXPECT_DOUBLE_EQ(scene.tracking.dropouts[0].to_s, 3.4);

    ASSERT_EQ(scene.success.size(), 6u);
    const auto* above = std::get_if<AbovePredicate>(&scene.success[0]);
    ASSERT_NE(above, nullptr);
    EXPECT_EQ(above->body, "cube1");
    EXPECT_DOUBLE_EQ(above->min_y, 0.9);
    EXPECT_FALSE(above->at.has_value());  // "end"

    const auto* inside = std::get_if<InsidePredicate>(&scene.success[1]);
    ASSERT_NE(inside, nullptr);
    EXPECT_EQ(inside->body, "ball");
    EXPECT_TRUE(inside->center.isApprox(Vec3(0, 0.8, -0.3)));
    EXPECT_TRUE(inside->half_extents.isApprox(Vec3(0.1, 0.05, 0.1)));
    ASSERT_TRUE(inside->at.has_value());
    EXPECT_DOUBLE_EQ(*inside->at, 5.0);

    const auto* displaced = std::get_if<DisplacedPredicate>(&scene.success[2]);
    ASSERT_NE(displaced, nullptr);
    EXPECT_EQ(displaced->body, "rock");
    EXPECT_DOUBLE_EQ(displaced->min_distance, 0.05);
    EXPECT_FALSE(displaced->at.has_value());  // absent: "end"

    const auto* stacked = std::get_if<StackedPredicate>(&scene.success[3]);
    ASSERT_NE(stacked, nullptr);
    EXPECT_EQ(stacked->bodies, (std::vector<std::string>{"table", "cube1"}));
    EXPECT_DOUBLE_EQ(stacked->tolerance, 0.02);

    const auto* held = std::get_if<HeldPredicate>(&scene.success[4]);
    ASSERT_NE(held, nullptr);
    EXPECT_EQ(held->body, "cube1");
    EXPECT_DOUBLE_EQ(held->min_y, 0.9);
    EXPECT_DOUBLE_EQ(held->from_s, 4.0);
    EXPECT_DOUBLE_EQ(held->to_s, 6.0);

    const auto* at_rest = std::get_if<AtRestPredicate>(&scene.success[5]);
    ASSERT_NE(at_rest, nullptr);
    EXPECT_EQ(at_rest->body, "ball");
    EXPECT_DOUBLE_EQ(at_rest->max_speed, 0.05);  // default
    EXPECT_FALSE(at_rest->at.has_value());
}

TEST(SceneLoader, AbsentKeyframeKeysRepeatThePreviousKeyframe) {
    const Scene scene = parse_scene(kScene, {});
    const auto& k = scene.hand(HandSide::Left)->keyframes;
    ASSERT_EQ(k.size(), 3u);

    EXPECT_DOUBLE_EQ(k[0].t, 0.0);
    EXPECT_TRUE(k[0].wrist.position.isApprox(Vec3(-0.2, 1.0, -0.3)));
    EXPECT_EQ(k[0].articulation.curl, (std::array<double, 5>{0.1, 0.2, 0.3, 0.4, 0.5}));
    EXPECT_DOUBLE_EQ(k[0].articulation.spread, 0.5);

    // Keyframe 1 gives only t and curl: wrist and spread repeat keyframe 0.
    EXPECT_DOUBLE_EQ(k[1].t, 1.5);
    EXPECT_TRUE(k[1].wrist.position.isApprox(k[0].wrist.position));
    EXPECT_EQ(k[1].articulation.curl, (std::array<double, 5>{0.7, 0.8, 0.8, 0.8, 0.9}));
    EXPECT_DOUBLE_EQ(k[1].articulation.spread, 0.5);

    // Keyframe 2 gives wrist and spread: curl repeats keyframe 1.
    EXPECT_TRUE(k[2].wrist.position.isApprox(Vec3(0, 1.2, -0.3)));
    EXPECT_DOUBLE_EQ(k[2].wrist.orientation.z(), 0.6);
    EXPECT_DOUBLE_EQ(k[2].wrist.orientation.w(), 0.8);
    EXPECT_EQ(k[2].articulation.curl, k[1].articulation.curl);
    EXPECT_DOUBLE_EQ(k[2].articulation.spread, -1.0);
}

TEST(SceneLoader, FirstKeyframeDefaultsToAnOpenHand) {
    json scene = json::parse(kMinimalScene);
    scene["hands"]["right"] =
        json::parse(R"({ "keyframes": [ { "t": 0, "wrist": { "position": [0, 1, 0] } } ] })");
    const Scene parsed = parse_scene(scene.dump(), {});
    ASSERT_TRUE(parsed.hand(HandSide::Right).has_value());
    const HandScript& right = *parsed.hand(HandSide::Right);
    EXPECT_EQ(right.interpolation, Interpolation::Smooth);
    EXPECT_DOUBLE_EQ(right.scale, 1.0);
    ASSERT_EQ(right.keyframes.size(), 1u);
    EXPECT_EQ(right.keyframes[0].articulation.curl, (std::array<double, 5>{}));
    EXPECT_DOUBLE_EQ(right.keyframes[0].articulation.spread, 0.0);
    EXPECT_TRUE(right.keyframes[0].wrist.orientation.isApprox(Quat::Identity()));
}

TEST(SceneLoader, MinimalSceneUsesDefaults) {
    const Scene scene = parse_scene(kMinimalScene, {});
    EXPECT_EQ(scene.name, "empty");
    EXPECT_EQ(scene.description, "");
    EXPECT_TRUE(scene.gravity.isApprox(Vec3(0, -9.81, 0)));
    EXPECT_TRUE(scene.colliders.empty());
    EXPECT_FALSE(scene.hand(HandSide::Left).has_value());
    EXPECT_FALSE(scene.hand(HandSide::Right).has_value());
    EXPECT_DOUBLE_EQ(scene.tracking.rate_hz, 90.0);
    EXPECT_DOUBLE_EQ(scene.tracking.noise_mm, 0.0);
    EXPECT_EQ(scene.tracking.seed, 1u);
    EXPECT_TRUE(scene.tracking.dropouts.empty());
    EXPECT_TRUE(scene.success.empty());
}

TEST(SceneLoader, FindColliderById) {
    const Scene scene = parse_scene(kScene, {});
    const Collider* ball = scene.find_collider("ball");
    ASSERT_NE(ball, nullptr);
    EXPECT_EQ(ball, &scene.colliders[3]);
    EXPECT_EQ(scene.find_collider("cube9"), nullptr);
    EXPECT_EQ(scene.find_collider(""), nullptr);
}

// ---- Invalid scenes: each case edits the valid scene and names the expected message ------

struct ErrorCase {
    std::string name;
    std::function<void(json&)> edit;
    std::string message;  // the start of FormatError::what()
};

void PrintTo(const ErrorCase& c, std::ostream* out) {
    *out << c.name;
}

class FormatErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(FormatErrors, NamesThePathAndWhatWasExpected) {
    json scene = base_scene();
    GetParam().edit(scene);
    EXPECT_THAT(error_of(scene), StartsWith(GetParam().message));
}

json& collider(json& s, int i) {
    return s["colliders"][i];
}
json& keyframe(json& s, int i) {
    return s["hands"]["left"]["keyframes"][i];
}
json& predicate(json& s, int i) {
    return s["success"][i];
}

const ErrorCase kErrorCases[] = {
    // Top level.
    {"RootNotObject", [](json& s) { s = json::array(); }, "expected an object"},
    {"FormatMissing", [](json& s) { s.erase("format"); }, "format: required"},
    {"FormatWrong", [](json& s) { s["format"] = "physhand-scene/2"; },
     R"(format: expected "physhand-scene/1", got "physhand-scene/2")"},
    {"FormatNotString", [](json& s) { s["format"] = 1; }, "format: expected a string"},
    {"NameMissing", [](json& s) { s.erase("name"); }, "name: required"},
    {"NameEmpty", [](json& s) { s["name"] = ""; }, "name: expected a non-empty string"},
    {"DescriptionNotString", [](json& s) { s["description"] = 3; },
     "description: expected a string"},
    {"DurationMissing", [](json& s) { s.erase("duration_s"); }, "duration_s: required"},
    {"DurationZero", [](json& s) { s["duration_s"] = 0; }, "duration_s: expected a number > 0"},
    {"DurationString", [](json& s) { s["duration_s"] = "12"; }, "duration_s: expected a number"},
    {"GravityShort",
     [](json& s) {
         s["gravity"] = {0, -9.81};
     },
     "gravity: expected an array of 3 numbers"},
    {"GravityNotNumber",
     [](json& s) {
         s["gravity"] = {0, "down", 0};
     },
     "gravity: expected an array of 3 numbers"},
    {"CollidersMissing", [](json& s) { s.erase("colliders"); }, "colliders: required"},
    {"CollidersNotArray", [](json& s) { s["colliders"] = json::object(); },
     "colliders: expected an array"},
    {"UnknownTopLevelKey", [](json& s) { s["colour"] = "red"; }, "colour: unknown key"},

    // Colliders.
    {"ColliderNotObject", [](json& s) { collider(s, 2) = 3; }, "colliders[2]: expected an object"},
    {"UnknownColliderKey", [](json& s) { collider(s, 0)["frictoin"] = 0.5; },
     "colliders[0].frictoin: unknown key"},
    {"KeyOfAnotherShape",
     [](json& s) {
         collider(s, 3)["half_extents"] = {1, 1, 1};
     },
     "colliders[3].half_extents: unknown key"},
    {"IdMissing", [](json& s) { collider(s, 2).erase("id"); }, "colliders[2].id: required"},
    {"IdEmpty", [](json& s) { collider(s, 2)["id"] = ""; },
     "colliders[2].id: expected a non-empty string"},
    {"IdDuplicate", [](json& s) { collider(s, 3)["id"] = "cube1"; },
     R"(colliders[3].id: duplicate id "cube1")"},
    {"ShapeMissing", [](json& s) { collider(s, 1).erase("shape"); },
     "colliders[1].shape: required"},
    {"ShapeUnknown", [](json& s) { collider(s, 1)["shape"] = "cube"; },
     R"(colliders[1].shape: unknown shape "cube" (expected box, sphere, capsule, cylinder, convex, mesh or plane))"},
    {"HalfExtentsShort",
     [](json& s) {
         collider(s, 2)["half_extents"] = {0.03, 0.03};
     },
     "colliders[2].half_extents: expected an array of 3 numbers"},
    {"HalfExtentsZero",
     [](json& s) {
         collider(s, 2)["half_extents"] = {0.03, 0, 0.03};
     },
     "colliders[2].half_extents[1]: expected a number > 0"},
    {"HalfExtentsMissing", [](json& s) { collider(s, 2).erase("half_extents"); },
     "colliders[2].half_extents: required"},
    {"SphereRadiusZero", [](json& s) { collider(s, 3)["radius"] = 0; },
     "colliders[3].radius: expected a number > 0"},
    {"CylinderHalfHeightZero", [](json& s) { collider(s, 4)["half_height"] = 0; },
     "colliders[4].half_height: expected a number > 0"},
    {"CapsuleHalfHeightNegative", [](json& s) { collider(s, 5)["half_height"] = -0.1; },
     "colliders[5].half_height: expected a number >= 0"},
    {"CapsuleRadiusMissing", [](json& s) { collider(s, 5).erase("radius"); },
     "colliders[5].radius: required"},
    {"ConvexTooFewVertices", [](json& s) { collider(s, 6)["vertices"].erase(3); },
     "colliders[6].vertices: expected an array of at least 4 points"},
    {"ConvexBadVertex",
     [](json& s) {
         collider(s, 6)["vertices"][2] = {0, 0};
     },
     "colliders[6].vertices[2]: expected an array of 3 numbers"},
    {"ConvexFlat",
     [](json& s) {
         collider(s, 6)["vertices"] = {{0, 0, 0}, {0.1, 0, 0}, {0, 0, 0.1}, {0.1, 0, 0.1}};
     },
     R"(colliders[6]: collider "rock": vertices span no volume)"},
    {"MeshOnlySlivers",
     [](json& s) {
         collider(s, 7)["vertices"] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
         collider(s, 7)["indices"] = {{0, 1, 2}};
     },
     R"(colliders[7]: collider "ramp": every mesh triangle has zero area)"},
    {"MeshTooFewVertices", [](json& s) { collider(s, 7)["vertices"].erase(2); },
     "colliders[7].vertices: expected an array of at least 3 points"},
    {"MeshNoTriangles", [](json& s) { collider(s, 7)["indices"] = json::array(); },
     "colliders[7].indices: expected a non-empty array of triangles"},
    {"MeshIndexOutOfRange",
     [](json& s) {
         collider(s, 7)["indices"][0] = {0, 1, 3};
     },
     "colliders[7].indices[0][2]: expected an integer index in [0, 2]"},
    {"MeshIndexNegative",
     [](json& s) {
         collider(s, 7)["indices"][0] = {-1, 1, 2};
     },
     "colliders[7].indices[0][0]: expected an integer index in [0, 2]"},
    {"MeshIndexNotInteger",
     [](json& s) {
         collider(s, 7)["indices"][0] = {0, 1.5, 2};
     },
     "colliders[7].indices[0][1]: expected an integer index in [0, 2]"},
    {"MeshTriangleShort",
     [](json& s) {
         collider(s, 7)["indices"][0] = {0, 1};
     },
     "colliders[7].indices[0]: expected an array of 3 numbers"},
    {"MeshNotStatic",
     [](json& s) {
         collider(s, 7)["motion"] = "dynamic";
         collider(s, 7)["mass"] = 1;
     },
     "colliders[7].motion: a mesh collider must be static"},
    {"PlaneNotStatic", [](json& s) { collider(s, 0)["motion"] = "kinematic"; },
     "colliders[0].motion: a plane collider must be static"},
    {"PlaneNormalZero",
     [](json& s) {
         collider(s, 0)["normal"] = {0, 0, 0};
     },
     "colliders[0].normal: expected a non-zero vector"},
    {"PlaneOffsetMissing", [](json& s) { collider(s, 0).erase("offset"); },
     "colliders[0].offset: required"},
    {"MotionMissing", [](json& s) { collider(s, 2).erase("motion"); },
     "colliders[2].motion: required"},
    {"MotionUnknown", [](json& s) { collider(s, 2)["motion"] = "moving"; },
     R"(colliders[2].motion: unknown motion "moving" (expected static, kinematic or dynamic))"},
    {"DynamicMassMissing", [](json& s) { collider(s, 2).erase("mass"); },
     "colliders[2].mass: required and > 0 for a dynamic collider"},
    {"DynamicMassZero", [](json& s) { collider(s, 2)["mass"] = 0; },
     "colliders[2].mass: required and > 0 for a dynamic collider"},
    {"DynamicMassNotNumber", [](json& s) { collider(s, 2)["mass"] = "light"; },
     "colliders[2].mass: expected a number"},
    {"StaticWithMass", [](json& s) { collider(s, 1)["mass"] = 1; },
     "colliders[1].mass: only allowed for a dynamic collider"},
    {"KinematicWithMass", [](json& s) { collider(s, 4)["mass"] = 1; },
     "colliders[4].mass: only allowed for a dynamic collider"},
    {"FrictionNegative", [](json& s) { collider(s, 2)["friction"] = -0.1; },
     "colliders[2].friction: expected a number >= 0"},
    {"RestitutionAboveOne", [](json& s) { collider(s, 2)["restitution"] = 1.5; },
     "colliders[2].restitution: expected a number in [0, 1]"},
    {"PoseMissing", [](json& s) { collider(s, 1).erase("pose"); }, "colliders[1].pose: required"},
    {"PoseNotObject",
     [](json& s) {
         collider(s, 1)["pose"] = {0, 0, 0};
     },
     "colliders[1].pose: expected an object"},
    {"PositionMissing", [](json& s) { collider(s, 1)["pose"].erase("position"); },
     "colliders[1].pose.position: required"},
    {"UnknownPoseKey",
     [](json& s) {
         collider(s, 2)["pose"]["rotation"] = {0, 0, 0, 1};
     },
     "colliders[2].pose.rotation: unknown key"},
    {"QuaternionZero",
     [](json& s) {
         collider(s, 2)["pose"]["orientation"] = {0, 0, 0, 0};
     },
     "colliders[2].pose.orientation: expected a non-zero quaternion"},
    {"QuaternionShort",
     [](json& s) {
         collider(s, 2)["pose"]["orientation"] = {0, 0, 1};
     },
     "colliders[2].pose.orientation: expected an array of 4 numbers"},
    {"PathOnDynamic", [](json& s) { collider(s, 2)["path"] = collider(s, 4)["path"]; },
     "colliders[2].path: only allowed for a kinematic collider"},
    {"PathEmpty", [](json& s) { collider(s, 4)["path"] = json::array(); },
     "colliders[4].path: expected a non-empty array"},
    {"PathTimeNotIncreasing", [](json& s) { collider(s, 4)["path"][1]["t"] = 0; },
     "colliders[4].path[1].t: expected a time after the previous entry's (0)"},
    {"PathPoseMissing", [](json& s) { collider(s, 4)["path"][1].erase("pose"); },
     "colliders[4].path[1].pose: required"},
    {"PathUnknownKey", [](json& s) { collider(s, 4)["path"][0]["speed"] = 1; },
     "colliders[4].path[0].speed: unknown key"},
    {"PathDeepUnknownKey", [](json& s) { collider(s, 4)["path"][1]["pose"]["scale"] = 2; },
     "colliders[4].path[1].pose.scale: unknown key"},

    // Hands.
    {"HandsNotObject", [](json& s) { s["hands"] = json::array(); }, "hands: expected an object"},
    {"UnknownHand", [](json& s) { s["hands"]["middle"] = s["hands"]["left"]; },
     "hands.middle: unknown key"},
    {"HandNeither",
     [](json& s) {
         s["hands"]["left"] = {{"scale", 1}};
     },
     "hands.left: expected keyframes or track"},
    {"HandBoth", [](json& s) { s["hands"]["left"]["track"] = "x.csv"; },
     "hands.left: expected either keyframes or track, not both"},
    {"TrackWithScale",
     [](json& s) {
         s["hands"]["left"] = {{"track", "x.csv"}, {"scale", 1}};
     },
     "hands.left.scale: only allowed with keyframes"},
    {"UnknownHandKey", [](json& s) { s["hands"]["left"]["smoothing"] = 1; },
     "hands.left.smoothing: unknown key"},
    {"KeyframesEmpty", [](json& s) { s["hands"]["left"]["keyframes"] = json::array(); },
     "hands.left.keyframes: expected a non-empty array"},
    {"KeyframeTimeMissing", [](json& s) { keyframe(s, 1).erase("t"); },
     "hands.left.keyframes[1].t: required"},
    {"KeyframeTimeNotIncreasing", [](json& s) { keyframe(s, 2)["t"] = 1.5; },
     "hands.left.keyframes[2].t: expected a time after the previous entry's (1.5)"},
    {"FirstWristMissing", [](json& s) { keyframe(s, 0).erase("wrist"); },
     "hands.left.keyframes[0].wrist: required in the first keyframe"},
    {"WristPositionMissing", [](json& s) { keyframe(s, 2)["wrist"].erase("position"); },
     "hands.left.keyframes[2].wrist.position: required"},
    {"CurlShort",
     [](json& s) {
         keyframe(s, 1)["curl"] = {0.1, 0.1, 0.1, 0.1};
     },
     "hands.left.keyframes[1].curl: expected an array of 5 numbers"},
    {"CurlAboveOne", [](json& s) { keyframe(s, 0)["curl"][2] = 1.2; },
     "hands.left.keyframes[0].curl[2]: expected a number in [0, 1]"},
    {"CurlNegative", [](json& s) { keyframe(s, 1)["curl"][0] = -0.1; },
     "hands.left.keyframes[1].curl[0]: expected a number in [0, 1]"},
    {"SpreadOutOfRange", [](json& s) { keyframe(s, 2)["spread"] = -1.5; },
     "hands.left.keyframes[2].spread: expected a number in [-1, 1]"},
    {"UnknownKeyframeKey", [](json& s) { keyframe(s, 1)["grip"] = 1; },
     "hands.left.keyframes[1].grip: unknown key"},
    {"InterpolationUnknown", [](json& s) { s["hands"]["left"]["interpolation"] = "cubic"; },
     R"(hands.left.interpolation: unknown interpolation "cubic" (expected linear or smooth))"},
    {"ScaleZero", [](json& s) { s["hands"]["left"]["scale"] = 0; },
     "hands.left.scale: expected a number > 0"},

    // Tracking.
    {"RateZero", [](json& s) { s["tracking"]["rate_hz"] = 0; },
     "tracking.rate_hz: expected a number > 0"},
    {"NoiseNegative", [](json& s) { s["tracking"]["noise_mm"] = -1; },
     "tracking.noise_mm: expected a number >= 0"},
    {"SeedNegative", [](json& s) { s["tracking"]["seed"] = -1; },
     "tracking.seed: expected a non-negative integer"},
    {"SeedFraction", [](json& s) { s["tracking"]["seed"] = 1.5; },
     "tracking.seed: expected a non-negative integer"},
    {"UnknownTrackingKey", [](json& s) { s["tracking"]["jitter"] = 1; },
     "tracking.jitter: unknown key"},
    {"DropoutHandUnknown", [](json& s) { s["tracking"]["dropouts"][0]["hand"] = "both"; },
     R"(tracking.dropouts[0].hand: unknown hand "both" (expected left or right))"},
    {"DropoutEmpty", [](json& s) { s["tracking"]["dropouts"][0]["to_s"] = 3.0; },
     "tracking.dropouts[0].to_s: expected a time after from_s (3)"},
    {"DropoutUnknownKey", [](json& s) { s["tracking"]["dropouts"][0]["side"] = "left"; },
     "tracking.dropouts[0].side: unknown key"},

    // Success predicates.
    {"SuccessNotArray", [](json& s) { s["success"] = json::object(); },
     "success: expected an array"},
    {"PredicateTypeMissing", [](json& s) { predicate(s, 0).erase("type"); },
     "success[0].type: required"},
    {"PredicateTypeUnknown", [](json& s) { predicate(s, 0)["type"] = "near"; },
     R"(success[0].type: unknown predicate type "near" (expected above, inside, displaced, stacked, held or at_rest))"},
    {"PredicateUnknownBody", [](json& s) { predicate(s, 1)["body"] = "cube9"; },
     R"(success[1].body: no collider with id "cube9")"},
    {"PredicateBodyMissing", [](json& s) { predicate(s, 2).erase("body"); },
     "success[2].body: required"},
    {"PredicateKeyOfAnotherType", [](json& s) { predicate(s, 0)["tolerance"] = 0.1; },
     "success[0].tolerance: unknown key"},
    {"HeldWithAt", [](json& s) { predicate(s, 4)["at"] = "end"; }, "success[4].at: unknown key"},
    {"AtUnknownWord", [](json& s) { predicate(s, 0)["at"] = "start"; },
     R"(success[0].at: expected a time >= 0 or "end")"},
    {"AtNegative", [](json& s) { predicate(s, 1)["at"] = -1; },
     R"(success[1].at: expected a time >= 0 or "end")"},
    {"AboveMinYMissing", [](json& s) { predicate(s, 0).erase("min_y"); },
     "success[0].min_y: required"},
    {"InsideRegionHalfExtentsMissing",
     [](json& s) { predicate(s, 1)["region"].erase("half_extents"); },
     "success[1].region.half_extents: required"},
    {"InsideRegionUnknownKey", [](json& s) { predicate(s, 1)["region"]["size"] = 1; },
     "success[1].region.size: unknown key"},
    {"DisplacedMinDistanceZero", [](json& s) { predicate(s, 2)["min_distance"] = 0; },
     "success[2].min_distance: expected a number > 0"},
    {"StackedUnknownBody", [](json& s) { predicate(s, 3)["bodies"][1] = "cube9"; },
     R"(success[3].bodies[1]: no collider with id "cube9")"},
    {"StackedOneBody", [](json& s) { predicate(s, 3)["bodies"] = {"cube1"}; },
     "success[3].bodies: expected an array of at least 2 ids"},
    {"StackedToleranceZero", [](json& s) { predicate(s, 3)["tolerance"] = 0; },
     "success[3].tolerance: expected a number > 0"},
    {"HeldEmptyInterval", [](json& s) { predicate(s, 4)["to_s"] = 3.0; },
     "success[4].to_s: expected a time after from_s (4)"},
    {"AtRestMaxSpeedZero", [](json& s) { predicate(s, 5)["max_speed"] = 0; },
     "success[5].max_speed: expected a number > 0"},
};

INSTANTIATE_TEST_SUITE_P(SceneLoader, FormatErrors, ::testing::ValuesIn(kErrorCases),
                         [](const auto& info) { return info.param.name; });

// ---- Invalid JSON ---------------------------------------------------------------------

TEST(SceneLoader, SyntaxErrorNamesLineAndColumn) {
    EXPECT_THAT(error_of_text("{\n  \"format\": }"),
                StartsWith("invalid JSON: parse error at line 2, column 13"));
}

TEST(SceneLoader, NumberOverflowIsInvalidJson) {
    std::string text = base_scene().dump();
    text.replace(text.find("12.5"), 4, "1e999");
    EXPECT_THAT(error_of_text(text), StartsWith("invalid JSON: number overflow"));
}

TEST(SceneLoader, DuplicateKeysAreErrors) {
    EXPECT_THAT(error_of_text(R"({"format": "physhand-scene/1", "format": "physhand-scene/1"})"),
                StartsWith("format: duplicate key"));
    std::string text = base_scene().dump();
    const std::string mass = R"("mass":0.05)";
    text.replace(text.find(mass), mass.size(), mass + ',' + mass);
    EXPECT_THAT(error_of_text(text), StartsWith("colliders[3].mass: duplicate key"));
}

// ---- Recorded tracks ------------------------------------------------------------------

constexpr const char* kTrackHeader = "t,joint,px,py,pz,qx,qy,qz,qw,radius,valid";

// One CSV row: joint j at (j/100, t, -0.3), orientation [0, 0, 3, 4] (normalised on load).
std::string track_row(double t, int joint, int valid = 1) {
    std::ostringstream row;
    row << t << ',' << joint << ',' << joint / 100.0 << ',' << t << ",-0.3,0,0,3,4,0.01," << valid;
    return row.str();
}

// The 26 rows of one sample time, joints in order.
std::vector<std::string> track_sample(double t) {
    std::vector<std::string> rows;
    for (int j = 0; j < static_cast<int>(kJointCount); ++j) rows.push_back(track_row(t, j));
    return rows;
}

std::string track_csv(const std::vector<std::string>& rows, const std::string& eol = "\n") {
    std::string text = std::string(kTrackHeader) + eol;
    for (const std::string& row : rows) text += row + eol;
    return text;
}

json scene_with_right_track(const std::string& track) {
    json scene = json::parse(kMinimalScene);
    scene["hands"]["right"] = {{"track", track}};
    return scene;
}

TEST(SceneLoader, ParsesRecordedTrack) {
    const fs::path dir = test_dir();
    std::vector<std::string> rows = track_sample(0.0);
    // The second sample lists its joints in reverse order and has one invalid joint
    // (with a zero quaternion, which an invalid row may carry).
    std::vector<std::string> second = track_sample(0.1);
    std::reverse(second.begin(), second.end());
    second[0] = "0.1,25,0,0,0,0,0,0,0,0,0";
    rows.insert(rows.end(), second.begin(), second.end());
    write_file(dir / "recordings" / "right.csv", track_csv(rows));

    const Scene scene = parse_scene(scene_with_right_track("recordings/right.csv").dump(), dir);
    ASSERT_TRUE(scene.hand(HandSide::Right).has_value());
    const HandScript& right = *scene.hand(HandSide::Right);
    EXPECT_TRUE(right.keyframes.empty());
    ASSERT_EQ(right.recorded.size(), 2u);

    const RecordedSample& first = right.recorded[0];
    EXPECT_DOUBLE_EQ(first.t, 0.0);
    EXPECT_TRUE(first.hand.active);
    EXPECT_TRUE(first.hand[Joint::IndexTip].position.isApprox(Vec3(0.10, 0.0, -0.3)));
    EXPECT_DOUBLE_EQ(first.hand[Joint::IndexTip].orientation.z(), 0.6);
    EXPECT_DOUBLE_EQ(first.hand[Joint::IndexTip].orientation.w(), 0.8);
    EXPECT_DOUBLE_EQ(first.hand.radii[index_of(Joint::Wrist)], 0.01);

    const RecordedSample& last = right.recorded[1];
    EXPECT_DOUBLE_EQ(last.t, 0.1);
    EXPECT_FALSE(last.hand.active);  // joint 25 was not valid
    EXPECT_TRUE(last.hand[Joint::Palm].position.isApprox(Vec3(0.0, 0.1, -0.3)));
    EXPECT_TRUE(last.hand[Joint::LittleTip].orientation.isApprox(Quat::Identity()));
}

TEST(SceneLoader, RecordedTrackAcceptsCrLf) {
    const fs::path dir = test_dir();
    write_file(dir / "right.csv", track_csv(track_sample(0.0), "\r\n"));
    const Scene scene = parse_scene(scene_with_right_track("right.csv").dump(), dir);
    EXPECT_EQ(scene.hand(HandSide::Right)->recorded.size(), 1u);
}

struct TrackErrorCase {
    std::string name;
    std::function<std::string()> csv;
    std::string message;  // contained in FormatError::what()
};

void PrintTo(const TrackErrorCase& c, std::ostream* out) {
    *out << c.name;
}

class TrackErrors : public ::testing::TestWithParam<TrackErrorCase> {};

TEST_P(TrackErrors, NameTheFileAndLine) {
    const fs::path dir = test_dir();
    write_file(dir / "rec" / "bad.csv", GetParam().csv());
    const std::string error = error_of(scene_with_right_track("rec/bad.csv"), dir);
    EXPECT_THAT(error, StartsWith("hands.right.track: rec/bad.csv:"));
    EXPECT_THAT(error, HasSubstr(GetParam().message));
}

// The rows of one sample at t=0 with row `i` (file line i + 2) replaced.
std::string sample_with_row(std::size_t i, const std::string& row) {
    std::vector<std::string> rows = track_sample(0.0);
    rows[i] = row;
    return track_csv(rows);
}

const TrackErrorCase kTrackErrorCases[] = {
    {"WrongHeader", [] { return "t,joint,x,y,z\n" + track_row(0, 0) + "\n"; },
     "rec/bad.csv:1: expected the header \"t,joint,px,py,pz,qx,qy,qz,qw,radius,valid\""},
    {"EmptyFile", [] { return std::string(); }, "rec/bad.csv:1: expected the header"},
    {"HeaderOnly", [] { return track_csv({}); }, "rec/bad.csv:1: no samples after the header"},
    {"TooFewFields", [] { return sample_with_row(1, "0,1,0,0,0,0,0,0,1,0.01"); },
     "rec/bad.csv:3: expected 11 fields, got 10"},
    {"TooManyFields", [] { return sample_with_row(0, track_row(0, 0) + ",1"); },
     "rec/bad.csv:2: expected 11 fields, got 12"},
    {"NotANumber", [] { return sample_with_row(2, "0,2,abc,0,0,0,0,0,1,0.01,1"); },
     "rec/bad.csv:4: px: expected a finite number, got \"abc\""},
    {"EmptyField", [] { return sample_with_row(2, "0,2,0,0,0,0,0,0,1,,1"); },
     "rec/bad.csv:4: radius: expected a finite number, got \"\""},
    {"Infinite", [] { return sample_with_row(3, "0,3,0,inf,0,0,0,0,1,0.01,1"); },
     "rec/bad.csv:5: py: expected a finite number, got \"inf\""},
    {"JointOutOfRange", [] { return sample_with_row(25, "0,26,0,0,0,0,0,0,1,0.01,1"); },
     "rec/bad.csv:27: joint: expected an integer in [0, 25]"},
    {"JointFraction", [] { return sample_with_row(4, "0,4.5,0,0,0,0,0,0,1,0.01,1"); },
     "rec/bad.csv:6: joint: expected an integer in [0, 25]"},
    {"ValidNotBoolean", [] { return sample_with_row(0, "0,0,0,0,0,0,0,0,1,0.01,2"); },
     "rec/bad.csv:2: valid: expected 0 or 1"},
    {"NegativeRadius", [] { return sample_with_row(0, "0,0,0,0,0,0,0,0,1,-0.01,1"); },
     "rec/bad.csv:2: radius: expected a number >= 0"},
    {"ZeroQuaternionOnValidRow", [] { return sample_with_row(13, "0,13,0,0,0,0,0,0,0,0.01,1"); },
     "rec/bad.csv:15: zero quaternion on a valid row"},
    {"JointTwice", [] { return sample_with_row(6, track_row(0, 5)); },
     "rec/bad.csv:8: joint 5 appears twice at t=0"},
    {"IncompleteSample",
     [] {
         std::vector<std::string> rows = track_sample(0.0);
         rows.pop_back();
         for (const std::string& row : track_sample(0.1)) rows.push_back(row);
         return track_csv(rows);
     },
     "rec/bad.csv:2: the sample at t=0 has 25 joints (expected 26)"},
    {"IncompleteLastSample",
     [] {
         std::vector<std::string> rows = track_sample(0.0);
         rows.push_back(track_row(0.1, 0));
         return track_csv(rows);
     },
     "rec/bad.csv:28: the sample at t=0.1 has 1 joints (expected 26)"},
    {"TimeGoesBack",
     [] {
         std::vector<std::string> rows = track_sample(0.1);
         for (const std::string& row : track_sample(0.0)) rows.push_back(row);
         return track_csv(rows);
     },
     "rec/bad.csv:28: t=0 is before the previous sample's t=0.1"},
};

INSTANTIATE_TEST_SUITE_P(SceneLoader, TrackErrors, ::testing::ValuesIn(kTrackErrorCases),
                         [](const auto& info) { return info.param.name; });

TEST(SceneLoader, MissingTrackFile) {
    const fs::path dir = test_dir();
    EXPECT_THAT(error_of(scene_with_right_track("nowhere.csv"), dir),
                StartsWith("hands.right.track: cannot open " + (dir / "nowhere.csv").string()));
}

// ---- load_scene -----------------------------------------------------------------------

TEST(SceneLoader, LoadSceneResolvesTracksBesideTheFile) {
    const fs::path dir = test_dir();
    write_file(dir / "recordings" / "right.csv", track_csv(track_sample(0.5)));
    write_file(dir / "scene.json", scene_with_right_track("recordings/right.csv").dump(2));
    const Scene scene = load_scene(dir / "scene.json");
    EXPECT_EQ(scene.name, "empty");
    ASSERT_EQ(scene.hand(HandSide::Right)->recorded.size(), 1u);
    EXPECT_DOUBLE_EQ(scene.hand(HandSide::Right)->recorded[0].t, 0.5);
}

// The message of the FormatError that load_scene(file) throws.
std::string load_error(const fs::path& file) {
    try {
        load_scene(file);
    } catch (const FormatError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no FormatError for " << file;
    return "";
}

TEST(SceneLoader, LoadSceneMissingFile) {
    const fs::path file = test_dir() / "missing.json";
    EXPECT_EQ(load_error(file), file.string() + ": cannot open");
}

TEST(SceneLoader, LoadSceneInvalidJsonNamesFileAndPosition) {
    const fs::path file = test_dir() / "broken.json";
    write_file(file, "{\n  \"format\": \"physhand-scene/1\",\n  \"name\" \"x\"\n}\n");
    EXPECT_THAT(load_error(file),
                StartsWith(file.string() + ": invalid JSON: parse error at line 3, column"));
}

TEST(SceneLoader, LoadScenePrefixesErrorsWithTheFile) {
    const fs::path file = test_dir() / "scene.json";
    json scene = base_scene();
    collider(scene, 0)["id"] = 7;
    write_file(file, scene.dump(2));
    EXPECT_EQ(load_error(file), file.string() + ": colliders[0].id: expected a string");
}

}  // namespace
}  // namespace physhand
