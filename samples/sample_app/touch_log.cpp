#include "touch_log.h"

#include "scene_colliders.h"
#include "xr_convert.h"

namespace physhand::sample {

TouchLog::TouchLog(const Scene& scene) : scene_(scene), tracks_(scene.colliders.size()) {}

void TouchLog::add_frame(int frame,
                         const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders,
                         const ViewPosition& view0_position) {
    for (std::size_t i = 0; i < colliders.size(); ++i) {
        if (scene_.colliders[i].motion != Motion::Dynamic) continue;
        Track& track = tracks_[i];
        const Vec3 centre = to_vec3(colliders[i].pose.position);
        if (!touched(colliders[i])) {
            track.current = {};
            if (!track.touched) track.approach = Sighting{frame, view0_position(centre)};
            continue;
        }
        track.touched = true;
        if (track.current.positions.empty()) track.current.first = frame;
        track.current.last = frame;
        track.current.positions.push_back(view0_position(centre));
        if (track.current.positions.size() > track.longest.positions.size()) {
            track.longest = track.current;
        }
    }
}

nlohmann::json TouchLog::to_json() const {
    nlohmann::json out = nlohmann::json::array();
    for (std::size_t i = 0; i < tracks_.size(); ++i) {
        const Run& run = tracks_[i].longest;
        if (run.positions.empty()) continue;
        const std::size_t middle = run.positions.size() / 2;
        const auto position = [](const std::optional<std::array<double, 2>>& p) {
            return p ? nlohmann::json(*p) : nlohmann::json();
        };
        const std::optional<Sighting>& approach = tracks_[i].approach;
        out.push_back(
            {{"collider", scene_.colliders[i].id},
             {"first_frame", run.first},
             {"last_frame", run.last},
             {"frame", run.first + static_cast<int>(middle)},
             {"view0_position", position(run.positions[middle])},
             {"approach_frame", approach ? nlohmann::json(approach->frame) : nlohmann::json()},
             {"approach_view0_position",
              approach ? position(approach->position) : nlohmann::json()}});
    }
    return out;
}

}  // namespace physhand::sample
