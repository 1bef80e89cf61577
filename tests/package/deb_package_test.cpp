// The Debian package: `cpack -G DEB` in the build tree makes physhand_VERSION_ARCH.deb, whose
// implicit manifest names the library it installs, so that the loader, searching where the
// package puts it, finds the layer once and loads it.

#include <gtest/gtest.h>
#include <openxr/openxr.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "openxr/physhand_physical_hands.h"

namespace {

namespace fs = std::filesystem;

constexpr const char* kLayerName = "XR_APILAYER_PHYSHAND_physical_hands";

// Runs a shell command, returning its output; fails the test when it fails.
std::string run(const std::string& command) {
    std::string output;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (pipe == nullptr) {
        ADD_FAILURE() << "cannot run " << command;
        return output;
    }
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
    EXPECT_EQ(pclose(pipe), 0) << command << ":\n" << output;
    return output;
}

std::string trimmed(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

class DebPackage : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("physhand_deb_package_" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    fs::path dir_;
};

TEST_F(DebPackage, InstallsTheLayerWhereTheLoaderFindsItOnce) {
    run("cpack --config '" PHYSHAND_BUILD_DIR "/CPackConfig.cmake' -G DEB -B '" + dir_.string() +
        "'");
    const std::string arch = trimmed(run("dpkg --print-architecture"));
    const fs::path deb = dir_ / ("physhand_" PHYSHAND_VERSION "_" + arch + ".deb");
    ASSERT_TRUE(fs::exists(deb)) << deb;

    const std::string fields = run("dpkg-deb -f '" + deb.string() + "' Package Depends");
    EXPECT_NE(fields.find("Package: physhand"), std::string::npos) << fields;
    EXPECT_NE(fields.find("libopenxr-loader1"), std::string::npos) << fields;

    const fs::path root = dir_ / "root";
    run("dpkg-deb -x '" + deb.string() + "' '" + root.string() + "'");
    const fs::path usr = root / "usr";
    const fs::path manifest_dir = usr / "share/openxr/1/api_layers/implicit.d";
    const fs::path manifest = manifest_dir / "XrApiLayer_physhand.json";
    ASSERT_TRUE(fs::exists(manifest));
    EXPECT_TRUE(fs::exists(usr / "include/openxr/physhand_physical_hands.h"));
    EXPECT_TRUE(fs::exists(usr / "bin/physhand-scene"));
    EXPECT_TRUE(fs::exists(usr / "bin/physhand-sample"));
    EXPECT_TRUE(fs::exists(usr / "share/physhand/scenes/lift_hold.json"));
    EXPECT_TRUE(fs::exists(usr / "share/doc/physhand/examples/config.json"));
    // Only the implicit manifest where the loader looks: the explicit one there too would
    // list the layer twice.
    EXPECT_FALSE(fs::exists(usr / "share/openxr/1/api_layers/explicit.d"));
    EXPECT_TRUE(fs::exists(usr / "share/physhand/explicit/XrApiLayer_physhand.json"));

    // The manifest names the library the package installs, as it will lie under /usr.
    std::ifstream in(manifest);
    const nlohmann::json json = nlohmann::json::parse(in);
    const fs::path library = json.at("api_layer").at("library_path").get<std::string>();
    ASSERT_TRUE(library.is_relative()) << library;
    const fs::path installed = (manifest_dir / library).lexically_normal();
    EXPECT_TRUE(fs::is_regular_file(installed)) << installed;
    EXPECT_EQ(installed.filename(), "libXrApiLayer_physhand.so");
    EXPECT_EQ(json.at("api_layer").at("name"), kLayerName);

    // The loader, searching the package's share/ alone, lists the layer once and loads it.
    setenv("XDG_DATA_DIRS", (usr / "share").c_str(), 1);
    setenv("XDG_DATA_HOME", (dir_ / "no_data_home").c_str(), 1);
    setenv("XDG_CONFIG_HOME", (dir_ / "no_config_home").c_str(), 1);
    unsetenv("XR_API_LAYER_PATH");
    unsetenv("XR_ENABLE_API_LAYERS");
    std::uint32_t count = 0;
    ASSERT_EQ(xrEnumerateApiLayerProperties(0, &count, nullptr), XR_SUCCESS);
    XrApiLayerProperties empty{};
    empty.type = XR_TYPE_API_LAYER_PROPERTIES;
    std::vector<XrApiLayerProperties> layers(count, empty);
    ASSERT_EQ(xrEnumerateApiLayerProperties(count, &count, layers.data()), XR_SUCCESS);
    EXPECT_EQ(std::count_if(layers.begin(), layers.end(),
                            [](const XrApiLayerProperties& p) {
                                return std::strcmp(p.layerName, kLayerName) == 0;
                            }),
              1);

    setenv("XR_RUNTIME_JSON", PHYSHAND_SIM_RUNTIME_JSON, 1);
    const char* extensions[] = {XR_PHYSHAND_PHYSICAL_HANDS_EXTENSION_NAME};
    XrInstanceCreateInfo info{};
    info.type = XR_TYPE_INSTANCE_CREATE_INFO;
    std::strcpy(info.applicationInfo.applicationName, "physhand deb test");
    info.applicationInfo.apiVersion = XR_CURRENT_API_VERSION;
    info.enabledExtensionCount = 1;
    info.enabledExtensionNames = extensions;
    XrInstance instance = XR_NULL_HANDLE;
    ASSERT_EQ(xrCreateInstance(&info, &instance), XR_SUCCESS)
        << "the extension only the layer offers, from the packaged layer";
    EXPECT_EQ(xrDestroyInstance(instance), XR_SUCCESS);
}

}  // namespace
