#pragma once

#include <openxr/openxr.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "hand_skeleton.h"

namespace physhand::layer {

// Writes the ghost hands of a session as recorded tracks (docs/scene-format.md,
// "Recorded"), one CSV per hand, so that a motion recorded on a headset replays in any
// scene. Enabled by PHYSHAND_RECORD=DIR.
class Recorder {
  public:
    // Null unless PHYSHAND_RECORD names a folder (created if missing). Files are named
    // physhand-<pid>-<session>-<left|right>.csv.
    static std::unique_ptr<Recorder> from_environment(unsigned session_number);

    // One sample: 26 rows at time `t` (seconds of simulation time), joints in the layer's
    // frame (STAGE, the scene files' frame). A joint is valid when its pose is.
    void write(HandSide side, double t,
               const std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT>& joints);

  private:
    Recorder(std::filesystem::path folder, std::string stem);

    std::filesystem::path folder_;
    std::string stem_;
    std::array<std::ofstream, 2> files_;  // by HandSide, opened at the hand's first sample
};

}  // namespace physhand::layer
