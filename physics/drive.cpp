#include "drive.h"

#include <algorithm>
#include <cmath>

namespace physhand {

namespace {

// Torque limit = force limit times a finger-length lever.
constexpr double kTorqueLever = 0.03;

// `v` scaled down to the drive's force limit (times `lever` for a torque), or kMaxDriveForce.
Vec3 clamp_norm(const Vec3& v, double force_limit, double lever = 1.0) {
    const double limit =
        (force_limit > 0.0 ? std::min(force_limit, kMaxDriveForce) : kMaxDriveForce) * lever;
    const double n = v.norm();
    if (!std::isfinite(n)) return Vec3::Zero();  // overflowed gains: no usable direction
    return n > limit ? v * (limit / n) : v;
}

// Velocity at the end of the substep under a spring-damper evaluated at that end state
// (backward Euler), for a unit-mass system with gains k, d: stable for any k, d, h.
Vec3 implicit_velocity(const Vec3& error, const Vec3& velocity, const Vec3& target_velocity,
                       double k, double d, double h) {
    return (velocity - h * k * error + h * d * target_velocity) / (1.0 + h * h * k + h * d);
}

}  // namespace

const std::vector<DriveSettings>& builtin_drives() {
    // Gains and smoothing of the implicit drives come from the sweep in BENCHMARKS.md. The
    // stiff drives would pass tracking noise on whole, so they follow a smoothed ghost: 1 Hz
    // when still, the cutoff rising 3.5 kHz per m/s (measured: jitter 4.8 -> 2.1 mm under
    // 2 mm of noise, for 0.03-0.06 mm more tracking error in the moving scenes). Touching or
    // not, they first take out the noise the NoiseFilter measures, expecting joints to change
    // speed by about 1 m/s^2 (robustness benchmark: grips under 3 mm of noise held 16 -> 60 %
    // for bones, 20 -> 80 % for implicit; 0.5-4 m/s^2 within seed noise of that, 4 worse).
    // Before all that, the SkeletonFit puts each joint that moved on its own back on its bone
    // (robustness, bones/1 over 3200 plays: 79.3 -> 88.9 %; noise family 70 -> 89 %).
    // `paper` follows the ghost as it comes, as Algorithm 1 does.
    // The force limit is far above a grip's (a 0.1 kg bone pushes about m/h^2 = 810 N/m times
    // its ghost's reach past what stops it: 3-4 N holding the thrown or placed cube, 15 N
    // while lift_hold's fingers close at curl 0.8).
    // Capping each part's push along its contact normal lower (a grip saturating with depth) kept
    // the squeeze shallower (curl 0.5: 0.8 mm at 3 N against 3.7 mm) but let the squeezed cube go
    // at higher curls, and stalled the displacement task's cube, which a thumb pushes into its hole
    // while the wall stops the rest of the hand (robustness, bones/1, 800 plays: 4 N, displacement
    // 13 of 160 against 128). Capping only while no part touches anything fixed re-aimed the throw
    // rather than steadying it (at 4 N, 3200 plays: 2952 -> 3002, the throw's release speed 1.9 ->
    // 1.7 m/s with the same sideways kick; mirrored throws 16 -> 5 of 16, the mass family's 29 ->
    // 16 of 32: the 3x heavy projectile was not thrown).
    // `bones` joins every bone to the body before it. Unjoined (as it was until the joined hand,
    // then named `jointed`, matched it), its bones parted by up to 53 mm in the sample scenes,
    // and a hand mesh posed on the returned joints showed fingers torn off. Robustness, 3200
    // plays at one substep, unjoined against joined: 3061 against 3064; the displacement task's
    // cube 1.5 and 2 times as heavy placed at 4 and 0 of 16 shifts against 16 and 16; lift_hold
    // squeezed to curls 0.3-1.0 over 16 shifts held 124 against 83 of 128 (the joined hand drops
    // the cube where the ghost's fingers pass right through it, curls 0.7-1.0; unjoined, its
    // bones parted by 45 mm there).
    // A bone is moved out of what it went into in up to three moves, as an edge that turned
    // under it in the substep asks: one move left a thumb 2.2 mm in a squeezed cube that spun
    // (found 8.2 mm deep). lift_hold squeezed to curls 0.3-1.0 over 16 shifts: 74 -> 83 of 128
    // held, contact points 5.6 -> 2.3 mm deep (two moves: 76, 1.8 mm); robustness, 3200 plays,
    // 3055 -> 3064.
    constexpr int kBoneDepenetrationMoves = 3;
    constexpr GhostSmoothing kSmoothing{
        .min_cutoff_hz = 1.0, .beta = 3500.0, .noise_acceleration = 1.0, .fit_skeleton = true};
    static const std::vector<DriveSettings> drives = {
        {"bones", BodyModel::BoneCapsules, DriveLaw::Implicit, 20000.0, 90.0, true, 20.0, 1,
         kSmoothing, kBoneDepenetrationMoves},
        {"implicit", BodyModel::JointSpheres, DriveLaw::Implicit, 20000.0, 90.0, false, 20.0, 2,
         kSmoothing},
        {"paper", BodyModel::JointSpheres, DriveLaw::Explicit, 1000.0, 20.0, false, 0.0, 4, {}},
    };
    return drives;
}

const DriveSettings& default_drive() {
    return builtin_drives().front();
}

std::optional<DriveSettings> find_drive(std::string_view name) {
    if (name == "jointed") name = "bones";
    for (const DriveSettings& d : builtin_drives()) {
        if (d.name == name) return d;
    }
    return std::nullopt;
}

Vec3 drive_force(const DriveSettings& drive, double mass, const LinearState& body,
                 const LinearState& target, double h) {
    const Vec3 error = body.position - target.position;
    Vec3 force;
    if (drive.law == DriveLaw::Explicit) {
        force = -drive.stiffness * error - drive.damping * (body.velocity - target.velocity);
    } else {
        const Vec3 v_next = implicit_velocity(error, body.velocity, target.velocity,
                                              drive.stiffness / mass, drive.damping / mass, h);
        force = mass * (v_next - body.velocity) / h;
    }
    return clamp_norm(force, drive.force_limit);
}

Vec3 drive_torque(const DriveSettings& drive, double mass, const Eigen::Matrix3d& inertia_world,
                  const Quat& orientation, const Vec3& angular_velocity, const Quat& target,
                  const Vec3& target_angular_velocity, double h, bool resting) {
    // Like p - p_g: minus the rotation still to go.
    const Vec3 error = -rotation_between(orientation, target);
    const double scale = resting ? kRestingOrientationStiffness : 1.0;
    const double k = scale * drive.stiffness / mass;
    const double d = std::sqrt(scale) * drive.damping / mass;
    Vec3 acceleration;
    if (drive.law == DriveLaw::Explicit) {
        acceleration = -k * error - d * (angular_velocity - target_angular_velocity);
    } else {
        acceleration =
            (implicit_velocity(error, angular_velocity, target_angular_velocity, k, d, h) -
             angular_velocity) /
            h;
    }
    return clamp_norm(inertia_world * acceleration, drive.force_limit, kTorqueLever);
}

}  // namespace physhand
