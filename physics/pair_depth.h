#pragma once

#include <LinearMath/btVector3.h>

class btCollisionObject;
class btCollisionWorld;

namespace physhand {

// How deep `a` lies in `b`, and the way out for `a` at the deepest point.
struct PairDepth {
    double depth = 0.0;  // m; 0 when they do not overlap
    btVector3 out{0, 0, 0};
    // The deepest point's ends, on `a` and on `b`.
    btVector3 on_a{0, 0, 0};
    btVector3 on_b{0, 0, 0};
};

// Found afresh by the world's contact algorithms, those the solver's contacts come from (a
// capsule in a box measured along the capsule, as capsule_collision does), with no
// manifold's kept points in the way.
PairDepth pair_depth(btCollisionWorld& world, const btCollisionObject& a,
                     const btCollisionObject& b);

}  // namespace physhand
