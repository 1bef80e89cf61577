#pragma once

#include <LinearMath/btTransform.h>

#include <optional>
#include <utility>

class btCapsuleShape;
class btCollisionObject;

namespace physhand {

// A contact as Bullet states one: the point on the collider, the normal from the collider
// toward the ball, and the distance between the surfaces (negative: penetrating).
struct BallContact {
    btVector3 normal;
    btVector3 on_collider;
    btScalar distance;
};

// One contact is deeper than another beyond float rounding by more than this (m).
inline constexpr btScalar kDeeper = 1e-5f;

// The centres of a capsule's end balls, posed by `pose`: the capsule is the balls of its
// radius along the segment between them.
std::pair<btVector3, btVector3> capsule_ends(const btCapsuleShape& capsule,
                                             const btTransform& pose);

// A ball against a box of half extents `half` posed by `box` (sharp edges, as the scene
// describes it), exactly.
BallContact ball_box_contact(const btVector3& centre, btScalar radius, const btTransform& box,
                             const btVector3& half);

// A ball against a static plane, a box, a static mesh (its nearest triangle, seen from
// `outside`: triangle_contact.h) or any other convex collider (by GJK); none when a convex
// collider or every triangle is further than `reach`.
std::optional<BallContact> ball_contact(const btVector3& centre, btScalar radius,
                                        const btCollisionObject& collider, btScalar reach,
                                        const btVector3& outside);

}  // namespace physhand
