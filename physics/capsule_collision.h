#pragma once

class btCollisionDispatcher;

namespace physhand {

// Has `dispatcher` find the closest point between a capsule and a box or a static mesh
// exactly, in place of Bullet's GJK: the deepest or nearest point of the capsule's segment, by
// golden-section search on its distance to the box (signed) or to each triangle within reach,
// both convex along the segment. Against a box GJK took a quarter of a hand's step in
// press_table and lift_hold (callgrind). Against a mesh Bullet finds a point per triangle and
// keeps, of points within its reach of each other, whichever came last, at the normal GJK gave
// for that triangle: a hand pressed on a table of triangles sank 11-12 mm into it as shown
// while its one kept point read a thumb bone touching along a normal tilted 37 degrees, or
// 5.8 mm clear (triangle_contact.h).
void register_capsule_collision(btCollisionDispatcher& dispatcher);

}  // namespace physhand
