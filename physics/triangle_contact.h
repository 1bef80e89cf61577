#pragma once

#include <LinearMath/btVector3.h>

#include <optional>

#include "ball_contact.h"

class btConcaveShape;
class btTransform;

namespace physhand {

// A static mesh's triangles have no inside: each is met as a thin solid, its nearest point to
// what meets it giving the normal, but for a point over the face itself, which is as deep as
// it lies behind the face seen from `outside` (the centre of the body that meets it: a part
// whose end dips through a thin triangle is pushed back out on the side its middle lies on,
// not on through). Only the triangles within `reach` of the shape count; none there, none
// found.

// A ball against the mesh: the nearest triangle's contact.
std::optional<BallContact> mesh_ball_contact(const btVector3& centre, btScalar radius,
                                             const btConcaveShape& mesh, const btTransform& pose,
                                             btScalar reach, const btVector3& outside);

// A capsule (the balls of `radius` along the segment from `a` to `b`) against the mesh: the
// point of the segment nearest any triangle, by golden-section search along the segment (the
// distance to a triangle is convex along it).
std::optional<BallContact> mesh_capsule_contact(const btVector3& a, const btVector3& b,
                                                btScalar radius, const btConcaveShape& mesh,
                                                const btTransform& pose, btScalar reach,
                                                const btVector3& outside);

}  // namespace physhand
