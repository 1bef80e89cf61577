#include "contact_announcer.h"

#include <algorithm>
#include <iomanip>

#include "hand_skeleton.h"
#include "xr_check.h"

namespace physhand::sample {

ContactAnnouncer::ContactAnnouncer(XrInstance instance, XrSession session, XrSpace stage)
    : instance_(instance),
      session_(session),
      stage_(stage),
      get_events_(load_function<PFN_xrGetPhysicalContactEventsPHYSHAND>(
          instance, "xrGetPhysicalContactEventsPHYSHAND")) {
    const auto set_reporting = load_function<PFN_xrSetPhysicalContactReportingPHYSHAND>(
        instance, "xrSetPhysicalContactReportingPHYSHAND");
    XrPhysicalContactReportingInfoPHYSHAND info{};
    info.type = XR_TYPE_PHYSICAL_CONTACT_REPORTING_INFO_PHYSHAND;
    xr_check(instance, set_reporting(session, &info), "xrSetPhysicalContactReportingPHYSHAND");
}

void ContactAnnouncer::read(XrTime time, double t, const Scene& scene,
                            const SceneColliders& colliders, std::ostream& out) {
    XrPhysicalContactEventsGetInfoPHYSHAND info{};
    info.type = XR_TYPE_PHYSICAL_CONTACT_EVENTS_GET_INFO_PHYSHAND;
    info.baseSpace = stage_;
    info.time = time;
    XrPhysicalContactEventsPHYSHAND events{};
    events.type = XR_TYPE_PHYSICAL_CONTACT_EVENTS_PHYSHAND;
    xr_check(instance_, get_events_(session_, &info, &events),
             "xrGetPhysicalContactEventsPHYSHAND");
    if (events.eventCountOutput == 0) return;
    events_.resize(events.eventCountOutput);
    events.eventCapacityInput = events.eventCountOutput;
    events.events = events_.data();
    xr_check(instance_, get_events_(session_, &info, &events),
             "xrGetPhysicalContactEventsPHYSHAND");
    began_.resize(scene.colliders.size(), -std::numeric_limits<double>::infinity());
    for (std::uint32_t i = 0; i < events.eventCountOutput; ++i) {
        const XrPhysicalContactEventPHYSHAND& e = events_[i];
        const std::optional<std::size_t> index = colliders.index_of(e.collider);
        if (!index) continue;
        Touch& touch = touches_[{e.hand, *index}];
        if (e.kind == XR_PHYSICAL_CONTACT_EVENT_KIND_END_PHYSHAND) {
            touch.contacts = std::max(touch.contacts - 1, 0);
            if (touch.contacts == 0) touch.left = t;
            continue;
        }
        if (e.kind != XR_PHYSICAL_CONTACT_EVENT_KIND_BEGIN_PHYSHAND) continue;
        const bool new_touch = touch.contacts++ == 0 && t - touch.left >= kQuietS;
        if (!new_touch) continue;
        began_[*index] = t;
        const HandSide side = e.hand == XR_HAND_LEFT_EXT ? HandSide::Left : HandSide::Right;
        out << "touch t=" << std::fixed << std::setprecision(2) << t << " s "
            << hand_side_name(side) << " " << joint_name(static_cast<Joint>(e.joint)) << " -> "
            << scene.colliders[*index].id << " at " << std::setprecision(2) << e.approachSpeed
            << " m/s\n";
    }
    out.unsetf(std::ios::fixed);
}

std::vector<float> ContactAnnouncer::flashes(double t, std::size_t collider_count) const {
    std::vector<float> out(collider_count, 0.0f);
    for (std::size_t i = 0; i < std::min(collider_count, began_.size()); ++i) {
        out[i] = static_cast<float>(std::clamp(1.0 - (t - began_[i]) / kFlashS, 0.0, 1.0));
    }
    return out;
}

}  // namespace physhand::sample
