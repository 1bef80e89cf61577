#include "box_face_collision.h"

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <btBulletCollisionCommon.h>

#include <array>
#include <limits>

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

struct Face {
    btVector3 normal;  // out of the box, world frame
    btScalar offset;   // the face's plane: normal . x = offset
    int axis;          // the box's axis it is normal to
    btScalar separation = -std::numeric_limits<btScalar>::max();  // of the convex from it
};

btVector3 lowest_point(const btConvexShape& convex, const btTransform& pose,
                       const btVector3& down) {
    return pose * convex.localGetSupportingVertex(pose.getBasis().transpose() * down);
}

// The box's face the convex lies farthest above or least deep under: a separating axis if
// any of the box's faces is one.
Face facing_face(const btConvexShape& convex, const btTransform& convex_pose,
                 const btTransform& box_pose, const btVector3& half) {
    Face best;
    for (int axis = 0; axis < 3; ++axis) {
        for (const btScalar sign : {btScalar(1), btScalar(-1)}) {
            const btVector3 normal = box_pose.getBasis().getColumn(axis) * sign;
            const btScalar offset = normal.dot(box_pose.getOrigin()) + half[axis];
            const btScalar separation =
                normal.dot(lowest_point(convex, convex_pose, -normal)) - offset;
            if (separation > best.separation) best = {normal, offset, axis, separation};
        }
    }
    return best;
}

struct Settings {
    btConvexPenetrationDepthSolver* penetration;
    int turns;
    int fewest;
};

class BoxFaceAlgorithm : public btActivatingCollisionAlgorithm {
  public:
    BoxFaceAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                     const btCollisionObjectWrapper* first, const btCollisionObjectWrapper* second,
                     bool box_first, const Settings& settings)
        : btActivatingCollisionAlgorithm(info, first, second), box_first_(box_first) {
        const btCollisionObject* a = first->getCollisionObject();
        const btCollisionObject* b = second->getCollisionObject();
        if (!m_dispatcher->needsCollision(a, b)) return;
        // Kept in the wrappers' order, so that points are added unswapped.
        manifold_ = m_dispatcher->getNewManifold(a, b);
        void* memory = m_dispatcher->allocateCollisionAlgorithm(sizeof(btConvexConvexAlgorithm));
        gjk_ = new (memory) btConvexConvexAlgorithm(
            manifold_, info, first, second, settings.penetration, settings.turns, settings.fewest);
    }
    ~BoxFaceAlgorithm() override {
        if (gjk_) {
            gjk_->~btCollisionAlgorithm();
            m_dispatcher->freeCollisionAlgorithm(gjk_);
        }
        if (manifold_) m_dispatcher->releaseManifold(manifold_);
    }

    void processCollision(const btCollisionObjectWrapper* first,
                          const btCollisionObjectWrapper* second, const btDispatcherInfo& info,
                          btManifoldResult* result) override {
        if (!manifold_) return;
        result->setPersistentManifold(manifold_);
        // The two share the manifold, so a pair passing between them keeps its points.
        if (!rest_on_face(*first, *second, *result))
            gjk_->processCollision(first, second, info, result);
        if (manifold_->getNumContacts() > 0) result->refreshContactPoints();
    }

    btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                   btManifoldResult*) override {
        return 1;  // no continuous collision detection, as for Bullet's own convex pairs
    }

    void getAllContactManifolds(btManifoldArray& manifolds) override {
        if (manifold_) manifolds.push_back(manifold_);
    }

    struct CreateFunc : btCollisionAlgorithmCreateFunc {
        explicit CreateFunc(const Settings& s) : settings(s) {}
        btCollisionAlgorithm* CreateCollisionAlgorithm(
            btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* first,
            const btCollisionObjectWrapper* second) override {
            void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(BoxFaceAlgorithm));
            return new (memory) BoxFaceAlgorithm(info, first, second, m_swapped, settings);
        }
        Settings settings;
    };

  private:
    // Adds the points the convex rests on the box's face with, if it lies on one (or is
    // apart from the box); false where GJK must find them.
    bool rest_on_face(const btCollisionObjectWrapper& first, const btCollisionObjectWrapper& second,
                      btManifoldResult& result) const {
        const btCollisionObjectWrapper& convex_wrap = box_first_ ? second : first;
        const btCollisionObjectWrapper& box_wrap = box_first_ ? first : second;
        const auto& convex = static_cast<const btConvexShape&>(*convex_wrap.getCollisionShape());
        const auto& box = static_cast<const btBoxShape&>(*box_wrap.getCollisionShape());
        const btTransform& convex_pose = convex_wrap.getWorldTransform();
        const btTransform& box_pose = box_wrap.getWorldTransform();
        const btVector3 half = box.getHalfExtentsWithMargin();
        const Face face = facing_face(convex, convex_pose, box_pose, half);
        if (face.separation > manifold_->getContactBreakingThreshold()) return true;
        if (face.separation < -kFaceDepth) return false;

        btVector3 side, other_side;
        btPlaneSpace1(face.normal, side, other_side);
        const btScalar tilt = btMin(kMostTilt, kTiltReach / convex.getAngularMotionDisc());
        std::array<btVector3, kTilts> lowest;
        for (int k = 0; k < kTilts; ++k) {
            const btScalar about = SIMD_2_PI * static_cast<btScalar>(k) / kTilts;
            const btVector3 down = -face.normal * btCos(tilt) +
                                   (side * btCos(about) + other_side * btSin(about)) * btSin(tilt);
            lowest[k] = lowest_point(convex, convex_pose, down);
            const btVector3 on_box = box_pose.invXform(lowest[k]);
            for (int axis = 0; axis < 3; ++axis) {
                if (axis != face.axis && btFabs(on_box[axis]) > half[axis] + kEdgeSlack)
                    return false;
            }
        }
        for (const btVector3& point : lowest) {
            const btScalar distance = face.normal.dot(point) - face.offset;
            const btVector3 on_face = point - face.normal * distance;
            // Normal and point are body 1's (the box's, or the convex's where the box is first).
            if (box_first_) {
                result.addContactPoint(-face.normal, point, distance);
            } else {
                result.addContactPoint(face.normal, on_face, distance);
            }
        }
        return true;
    }

    btPersistentManifold* manifold_ = nullptr;
    btCollisionAlgorithm* gjk_ = nullptr;
    bool box_first_;
};

}  // namespace

void register_box_face_collision(btCollisionDispatcher& dispatcher,
                                 btConvexPenetrationDepthSolver& penetration, int turns,
                                 int fewest) {
    const Settings settings{&penetration, turns, fewest};
    static BoxFaceAlgorithm::CreateFunc convex_first(settings);
    static BoxFaceAlgorithm::CreateFunc box_first = [&] {
        BoxFaceAlgorithm::CreateFunc f(settings);
        f.m_swapped = true;
        return f;
    }();
    for (const int convex : {CYLINDER_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE}) {
        dispatcher.registerCollisionCreateFunc(convex, BOX_SHAPE_PROXYTYPE, &convex_first);
        dispatcher.registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, convex, &box_first);
    }
}

}  // namespace physhand
