#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "scene.h"

namespace physhand::sample {

// When each dynamic collider was touched, and where it was seen then: for each, its longest
// run of touched frames and, at the run's middle frame, where its centre appeared in view 0,
// and the last frame before its first touch, when a hand was about to touch it, with where
// it appeared then (so captured frames of these moments can be checked).
class TouchLog {
  public:
    // Where a scene point appears in view 0 (SceneGraphics::view0_position).
    using ViewPosition = std::function<std::optional<std::array<double, 2>>(const Vec3&)>;

    explicit TouchLog(const Scene& scene);

    // Scene frame `frame`, just rendered, with every collider in scene order.
    void add_frame(int frame, const std::vector<XrPhysicalColliderLocationPHYSHAND>& colliders,
                   const ViewPosition& view0_position);

    // [{"collider", "first_frame", "last_frame", "frame", "view0_position": [x, y] or null,
    //   "approach_frame": frame or null, "approach_view0_position": [x, y] or null}], in
    // scene order, for the colliders touched at all.
    nlohmann::json to_json() const;

  private:
    struct Run {
        int first = 0, last = -1;
        std::vector<std::optional<std::array<double, 2>>> positions;  // per frame of the run
    };
    struct Sighting {
        int frame = 0;
        std::optional<std::array<double, 2>> position;
    };
    struct Track {
        Run current;  // empty (last < first) while untouched
        Run longest;
        bool touched = false;              // at any frame so far
        std::optional<Sighting> approach;  // the latest untouched frame before the first touch
    };

    const Scene& scene_;
    std::vector<Track> tracks_;  // scene order
};

}  // namespace physhand::sample
