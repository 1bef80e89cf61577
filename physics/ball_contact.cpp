#include "ball_contact.h"

#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>

#include "triangle_contact.h"

namespace physhand {

namespace {

BallContact plane_contact(const btVector3& centre, btScalar radius,
                          const btCollisionObject& plane) {
    const auto& shape = static_cast<const btStaticPlaneShape&>(*plane.getCollisionShape());
    const btTransform& t = plane.getWorldTransform();
    const btVector3 normal = t.getBasis() * shape.getPlaneNormal();
    const btScalar height =
        normal.dot(centre) - normal.dot(t.getOrigin()) - shape.getPlaneConstant();
    return {normal, centre - normal * height, height - radius};
}

std::optional<BallContact> convex_contact(const btVector3& centre, btScalar radius,
                                          const btCollisionObject& other, btScalar reach) {
    btSphereShape sphere(radius);
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver penetration;
    const auto* convex = static_cast<const btConvexShape*>(other.getCollisionShape());
    btGjkPairDetector gjk(convex, &sphere, &simplex, &penetration);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = other.getWorldTransform();
    input.m_transformB = btTransform(btMatrix3x3::getIdentity(), centre);
    const btScalar far = radius + convex->getMargin() + reach;
    input.m_maximumDistanceSquared = far * far;
    btPointCollector found;
    gjk.getClosestPoints(input, found, nullptr);
    if (!found.m_hasResult) return std::nullopt;
    // The collector's B is the sphere: turn the contact around to the collider's side.
    const btVector3 on_collider =
        found.m_pointInWorld + found.m_normalOnBInWorld * found.m_distance;
    return BallContact{-found.m_normalOnBInWorld, on_collider, found.m_distance};
}

}  // namespace

std::pair<btVector3, btVector3> capsule_ends(const btCapsuleShape& capsule,
                                             const btTransform& pose) {
    btVector3 axis(0, 0, 0);
    axis[capsule.getUpAxis()] = capsule.getHalfHeight();
    return {pose * axis, pose * -axis};
}

BallContact ball_box_contact(const btVector3& centre, btScalar radius, const btTransform& box,
                             const btVector3& half) {
    const btVector3 local = box.invXform(centre);
    btVector3 nearest = local;
    nearest.setMax(-half);
    nearest.setMin(half);
    const btVector3 out = local - nearest;
    const btScalar outside = out.length();
    if (outside > SIMD_EPSILON) {
        return {box.getBasis() * (out / outside), box * nearest, outside - radius};
    }
    // Inside: out through the nearest face.
    int axis = 0;
    for (int i = 1; i < 3; ++i) {
        if (half[i] - btFabs(local[i]) < half[axis] - btFabs(local[axis])) axis = i;
    }
    btVector3 normal(0, 0, 0);
    normal[axis] = local[axis] < 0 ? -1 : 1;
    nearest[axis] = normal[axis] * half[axis];
    return {box.getBasis() * normal, box * nearest, -(half[axis] - btFabs(local[axis])) - radius};
}

std::optional<BallContact> ball_contact(const btVector3& centre, btScalar radius,
                                        const btCollisionObject& collider, btScalar reach,
                                        const btVector3& outside) {
    const btCollisionShape& shape = *collider.getCollisionShape();
    switch (shape.getShapeType()) {
        case STATIC_PLANE_PROXYTYPE:
            return plane_contact(centre, radius, collider);
        case BOX_SHAPE_PROXYTYPE:
            return ball_box_contact(
                centre, radius, collider.getWorldTransform(),
                static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin());
        case TRIANGLE_MESH_SHAPE_PROXYTYPE:
            return mesh_ball_contact(centre, radius, static_cast<const btConcaveShape&>(shape),
                                     collider.getWorldTransform(), reach, outside);
        default:
            return convex_contact(centre, radius, collider, reach);
    }
}

}  // namespace physhand
