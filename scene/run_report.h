#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "scene_run.h"

namespace physhand {

// The result object of docs/design.md ("Command-line tools"), shared by physhand-scene and
// physhand-sample.
nlohmann::json to_json(const RunResult& result);
// One line for people: scene, success, the headline figures.
std::string summary_line(const RunResult& result);

}  // namespace physhand
