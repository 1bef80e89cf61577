#include "face_contacts.h"

#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <btBulletCollisionCommon.h>

#include <array>

#include "box_face_collision.h"

namespace physhand {

namespace {

constexpr std::array<int, 3> kFlatSided = {BOX_SHAPE_PROXYTYPE, CYLINDER_SHAPE_PROXYTYPE,
                                           CONVEX_HULL_SHAPE_PROXYTYPE};

}  // namespace

void register_face_contacts(btCollisionDispatcher& dispatcher) {
    static btGjkEpaPenetrationDepthSolver penetration;
    static btConvexConvexAlgorithm::CreateFunc convex = [] {
        btConvexConvexAlgorithm::CreateFunc f(&penetration);
        f.m_numPerturbationIterations = kPerturbationTurns;
        f.m_minimumPointsPerturbationThreshold = kFewestPoints;
        return f;
    }();
    static btConvexPlaneCollisionAlgorithm::CreateFunc on_plane = [] {
        btConvexPlaneCollisionAlgorithm::CreateFunc f;
        f.m_numPerturbationIterations = kPerturbationTurns;
        f.m_minimumPointsPerturbationThreshold = kFewestPoints;
        return f;
    }();
    static btConvexPlaneCollisionAlgorithm::CreateFunc plane_first = [] {
        btConvexPlaneCollisionAlgorithm::CreateFunc f = on_plane;
        f.m_swapped = true;
        return f;
    }();
    for (const int a : kFlatSided) {
        for (const int b : kFlatSided) {
            // Two boxes keep Bullet's box-box test, which finds a face's points itself.
            if (a == BOX_SHAPE_PROXYTYPE && b == BOX_SHAPE_PROXYTYPE) continue;
            dispatcher.registerCollisionCreateFunc(a, b, &convex);
        }
        dispatcher.registerCollisionCreateFunc(a, STATIC_PLANE_PROXYTYPE, &on_plane);
        dispatcher.registerCollisionCreateFunc(STATIC_PLANE_PROXYTYPE, a, &plane_first);
    }
    register_box_face_collision(dispatcher);
}

}  // namespace physhand
