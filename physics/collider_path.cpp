#include <algorithm>

#include "collider.h"

namespace physhand {

Pose Collider::pose_at(double t) const {
    if (path.empty()) return pose;
    if (t <= path.front().t) return path.front().pose;
    if (t >= path.back().t) return path.back().pose;
    const auto next = std::upper_bound(path.begin(), path.end(), t,
                                       [](double v, const TimedPose& p) { return v < p.t; });
    const TimedPose& a = *(next - 1);
    const TimedPose& b = *next;
    return interpolate(a.pose, b.pose, (t - a.t) / (b.t - a.t));
}

}  // namespace physhand
