#pragma once

class btCollisionDispatcher;

namespace physhand {

// Bullet finds one closest point between two convex shapes, and none at all between two
// boxes until they overlap, so a hand part that lands along a surface is held only where it
// touched first and the rest of it enters the surface during the substep (a finger 2.5 mm,
// a palm box 0.025 mm at one substep per frame in press_table, measured). This gives each
// end of every finger capsule, and each of the four corners of the palm box nearest a
// collider, a contact of its own with each convex, plane or mesh collider within the hand's
// contact reach, after collision detection and before the solver. A joint sphere's contact
// is found again too, so that a friction anchor does not hide how deep it lies
// (contact_insertion.h).
void add_hand_point_contacts(btCollisionDispatcher& dispatcher);

}  // namespace physhand
