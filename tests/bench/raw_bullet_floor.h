#pragma once

#include "scene.h"

namespace physhand::bench {

// The floor of the present design under a scene: the same colliders in a plain Bullet world
// with Bullet's defaults (one step per 90 Hz frame, its own contacts, solver and sleeping),
// each hand a kinematic palm box and a capsule per finger bone set to its ghost every frame.
// Whatever a physhand step costs above this is the project's own (drives, its contacts,
// substeps, gating, speed limits, bookkeeping). The median step in µs over the scene.
double raw_bullet_step_us(const Scene& scene);

}  // namespace physhand::bench
