#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene.h"

namespace physhand {

// A scene changed in one way a real user or headset changes it: what the robustness
// benchmark plays instead of the scenes the hand was tuned on.
struct SceneVariant {
    std::string family;  // mass, friction, speed, tracking, noise, dropout, mirror
    std::string name;    // the family's parameter, e.g. "x0.3", "30hz_2mm_seed2"
    Scene scene;
};

// How many seeds the families with random input (noise, dropouts) are played with.
struct VariantOptions {
    int seeds = 3;
};

// Every variant of `base`, family by family (docs/metrics.md variant_success):
// - mass: every dynamic collider x0.3 and x3, the motion unchanged;
// - friction: every dynamic collider's friction 0.5;
// - speed: the whole script (hands, kinematic paths, dropouts, timed predicates) 0.7x and
//   1.3x as fast; the scene lasts at least as long as before, so what the hand set moving
//   has the time it had to settle;
// - tracking: 30 and 60 Hz with 2 mm of noise;
// - noise: 3 mm of noise at the scene's rate;
// - dropout: one 300 ms dropout of each tracked hand at a seeded time within its motion;
// - mirror: the scene reflected through the YZ plane, the right hand's motion played by
//   the left (x -> -x for every position, collider and region).
std::vector<SceneVariant> scene_variants(const Scene& base, const VariantOptions& options);

// The scene reflected through the YZ plane, hands swapped.
Scene mirrored(const Scene& scene);
// The scene's script played `speed` times as fast.
Scene sped_up(const Scene& scene, double speed);
// The final grip made tighter: the four fingers' curl raised to at least `curl` from the
// keyframe where each hand's curls reach their final values (docs/metrics.md
// squeeze_penetration_mm: the ghost's fingers close further into what the hand holds).
Scene squeezed(const Scene& scene, double curl);

}  // namespace physhand
