#pragma once

class btCollisionDispatcher;
class btConvexPenetrationDepthSolver;

namespace physhand {

// Has `dispatcher` find, for a cylinder or a convex hull lying on a face of a box, the points
// it rests on as on a plane: its lowest points for a few directions tilted slightly off the
// face's normal, each measured straight to the face. Bullet's GJK finds one point a step,
// measured on a turned copy where it perturbs for more, and those points' depths did not
// agree: a 50 cm rod lying on a box rolled ever faster with nothing touching it, and off
// the box (1 and 2 substeps; on a plane, whose points are found this way, it lay still).
// Where a point falls outside the face (an object over the box's edge, or larger than the
// face) the pair keeps Bullet's GJK, perturbed `turns` times while the manifold holds fewer
// than `fewest` points.
void register_box_face_collision(btCollisionDispatcher& dispatcher,
                                 btConvexPenetrationDepthSolver& penetration, int turns,
                                 int fewest);

}  // namespace physhand
