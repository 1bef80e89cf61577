#pragma once

class btCollisionDispatcher;

namespace physhand {

// Bullet finds one closest point between two convex shapes, so a finger capsule that lands
// along a surface is held only where it touched first, and its other end enters the surface
// during the substep (2.5 mm at one substep per frame in press_table, measured). This gives
// each end of every hand capsule a contact of its own with each convex or plane collider
// within the hand's contact reach, after collision detection and before the solver.
void add_capsule_end_contacts(btCollisionDispatcher& dispatcher);

}  // namespace physhand
