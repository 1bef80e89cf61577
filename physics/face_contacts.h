#pragma once

class btCollisionDispatcher;

namespace physhand {

// Has `dispatcher` find, for a cylinder or a convex hull against a box, a cylinder or a hull,
// and for a box, a cylinder or a hull on a plane, the points of the whole face or line they
// touch along at once: Bullet finds one point a step, so such an object resting on a face or
// a line stood on that point alone until it had tipped far enough to find more (a lying rod
// rolled off a table, a 1 cm box wandered 12 cm over the floor, 60 s, nothing touching them).
// The pair is turned a little about a few axes (Bullet's multipoint perturbation). Spheres
// and capsules keep Bullet's single point: turned, a ball finds the same one again, and the
// sphere drives' grips changed with the extra points (squeeze sweep, measured). A cylinder or
// hull lying on a box's face gets its points as on a plane (box_face_collision.h).
void register_face_contacts(btCollisionDispatcher& dispatcher);

}  // namespace physhand
