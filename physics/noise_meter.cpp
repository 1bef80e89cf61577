#include "noise_meter.h"

#include <algorithm>
#include <cmath>

namespace physhand {

JointVectors positions(const HandPose& hand) {
    JointVectors out;
    for (std::size_t j = 0; j < kJointCount; ++j) out[j] = hand.joints[j].position;
    return out;
}

void ThirdDifferences::restart(const JointVectors& values) {
    history_[0] = values;
    intervals_ = 0;
}

std::optional<JointVectors> ThirdDifferences::add(const JointVectors& values, double dt) {
    const bool same_dt = intervals_ > 0 && std::abs(dt - last_dt_) <= 1e-3 * last_dt_;
    intervals_ = same_dt ? std::min(intervals_ + 1, 3) : 1;
    last_dt_ = dt;
    std::optional<JointVectors> third;
    if (intervals_ == 3) {
        third.emplace();
        for (std::size_t j = 0; j < kJointCount; ++j) {
            (*third)[j] = values[j] - 3.0 * history_[0][j] + 3.0 * history_[1][j] - history_[2][j];
        }
    }
    history_[2] = history_[1];
    history_[1] = history_[0];
    history_[0] = values;
    return third;
}

JointVectors zero_vectors() {
    JointVectors out;
    out.fill(Vec3::Zero());
    return out;
}

double running_weight(double dt, double memory) {
    return 1.0 - std::exp(-dt / memory);
}

}  // namespace physhand
