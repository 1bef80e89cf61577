#include "config.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "collider_syntax.h"
#include "layer_log.h"

namespace physhand::layer {

namespace {

using nlohmann::json;

bool get_bool(const json& value, const std::string& key) {
    if (!value.is_boolean()) throw std::runtime_error(key + ": expected true or false");
    return value.get<bool>();
}

double get_number(const json& value, const std::string& key) {
    if (!value.is_number()) throw std::runtime_error(key + ": expected a number");
    return value.get<double>();
}

int get_int(const json& value, const std::string& key) {
    if (!value.is_number_integer() || value.get<std::int64_t>() < std::numeric_limits<int>::min() ||
        value.get<std::int64_t>() > std::numeric_limits<int>::max()) {
        throw std::runtime_error(key + ": expected an integer");
    }
    return value.get<int>();
}

// A fraction from 0 to 1: a colour channel or an opacity.
float get_fraction(const json& value, const std::string& key, const char* expected) {
    if (!value.is_number() || !(value.get<double>() >= 0.0 && value.get<double>() <= 1.0)) {
        throw std::runtime_error(key + ": expected " + expected);
    }
    return value.get<float>();
}

overlay::Color parse_color(const json& value, const std::string& key) {
    constexpr const char* kExpected = "an array of 3 numbers from 0 to 1 (sRGB red, green, blue)";
    if (!value.is_array() || value.size() != 3) {
        throw std::runtime_error(key + ": expected " + kExpected);
    }
    return {get_fraction(value[0], key, kExpected), get_fraction(value[1], key, kExpected),
            get_fraction(value[2], key, kExpected)};
}

// Absent colours keep the overlay's own.
void parse_colors(const json& object, overlay::Settings& drawing) {
    if (!object.is_object()) throw std::runtime_error("colors: expected an object");
    for (const auto& [key, value] : object.items()) {
        const std::string path = "colors." + key;
        if (key == "left") {
            drawing.hand_colors[0] = parse_color(value, path);
        } else if (key == "right") {
            drawing.hand_colors[1] = parse_color(value, path);
        } else if (key == "contact") {
            drawing.contact_tint = parse_color(value, path);
        } else {
            throw std::runtime_error(path + ": unknown key (known: left, right, contact)");
        }
    }
}

std::string drive_names() {
    std::string names;
    for (const DriveSettings& d : builtin_drives()) names += (names.empty() ? "" : ", ") + d.name;
    return names;
}

DriveSettings parse_drive(const json& object) {
    if (!object.is_object()) throw std::runtime_error("drive: expected an object");
    std::string name;
    DriveOverrides overrides;
    for (const auto& [key, value] : object.items()) {
        const std::string path = "drive." + key;
        if (key == "name") {
            if (!value.is_string()) throw std::runtime_error(path + ": expected a string");
            name = value.get<std::string>();
        } else if (key == "stiffness") {
            overrides.stiffness = get_number(value, path);
        } else if (key == "damping") {
            overrides.damping = get_number(value, path);
        } else if (key == "force_limit") {
            overrides.force_limit = get_number(value, path);
        } else if (key == "substeps") {
            overrides.substeps = get_int(value, path);
        } else {
            throw std::runtime_error(path + ": unknown key");
        }
    }
    std::optional<DriveSettings> drive;
    try {
        drive = make_drive(name, overrides);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(std::string("drive.") + e.what());
    }
    if (!drive) {
        throw std::runtime_error("drive.name: no drive named \"" + name +
                                 "\" (known: " + drive_names() + ")");
    }
    return *drive;
}

// Config colliders are written as a scene file's colliders and read by the same unit; the
// messages name "colliders[i]...", their path in the config file too.
std::vector<Collider> parse_colliders(const json& array) {
    if (!array.is_array()) throw std::runtime_error("colliders: expected an array");
    std::vector<Collider> colliders;
    for (std::size_t i = 0; i < array.size(); ++i) {
        const std::string path = syntax::index_path("colliders", i);
        Collider collider = syntax::read_collider(syntax::Node(array[i], path), colliders);
        if (collider.motion != Motion::Static) {
            throw std::runtime_error(path +
                                     ".motion: expected \"static\" (config colliders are fixed in "
                                     "the room; apps declare moving ones through the extension)");
        }
        colliders.push_back(std::move(collider));
    }
    return colliders;
}

}  // namespace

std::optional<DriveSettings> make_drive(std::string_view name, const DriveOverrides& overrides) {
    std::optional<DriveSettings> drive =
        name.empty() ? std::optional<DriveSettings>(default_drive()) : find_drive(name);
    if (!drive) return std::nullopt;
    const auto checked = [](const char* key, double value, bool zero_allowed) {
        if (!std::isfinite(value) || value < 0 || (value == 0 && !zero_allowed)) {
            throw std::invalid_argument(std::string(key) + ": expected a finite number " +
                                        (zero_allowed ? ">= 0" : "> 0"));
        }
        return value;
    };
    if (overrides.stiffness) drive->stiffness = checked("stiffness", *overrides.stiffness, false);
    if (overrides.damping) drive->damping = checked("damping", *overrides.damping, true);
    if (overrides.force_limit) {
        drive->force_limit = checked("force_limit", *overrides.force_limit, true);
    }
    if (overrides.substeps) {
        if (*overrides.substeps < 1 || *overrides.substeps > kMaxSubsteps) {
            throw std::invalid_argument("substeps: expected an integer from 1 to " +
                                        std::to_string(kMaxSubsteps));
        }
        drive->substeps = *overrides.substeps;
    }
    return drive;
}

Config parse_config(const std::string& json_text) {
    json root;
    try {
        root = json::parse(json_text);
    } catch (const json::exception& e) {
        // nlohmann's exceptions (a syntax error, a number out of range) are not the
        // std::runtime_error callers expect.
        throw std::runtime_error(std::string("invalid JSON: ") + e.what());
    }
    if (!root.is_object()) throw std::runtime_error("expected a JSON object");
    Config config;
    for (const auto& [key, value] : root.items()) {
        if (key == "enabled") {
            config.enabled = get_bool(value, key);
        } else if (key == "overlay") {
            config.overlay = get_bool(value, key);
        } else if (key == "tint") {
            config.drawing.tint = get_bool(value, key);
        } else if (key == "colors") {
            parse_colors(value, config.drawing);
        } else if (key == "ghost_opacity") {
            config.drawing.ghost_alpha = get_fraction(value, key, "a number from 0 to 1");
        } else if (key == "drive") {
            config.drive = parse_drive(value);
        } else if (key == "colliders") {
            config.colliders = parse_colliders(value);
        } else {
            throw std::runtime_error(key + ": unknown key");
        }
    }
    return config;
}

Config load_config() {
    namespace fs = std::filesystem;
    fs::path path;
    bool named = false;
    if (const char* env = std::getenv("PHYSHAND_CONFIG"); env != nullptr && *env != '\0') {
        path = env;
        named = true;
    } else if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg != nullptr && *xdg != '\0') {
        path = fs::path(xdg) / "physhand" / "config.json";
    } else if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
        path = fs::path(home) / ".config" / "physhand" / "config.json";
    } else {
        return {};
    }
    std::ifstream file(path);
    if (!file) {
        // Only a file the user named is missed; the default location is optional.
        if (named) log_once("config " + path.string() + ": cannot be read; using the defaults");
        return {};
    }
    std::stringstream text;
    text << file.rdbuf();
    try {
        return parse_config(text.str());
    } catch (const std::exception& e) {
        log_once("config " + path.string() + ": " + e.what() + "; using the defaults");
        return {};
    }
}

}  // namespace physhand::layer
