#include "recording.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <system_error>

#include "layer_log.h"
#include "xr_util.h"

namespace physhand::layer {

std::unique_ptr<Recorder> Recorder::from_environment(unsigned session_number) {
    const char* folder = std::getenv("PHYSHAND_RECORD");
    if (folder == nullptr || *folder == '\0') return nullptr;
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) {
        log_once(std::string("PHYSHAND_RECORD=") + folder + ": " + error.message() +
                 "; not recording");
        return nullptr;
    }
    return std::unique_ptr<Recorder>(new Recorder(
        folder, "physhand-" + std::to_string(getpid()) + "-" + std::to_string(session_number)));
}

Recorder::Recorder(std::filesystem::path folder, std::string stem)
    : folder_(std::move(folder)), stem_(std::move(stem)) {}

void Recorder::write(HandSide side, double t,
                     const std::array<XrHandJointLocationEXT, XR_HAND_JOINT_COUNT_EXT>& joints) {
    std::ofstream& file = files_[static_cast<int>(side)];
    if (!file.is_open()) {
        const auto path = folder_ / (stem_ + "-" + std::string(hand_side_name(side)) + ".csv");
        file.open(path);
        if (!file) {
            log_once("PHYSHAND_RECORD: cannot write " + path.string());
            return;
        }
        file << "t,joint,px,py,pz,qx,qy,qz,qw,radius,valid\n";
    }
    // %.9g round-trips a float; t keeps microseconds over hours.
    char row[256];
    for (std::size_t i = 0; i < joints.size(); ++i) {
        const XrHandJointLocationEXT& j = joints[i];
        const XrPosef& p = j.pose;
        const bool valid = (j.locationFlags & kPoseValid) == kPoseValid;
        std::snprintf(row, sizeof row, "%.6f,%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", t,
                      i, p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
                      p.orientation.z, p.orientation.w, j.radius, valid ? 1 : 0);
        file << row;
    }
}

}  // namespace physhand::layer
