#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ghost_filter.h"
#include "pose.h"

namespace physhand {

// How the physical hand is built: a sphere per joint (as in the paper), or a palm box
// plus a capsule per bone (no gaps between joints, orientation carries friction), each bone
// joined to the body before it within a human joint's range (bone_joints).
enum class BodyModel { JointSpheres, BoneCapsules };

// The law that turns a ghost target into a force each substep.
enum class DriveLaw {
    Explicit,  // the paper's Algorithm 1: F = -k(p - p_g) - d(v - v_g), integrated explicitly
    Implicit,  // stable PD (Tan, Liu, Turk 2011): the spring acts on the end-of-substep state
};

struct DriveSettings {
    std::string name;
    BodyModel body_model = BodyModel::BoneCapsules;
    DriveLaw law = DriveLaw::Implicit;
    double stiffness = 1000.0;  // N/m, per body
    double damping = 20.0;      // N·s/m, per body
    // Orientation is driven with the same natural frequency and damping ratio as position
    // (gains scaled by inertia/mass), only for bodies whose orientation matters.
    bool drive_orientation = false;
    // N per body (torque: scaled likewise); 0: none of its own. kMaxDriveForce caps it.
    double force_limit = 0.0;
    int substeps = 4;          // per 90 Hz frame
    GhostSmoothing smoothing;  // of the ghost before the drive follows it
    // How many moves a hand part is given each substep to leave what it went into
    // (hand_depenetration.h).
    int depenetration_moves = 1;

    bool joined_bones() const { return body_model == BodyModel::BoneCapsules; }
};

// No drive force exceeds this, whatever the limit: past it, an explicit drive's overshoot
// on a body of a few grams overflows Bullet's float state into NaN (found by fuzzing the
// extension, tests/fuzz). A real hand pushes with a hundredth of it.
inline constexpr double kMaxDriveForce = 1e4;  // N

// The most substeps per 90 Hz frame a drive is given (the extension's and the config's limit).
inline constexpr int kMaxSubsteps = 64;

// The drives the project ships; the first is the default.
const std::vector<DriveSettings>& builtin_drives();
const DriveSettings& default_drive();
// A builtin drive by name. "jointed", the joined bones' name while `bones` was not joined yet,
// finds `bones`: configs and the extension's XR_HAND_DRIVE_KIND_JOINTED_PHYSHAND still use it.
std::optional<DriveSettings> find_drive(std::string_view name);

// Force for one body over one substep of length h. Targets are the ghost at the end of
// the substep; ghost velocity is its finite difference over the frame.
struct LinearState {
    Vec3 position;
    Vec3 velocity;
};
Vec3 drive_force(const DriveSettings& drive, double mass, const LinearState& body,
                 const LinearState& target, double h);

// Torque for one body: `inertia_world` is the body's world inertia tensor. A body `resting` on
// what it cannot move (a static or kinematic collider, and nothing it could move) turns
// kRestingOrientationStiffness times as stiffly, damping scaled by its square root (the
// damping ratio kept): with the full gains at one substep per frame, a palm and the finger
// bones pressed on a table rocked between their end contacts every other frame, 1 mm RMS
// with the ghost still (press_table; 0.035 mm softened). Parts that hold or push something
// movable keep the full gains: softened there too, grips under 2 mm tracking noise held less
// often (robustness benchmark, 8 seeds: tracking family 74 % -> 64 %).
inline constexpr double kRestingOrientationStiffness = 0.1;
// How far into the static colliders it rests on (and nothing else) a body's drive aims at
// most, m: a ghost pressed deeper into a table only pressed the body harder onto it, which
// moves nothing there. Pressed 5 cm into one (press_table), a thumb bone tipped on its end
// and walked up to 4.5 cm across it, off its hand, and the returned joints shook 0.035 mm RMS
// (0.19 mm on a table of triangles); with this, 1.6 mm and 0.005 mm (0.016 mm). Bodies that
// touch anything movable, or kinematic (perhaps an app's own object, gripped), are aimed as
// kLonePressGive says; the paper's Algorithm 1 keeps the full reach. The robustness benchmark
// does not tell them apart (bones/1, 200 variants under four solver perturbations: 590
// succeeded before, 594 with).
inline constexpr double kRestingPressDepth = 0.002;
// How much of its ghost's reach into a movable object a hand part gives up while it presses
// that object alone (no other hand part opposite, the object not resting on it) or comes
// within this of it, m, as a fingertip's pad gives: a finger whose ghost dips a few mm into
// what it brushes past (tracking noise, a hand drawn back over what it has just put down) no
// longer drags it along. A part that grips (another part opposite) or carries (the object's
// weight on it) keeps the full reach, so grips are as firm as before. The displacement task's
// cube was pulled back out of its hole by a fingertip dipping into its top under 2-3 mm of
// noise. Robustness, bones/1, 200 variants each shifted by 0 to 2.6 mm (8 shifts): 1216 ->
// 1268 of 1600 (displacement 149 -> 162 of 320, sphere 288 -> 312); giving only while
// touching, 1259, but a finger drawn across a cube pressed in again each time it came clear
// and dragged it 16 mm; 2 mm gave 631 of 800 against 612, 4 mm 618. A part that held the
// object and no longer does (its opposite has let go) gives up all its reach until it comes
// clear of it (Simulation's kOpposedShare). Giving up all its reach while its ghost leaves the
// object (outward along the normal at over 2 cm/s against the object) kept the displacement
// task's cube, twice as heavy, in its hole as the hand withdrew (the thumb alone lay on it, its
// ghost 12 mm in where the cube had turned onto it), but the sphere flicked under 30 Hz tracking
// (seed 8) missed at every shift (robustness, bones/1, 3200 plays: 3062 -> 3039); measured
// against the ghost's own speed, a fingertip pressed 1 cm into a cube dragged it 18 mm, not 30.
inline constexpr double kLonePressGive = 0.003;
Vec3 drive_torque(const DriveSettings& drive, double mass, const Eigen::Matrix3d& inertia_world,
                  const Quat& orientation, const Vec3& angular_velocity, const Quat& target,
                  const Vec3& target_angular_velocity, double h, bool resting = false);

}  // namespace physhand
