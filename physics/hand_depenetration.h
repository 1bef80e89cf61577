#pragma once

class btCollisionWorld;

namespace physhand {

// How deep a hand part may stay in a collider after a substep (m).
inline constexpr double kHandDepthAllowed = 0.001;

// Run after a substep has moved the bodies. Ten solver iterations leave a grip unconverged:
// held still, a thumb squeezed into a cube stayed 5 mm in, still closing after every solve
// (lift_hold, curl 0.6; 0.7 mm at 20 iterations, which cost grips: robustness 709 of 800
// plays against 764). Each hand part deeper than kHandDepthAllowed in a movable collider is
// moved out to that depth along the way out of its deepest point, the part alone: the
// collider keeps its place and has only the solver's impulses, so the grip presses as it
// did and launches nothing. A part so moved into a fixed collider is moved out of that too.
// One move along the deepest point's way out can leave a part deeper than allowed where an
// edge turned under it in the substep; up to `moves` moves are made.
// The part's points with movable colliders that claim more depth than the pair has (kept
// friction anchors, measured along their old normals) are then put at its deepest point.
void depenetrate_hands(btCollisionWorld& world, int moves = 1);

}  // namespace physhand
