#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "collider.h"
#include "drive.h"
#include "overlay_renderer.h"

namespace physhand::layer {

// The user's settings for the layer (a JSON file; see load_config).
struct Config {
    bool enabled = true;  // false: every call passes straight through
    bool overlay = true;  // false: no overlay at all (neither ghost nor physical hands drawn)
    // How the overlay draws the hands: colours, ghost opacity, contact tint on or off.
    overlay::Settings drawing;
    DriveSettings drive = default_drive();
    // Static colliders in the STAGE frame, for apps that declare none themselves.
    std::vector<Collider> colliders;
};

// Values replacing a built-in drive's own; absent keeps the drive's value.
struct DriveOverrides {
    std::optional<double> stiffness;
    std::optional<double> damping;
    std::optional<double> force_limit;
    std::optional<int> substeps;
};

// The built-in drive `name` ("" for the default one) with `overrides` applied; nullopt when
// no drive has that name. Throws std::invalid_argument naming the first bad value
// (stiffness > 0, damping >= 0, force_limit >= 0 with 0 unlimited, substeps 1..kMaxSubsteps).
std::optional<DriveSettings> make_drive(std::string_view name, const DriveOverrides& overrides);

// Parses a config file's text. Unknown keys are errors, so a typo never passes silently.
// Throws std::runtime_error naming the key at fault.
Config parse_config(const std::string& json_text);

// The config file named by PHYSHAND_CONFIG, else $XDG_CONFIG_HOME/physhand/config.json
// (XDG_CONFIG_HOME defaulting to ~/.config). No file there: the defaults. A file that
// cannot be read or parsed is reported once on stderr and the defaults are used, so a
// broken config never stops an app.
Config load_config();

}  // namespace physhand::layer
