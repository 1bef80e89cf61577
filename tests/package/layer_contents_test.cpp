// What the layer's shared libraries carry into every app: the one the loader loads exports
// one function and carries nothing but the opening of the layer proper; the layer proper
// exports the same function alone and carries the simulation core and the collider syntax
// of its config, and none of the scene player (scene files, tracking scripts, predicates,
// metrics), which lives in its own library.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr const char* kShim = PHYSHAND_LAYER_LIBRARY;
constexpr const char* kLayer = PHYSHAND_LAYER_IMPL_LIBRARY;

// The lines `command` prints; fails the test when it fails.
std::vector<std::string> lines_of(const std::string& command) {
    std::vector<std::string> lines;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (pipe == nullptr) {
        ADD_FAILURE() << "cannot run " << command;
        return lines;
    }
    std::string output;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
    EXPECT_EQ(pclose(pipe), 0) << command << ":\n" << output;
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& text) {
    for (const std::string& line : lines) {
        if (line.find(text) != std::string::npos) return true;
    }
    return false;
}

TEST(LayerContents, ExportsOnlyTheLoaderNegotiation) {
    for (const char* library : {kShim, kLayer}) {
        const std::vector<std::string> exported =
            lines_of(std::string("nm -D --defined-only ") + library);
        ASSERT_EQ(exported.size(), 1u) << library << " exports:\n"
                                       << testing::PrintToString(exported);
        EXPECT_TRUE(exported[0].ends_with(" T xrNegotiateLoaderApiLayerInterface")) << exported[0];
    }
}

TEST(LayerContents, TheLoadedLibraryOnlyOpensTheLayerProper) {
    const std::vector<std::string> symbols = lines_of(std::string("nm -C ") + kShim);
    EXPECT_TRUE(any_contains(symbols, "open_layer"));
    EXPECT_FALSE(any_contains(symbols, "physhand::"));
    EXPECT_FALSE(any_contains(lines_of(std::string("ldd ") + kShim), "libBullet"));
}

TEST(LayerContents, CarriesTheSimulationAndColliderSyntaxButNoScenePlayer) {
    const std::vector<std::string> symbols = lines_of(std::string("nm -C ") + kLayer);
    // What the layer needs is there, so the absences below are not those of a stripped file.
    EXPECT_TRUE(any_contains(symbols, "physhand::Simulation::step_sampling"));
    EXPECT_TRUE(any_contains(symbols, "physhand::syntax::read_collider"));
    for (const char* player :
         {"physhand::load_scene", "physhand::parse_scene", "physhand::PredicateEvaluator",
          "physhand::RunMetrics", "physhand::TrackedHands", "physhand::run_scene",
          "physhand::scene_variants", "physhand::summary_line"}) {
        EXPECT_FALSE(any_contains(symbols, player)) << player;
    }
}

}  // namespace
