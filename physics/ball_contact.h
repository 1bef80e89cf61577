#pragma once

#include <LinearMath/btTransform.h>

#include <optional>

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

// A ball against a box of half extents `half` posed by `box` (sharp edges, as the scene
// describes it), exactly.
BallContact ball_box_contact(const btVector3& centre, btScalar radius, const btTransform& box,
                             const btVector3& half);

// A ball against a static plane, a box or any other convex collider (by GJK); none when a
// convex collider is further than `reach`.
std::optional<BallContact> ball_contact(const btVector3& centre, btScalar radius,
                                        const btCollisionObject& collider, btScalar reach);

}  // namespace physhand
