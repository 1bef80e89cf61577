#include "box_face_collision.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <btBulletCollisionCommon.h>

#include <array>
#include <limits>
#include <utility>

#include "one_manifold_algorithm.h"

namespace physhand {

namespace {

// Directions tilted off the face's normal, spread about it, each giving a lowest point.
constexpr int kTilts = 4;
// How far from the straight-down lowest point a tilted one may lie on a round side (m): a rod
// lying on the face rests on a strip this wide, as good as a line, while a flat side still
// gives its outermost corners.
constexpr btScalar kTiltReach = 0.0005f;
constexpr btScalar kMostTilt = 0.05f;  // rad
// A lowest point this far outside the face's edges still rests on it (m, float rounding).
constexpr btScalar kEdgeSlack = 1e-5f;
// Deeper in the face than this, the pair is left to GJK (m): the face's points would
// stand for what lies below them only near its plane.
constexpr btScalar kFaceDepth = 0.01f;

// A face's plane, facing the convex, and how far the convex lies above it.
struct Plane {
    btVector3 normal;  // toward the convex, world frame
    btScalar offset;   // normal . x = offset on the plane
    btScalar separation = -std::numeric_limits<btScalar>::max();
};

btVector3 lowest_point(const btConvexShape& convex, const btTransform& pose,
                       const btVector3& down) {
    return pose * convex.localGetSupportingVertex(pose.getBasis().transpose() * down);
}

btScalar separation(const btConvexShape& convex, const btTransform& pose, const btVector3& normal,
                    btScalar offset) {
    return normal.dot(lowest_point(convex, pose, -normal)) - offset;
}

// The convex's lowest points toward a plane for directions tilted a little off its normal,
// diagonally to the convex's own axes: along an axis, a flat side's corners tie, and a brick
// square on the face gave three of its four.
std::array<btVector3, kTilts> lowest_points(const btConvexShape& convex, const btTransform& pose,
                                            const btVector3& normal) {
    const btMatrix3x3& axes = pose.getBasis();
    btVector3 side = axes.getColumn(0) - normal * normal.dot(axes.getColumn(0));
    if (side.length2() < btScalar(0.25))
        side = axes.getColumn(2) - normal * normal.dot(axes.getColumn(2));
    side.normalize();
    const btVector3 other_side = normal.cross(side);
    const btScalar tilt = btMin(kMostTilt, kTiltReach / convex.getAngularMotionDisc());
    std::array<btVector3, kTilts> points;
    for (int k = 0; k < kTilts; ++k) {
        const btScalar about = SIMD_2_PI * (static_cast<btScalar>(k) + btScalar(0.5)) / kTilts;
        const btVector3 down =
            -normal * btCos(tilt) + (side * btCos(about) + other_side * btSin(about)) * btSin(tilt);
        points[k] = lowest_point(convex, pose, down);
    }
    return points;
}

// The box's face the convex lies farthest above or least deep under (a separating axis if
// any of the box's faces is one), and the box's axis it is normal to.
std::pair<Plane, int> facing_face(const btConvexShape& convex, const btTransform& convex_pose,
                                  const btTransform& box_pose, const btVector3& half) {
    std::pair<Plane, int> best;
    for (int axis = 0; axis < 3; ++axis) {
        for (const btScalar sign : {btScalar(1), btScalar(-1)}) {
            const btVector3 normal = box_pose.getBasis().getColumn(axis) * sign;
            const btScalar offset = normal.dot(box_pose.getOrigin()) + half[axis];
            const btScalar s = separation(convex, convex_pose, normal, offset);
            if (s > best.first.separation) best = {{normal, offset, s}, axis};
        }
    }
    return best;
}

// GJK's penetration solver: it keeps no state between pairs.
btGjkEpaPenetrationDepthSolver g_penetration;

// A cylinder or a convex hull against a box, either first.
class BoxFaceAlgorithm : public OneManifoldAlgorithm {
  public:
    // The manifold is kept in the wrappers' order, so that points are added unswapped.
    BoxFaceAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                     const btCollisionObjectWrapper* first, const btCollisionObjectWrapper* second,
                     bool face_first)
        : OneManifoldAlgorithm(info, first, second, first->getCollisionObject(),
                               second->getCollisionObject()),
          face_first_(face_first) {
        if (!manifold_) return;
        void* memory = m_dispatcher->allocateCollisionAlgorithm(sizeof(btConvexConvexAlgorithm));
        gjk_ = new (memory) btConvexConvexAlgorithm(manifold_, info, first, second, &g_penetration,
                                                    kPerturbationTurns, kFewestPoints);
    }
    ~BoxFaceAlgorithm() override {
        if (!gjk_) return;
        gjk_->~btCollisionAlgorithm();
        m_dispatcher->freeCollisionAlgorithm(gjk_);
    }

    void processCollision(const btCollisionObjectWrapper* first,
                          const btCollisionObjectWrapper* second, const btDispatcherInfo& info,
                          btManifoldResult* result) override {
        if (!manifold_) return;
        result->setPersistentManifold(manifold_);
        const btCollisionObjectWrapper& convex = face_first_ ? *second : *first;
        const btCollisionObjectWrapper& box = face_first_ ? *first : *second;
        // The two share the manifold, so a pair passing between them keeps its points.
        if (!rest_on_box(convex, box, *result)) gjk_->processCollision(first, second, info, result);
        if (manifold_->getNumContacts() > 0) result->refreshContactPoints();
    }

    struct CreateFunc : btCollisionAlgorithmCreateFunc {
        explicit CreateFunc(bool face_first) { m_swapped = face_first; }
        btCollisionAlgorithm* CreateCollisionAlgorithm(
            btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* first,
            const btCollisionObjectWrapper* second) override {
            void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(BoxFaceAlgorithm));
            return new (memory) BoxFaceAlgorithm(info, first, second, m_swapped);
        }
    };

  private:
    // Adds the convex's lowest points that lie on the box's face it lies on; whether that is
    // all GJK need not look for: the convex is apart from the face's plane, or all of them lie
    // on the face. Where some lie beyond it (over the box's edge), GJK adds what they miss.
    bool rest_on_box(const btCollisionObjectWrapper& convex_wrap,
                     const btCollisionObjectWrapper& box_wrap, btManifoldResult& result) const {
        const auto& convex = static_cast<const btConvexShape&>(*convex_wrap.getCollisionShape());
        const btTransform& convex_pose = convex_wrap.getWorldTransform();
        const btTransform& box_pose = box_wrap.getWorldTransform();
        const btVector3 half = static_cast<const btBoxShape&>(*box_wrap.getCollisionShape())
                                   .getHalfExtentsWithMargin();
        const auto [plane, axis] = facing_face(convex, convex_pose, box_pose, half);
        if (plane.separation > manifold_->getContactBreakingThreshold()) return true;
        if (plane.separation < -kFaceDepth) return false;
        bool all_on_face = true;
        for (const btVector3& point : lowest_points(convex, convex_pose, plane.normal)) {
            const btVector3 local = box_pose.invXform(point);
            bool on_face = true;
            for (int other = 0; other < 3; ++other) {
                if (other != axis && btFabs(local[other]) > half[other] + kEdgeSlack)
                    on_face = false;
            }
            if (!on_face) {
                all_on_face = false;
                continue;
            }
            const btScalar distance = plane.normal.dot(point) - plane.offset;
            // Normal and point are the second body's: the face's, or the convex's.
            if (face_first_) {
                result.addContactPoint(-plane.normal, point, distance);
            } else {
                result.addContactPoint(plane.normal, point - plane.normal * distance, distance);
            }
        }
        return all_on_face;
    }

    btCollisionAlgorithm* gjk_ = nullptr;
    bool face_first_;
};

}  // namespace

void register_box_face_collision(btCollisionDispatcher& dispatcher) {
    static BoxFaceAlgorithm::CreateFunc convex_first(false);
    static BoxFaceAlgorithm::CreateFunc box_first(true);
    for (const int convex : {CYLINDER_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE}) {
        dispatcher.registerCollisionCreateFunc(convex, BOX_SHAPE_PROXYTYPE, &convex_first);
        dispatcher.registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, convex, &box_first);
    }
}

}  // namespace physhand
