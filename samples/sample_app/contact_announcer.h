#pragma once

#include <openxr/openxr.h>
#include <openxr/physhand_physical_hands.h>

#include <limits>
#include <map>
#include <ostream>
#include <utility>
#include <vector>

#include "scene.h"
#include "scene_colliders.h"

namespace physhand::sample {

// The extension's contact events as an app uses them for feedback: a line for each touch
// that begins (which hand part, what, how fast), and a brief flash of the object touched.
// A touch is a hand meeting an object: its parts' contacts begin and end many times while
// it holds or slides over it, so a touch begins only after kQuietS without any.
class ContactAnnouncer {
  public:
    // How long a touched object flashes, s.
    static constexpr double kFlashS = 0.2;
    // How long a hand must have left an object for its next contact to be a new touch, s.
    static constexpr double kQuietS = 0.25;

    // Turns the session's contact events on (begin and end only).
    ContactAnnouncer(XrInstance instance, XrSession session, XrSpace stage);

    // Reads the events since the last call, and writes a line to `out` for each begin, at
    // scene time `t` (the frame displayed at `time`).
    void read(XrTime time, double t, const Scene& scene, const SceneColliders& colliders,
              std::ostream& out);
    // For each collider in scene order, how bright its flash is at scene time `t`: 1 as a
    // touch begins, fading to 0 over kFlashS.
    std::vector<float> flashes(double t, std::size_t collider_count) const;

  private:
    XrInstance instance_;
    XrSession session_;
    XrSpace stage_;
    PFN_xrGetPhysicalContactEventsPHYSHAND get_events_ = nullptr;
    std::vector<XrPhysicalContactEventPHYSHAND> events_;
    std::vector<double> began_;  // scene time of each collider's latest touch, by scene index
    struct Touch {
        int contacts = 0;                                        // hand parts touching it now
        double left = -std::numeric_limits<double>::infinity();  // when the last one ended
    };
    std::map<std::pair<XrHandEXT, std::size_t>, Touch> touches_;  // by hand and scene index
};

}  // namespace physhand::sample
