#include "skeleton_fit.h"

#include <algorithm>
#include <cmath>

namespace physhand {

namespace {

// How long the noise estimates remember, s.
constexpr double kNoiseMemory = 0.5;
// A bone's offset is the mean of its samples over about this long, s (at first of all of
// them): a person's bones keep their lengths.
constexpr double kBoneMemory = 10.0;
// A sample this far from its bone's offset is not learned (a burst of noise, another hand's
// pose, garbage), m, unless kRelearnAfter samples in a row are: then the bone is learned
// anew from the next (the offset was what was wrong).
constexpr double kOutlier = 0.015;
constexpr int kRelearnAfter = 45;
// Beside that mean, one over kNoiseMemory: where the two part by more than this, m, and by
// kDriftSpread times as much as they have (the noise moves the shorter mean too), the bone has
// changed (a runtime refining its hand model) and is learned anew from this sample on.
constexpr double kChangedBone = 0.5e-3;
constexpr double kDriftSpread = 4.0;
// Where the bones as positions and as orientations give them disagree by less than this
// (per axis, RMS), the ghost passes as it came, and the fit is phased in up to twice it, m.
constexpr double kCleanDisagreement = 0.25e-3;
// A disagreement past this is more than any tracker's noise: the orientations do not describe
// the bones (a runtime that leaves them at identity), and the fit is phased out by twice it.
constexpr double kUnrelatedDisagreement = 6e-3;
// Joints that have a parent; the wrist is the root.
constexpr double kBoneCount = kJointCount - 1;

JointVectors bones_from_positions(const HandPose& ghost) {
    JointVectors out = zero_vectors();
    for (std::size_t j = 0; j < kJointCount; ++j) {
        if (const auto parent = joint_parent(static_cast<Joint>(j)))
            out[j] = ghost.joints[j].position - ghost[*parent].position;
    }
    return out;
}

}  // namespace

JointVectors SkeletonFit::bones_from_orientations(const HandPose& ghost) const {
    JointVectors out = zero_vectors();
    for (std::size_t j = 0; j < kJointCount; ++j) {
        if (const auto parent = joint_parent(static_cast<Joint>(j)))
            out[j] = ghost[*parent].orientation * offset_[j];
    }
    return out;
}

void SkeletonFit::learn(const HandPose& ghost, const JointVectors& from_positions, double dt) {
    const double recent_weight = running_weight(dt, kNoiseMemory);
    const double memory_weight = running_weight(dt, kBoneMemory);
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const auto parent = joint_parent(static_cast<Joint>(j));
        if (!parent) continue;
        const Vec3 local = ghost[*parent].orientation.inverse() * from_positions[j];
        Bone& b = bones_[j];
        if (b.samples > 0.0 && (local - offset_[j]).norm() > kOutlier) {
            if (++b.outliers > kRelearnAfter) b.samples = 0.0;
            continue;
        }
        b.outliers = 0;
        const double a = std::max(1.0 / (b.samples + 1.0), memory_weight);
        b.samples = 1.0 / a;
        offset_[j] += a * (local - offset_[j]);
        recent_[j] += std::max(a, recent_weight) * (local - recent_[j]);
        const double drift = (recent_[j] - offset_[j]).squaredNorm();
        if (drift > std::max(kChangedBone * kChangedBone, kDriftSpread * kDriftSpread * b.drift)) {
            offset_[j] = recent_[j] = local;
            b = Bone{.samples = 1.0};
        }
        b.drift += a * (drift - b.drift);
    }
}

void SkeletonFit::restart(const HandPose& ghost) {
    started_ = measuring_ = true;
    const JointVectors from_positions = bones_from_positions(ghost);
    learn(ghost, from_positions, 0.0);
    position_differences_.restart(from_positions);
    orientation_differences_.restart(bones_from_orientations(ghost));
}

double SkeletonFit::position_noise() const {
    return std::sqrt(position_variance_);
}

void SkeletonFit::measure_noise(const JointVectors& from_positions,
                                const JointVectors& from_orientations, double dt) {
    const std::optional<JointVectors> p = position_differences_.add(from_positions, dt);
    const std::optional<JointVectors> o = orientation_differences_.add(from_orientations, dt);
    if (!p || !o) return;
    double p_sum = 0.0, o_sum = 0.0, length_sum = 0.0;
    for (std::size_t j = 0; j < kJointCount; ++j) {
        p_sum += (*p)[j].squaredNorm();
        o_sum += (*o)[j].squaredNorm();
        length_sum += offset_[j].squaredNorm();
    }
    const double a = running_weight(dt, kNoiseMemory);
    position_variance_ += a * (p_sum / (3.0 * 20.0 * kBoneCount) - position_variance_);
    if (length_sum > 0.0)
        orientation_variance_ += a * (o_sum / (3.0 * 20.0 * length_sum) - orientation_variance_);
}

HandPose SkeletonFit::apply(const HandPose& ghost, double dt) {
    const JointVectors from_positions = bones_from_positions(ghost);
    // The bones as the orientations give them are measured before this sample is learned,
    // so that their noise is their own.
    const JointVectors from_orientations = bones_from_orientations(ghost);
    if (!(dt > 0.0) || !started_) {
        restart(ghost);
        return ghost;
    }
    double sample_disagreement = 0.0;
    for (std::size_t j = 0; j < kJointCount; ++j)
        sample_disagreement += (from_orientations[j] - from_positions[j]).squaredNorm();
    disagreement_variance_ += running_weight(dt, kNoiseMemory) *
                              (sample_disagreement / (3.0 * kBoneCount) - disagreement_variance_);
    // Positions and orientations that agree need nothing learned, measured or fitted.
    if (disagreement_variance_ <= kCleanDisagreement * kCleanDisagreement) {
        measuring_ = false;
        return ghost;
    }
    if (!measuring_) {
        position_differences_.restart(from_positions);
        orientation_differences_.restart(from_orientations);
        measuring_ = true;
    } else {
        measure_noise(from_positions, from_orientations, dt);
    }
    learn(ghost, from_positions, dt);
    const double disagreement = std::sqrt(disagreement_variance_);
    const double phase_in =
        std::clamp((disagreement - kCleanDisagreement) / kCleanDisagreement, 0.0, 1.0) *
        std::clamp(2.0 - disagreement / kUnrelatedDisagreement, 0.0, 1.0);
    if (phase_in == 0.0 || !(position_variance_ > 0.0)) return ghost;

    // Each bone weighed by the inverse of its noise; the orientations' includes what the
    // learned offset still has of the position noise it was learned from.
    const double p_var = position_variance_;
    JointVectors chain = zero_vectors();
    Vec3 shift = Vec3::Zero();
    for (std::size_t j = 0; j < kJointCount; ++j) {
        const auto parent = joint_parent(static_cast<Joint>(j));
        if (!parent) continue;
        const double o_var = orientation_variance_ * offset_[j].squaredNorm() +
                             p_var / std::max(bones_[j].samples, 1.0);
        const double w = phase_in * p_var / (p_var + o_var);
        chain[j] = from_positions[j] + w * (from_orientations[j] - from_positions[j]);
    }
    // Chained from the wrist (the palm, joint 0, hangs off it too).
    const std::size_t wrist = index_of(Joint::Wrist);
    JointVectors placed = zero_vectors();
    for (std::size_t j = 0; j < kJointCount; ++j) {
        if (j == wrist) continue;
        const std::size_t parent = index_of(*joint_parent(static_cast<Joint>(j)));
        placed[j] = placed[parent] + chain[j];
    }
    for (std::size_t j = 0; j < kJointCount; ++j) shift += ghost.joints[j].position - placed[j];
    shift /= static_cast<double>(kJointCount);
    HandPose out = ghost;
    for (std::size_t j = 0; j < kJointCount; ++j) out.joints[j].position = placed[j] + shift;
    return out;
}

}  // namespace physhand
