#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene.h"

namespace physhand {

// A scene changed in one way a real user or headset changes it: what the robustness
// benchmark plays instead of the scenes the hand was tuned on.
struct SceneVariant {
    std::string family;  // mass, friction, speed, size, tracking, noise, dropout, mirror
    std::string name;    // the family's parameter, e.g. "x0.3", "30hz_2mm_seed2"
    Scene scene;
    // How the motion was changed to suit the variant, as a person would change it; empty: the
    // scene's own motion.
    std::string adapted;
};

// How many seeds the families with random input (noise, dropouts) are played with.
struct VariantOptions {
    int seeds = 3;
};

// Every variant of `base`, family by family (docs/metrics.md variant_success):
// - mass: every dynamic collider x0.3 and x3, the motion unchanged;
// - friction: every dynamic collider's friction 0.5;
// - speed: the whole script (hands, kinematic paths, dropouts, timed predicates) 0.7x and
//   1.3x as fast, throws and flicks at their own pace (sped_up_aiming); the scene lasts at
//   least as long as before, so what the hand set moving has the time it had to settle;
// - size: the objects the hands handle x0.75 and x1.25, the hands adapted (resized);
// - tracking: 30 and 60 Hz with 2 mm of noise;
// - noise: 3 mm of noise at the scene's rate;
// - dropout: one 300 ms dropout of each tracked hand at a seeded time within its motion;
// - mirror: the scene reflected through the YZ plane, the right hand's motion played by
//   the left (x -> -x for every position, collider and region).
std::vector<SceneVariant> scene_variants(const Scene& base, const VariantOptions& options);

// The scene reflected through the YZ plane, hands swapped.
Scene mirrored(const Scene& scene);
// The scene moved by `offset`, everything in it and its regions with it. The same motion
// elsewhere: a contact-rich run's outcome can turn on the last bit of a float (the
// robustness benchmark plays each variant at several sub-millimetre offsets).
Scene shifted(const Scene& scene, const Vec3& offset);
// The scene turned by `degrees` about the vertical through the origin, everything in it and
// its regions with it: the same task done facing another way, which a runtime's reference
// space may put anywhere. A scene with an `inside` region (a box along the axes) turns only
// by multiples of 90 degrees; any other turn throws std::invalid_argument.
Scene turned(const Scene& scene, double degrees);
// Every dynamic collider `factor` times as heavy, the motion unchanged: a person cannot see
// what a thing weighs and reaches for it as for the scene's own.
Scene heavier(const Scene& scene, double factor);
// The scene's script played `speed` times as fast.
Scene sped_up(const Scene& scene, double speed);
// The same, except a throw or a flick (a keyframe leg in which a wrist moves faster than
// kStrokeSpeed): it keeps its own pace, as a person aiming at a target throws as hard as the
// target needs, however fast the rest. `adapted` says which legs kept their pace, or is
// cleared when none did.
inline constexpr double kStrokeSpeed = 0.5;  // m/s, docs/metrics.md's throw
Scene sped_up_aiming(const Scene& scene, double speed, std::string& adapted);
// Every dynamic box, sphere, capsule and cylinder that a hand handles (a ghost joint comes
// within kHandledDistance of it where it lies at the start) `scale` times as large, as dense,
// resting where it rested (its lowest point kept). The hands adapt as a person would. Where a
// hand works (the keyframe whose fingertips reach deepest into a handled object, or else the
// one coming closest to one) gives the point it works at: that object's centre, in the
// wrist's frame. Each keyframe raises the hand by (scale - 1) times that point's height above
// what the handled objects rest on, up to their heights stacked: at the grip, as much as the
// object's centre rose; placing on a stack of them, as much as the stack grew. In the grip
// each finger's curl changes so that its tip reaches as deep into the object as before, the
// change kept wherever the finger is curled. `adapted` says what changed.
inline constexpr double kHandledDistance = 0.02;  // m
Scene resized(const Scene& scene, double scale, std::string& adapted);
// Every dynamic object a hand handles (as `resized` finds them) moved by `offset`, the motion
// unchanged: the hand closes where it always does, so its grasp lands `offset` off the place the
// script reaches for, as a person's grasp lands a few millimetres beside a centre they aimed at.
Scene grasped_off_centre(const Scene& scene, const Vec3& offset);
// The final grip made tighter: the four fingers' curl raised to at least `curl` from the
// keyframe where each hand's curls reach their final values (docs/metrics.md
// squeeze_penetration_mm: the ghost's fingers close further into what the hand holds).
Scene squeezed(const Scene& scene, double curl);

}  // namespace physhand
