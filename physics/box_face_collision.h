#pragma once

class btCollisionDispatcher;

namespace physhand {

// Has `dispatcher` find, for a cylinder or a convex hull lying on a face of a box, the points
// it rests on as on a plane: its lowest points for a few directions tilted slightly off the
// face's normal, each measured straight to the face. Bullet's GJK finds one point a step,
// measured on a turned copy where it perturbs for more, and those points' depths did not
// agree: a 50 cm rod lying on a box rolled ever faster with nothing touching it, and off the
// box (1 and 2 substeps; on a plane, whose points are found this way, it lay still). Where
// some lowest points fall outside the face (an object over the box's edge, or larger than the
// face), Bullet's GJK, with the multipoint perturbation below, adds what lies beyond.
void register_box_face_collision(btCollisionDispatcher& dispatcher);

// Bullet's multipoint perturbation for flat-sided pairs: turns per manifold, tried while it
// holds fewer points than kFewestPoints (Bullet's suggestion).
inline constexpr int kPerturbationTurns = 3;
inline constexpr int kFewestPoints = 3;

}  // namespace physhand
