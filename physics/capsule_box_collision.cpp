#include "capsule_box_collision.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <btBulletCollisionCommon.h>

#include "ball_contact.h"
#include "contact_insertion.h"
#include "one_manifold_algorithm.h"

namespace physhand {

namespace {

// How far a point (in the box's frame) lies outside the box, squared, or minus how deep it
// lies inside, squared: ordered as the signed distance is, without a square root.
btScalar signed_distance_squared(const btVector3& p, const btVector3& half) {
    btVector3 nearest = p;
    nearest.setMax(-half);
    nearest.setMin(half);
    const btScalar outside = (p - nearest).length2();
    if (outside > 0) return outside;
    const btVector3 depth = half - p.absolute();
    const btScalar least = btMin(depth.x(), btMin(depth.y(), depth.z()));
    return -least * least;
}

// The point of the segment from `a` to `b`, swollen by `radius`, deepest in or nearest to
// the box. Signed distance to a box is convex, so along the segment it has one minimum (or
// a flat stretch of them); 24 golden-section steps narrow it to 1e-5 of the segment.
BallContact segment_box_contact(const btVector3& a, const btVector3& b, btScalar radius,
                                const btTransform& box, const btVector3& half) {
    constexpr btScalar kShrink = 0.6180340f;
    constexpr int kSteps = 24;
    const btVector3 la = box.invXform(a);
    const btVector3 lab = box.invXform(b) - la;
    auto distance = [&](btScalar t) { return signed_distance_squared(la + lab * t, half); };
    btScalar lo = 0, hi = 1;
    btScalar x1 = hi - kShrink, x2 = lo + kShrink;
    btScalar f1 = distance(x1), f2 = distance(x2);
    for (int i = 0; i < kSteps; ++i) {
        if (f1 <= f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - kShrink * (hi - lo);
            f1 = distance(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + kShrink * (hi - lo);
            f2 = distance(x2);
        }
    }
    const BallContact inner = ball_box_contact(a + (b - a) * ((lo + hi) / 2), radius, box, half);
    const BallContact at_a = ball_box_contact(a, radius, box, half);
    const BallContact at_b = ball_box_contact(b, radius, box, half);
    const BallContact& end = at_a.distance <= at_b.distance ? at_a : at_b;
    return inner.distance < end.distance - kDeeper ? inner : end;
}

class CapsuleBoxAlgorithm : public OneManifoldAlgorithm {
  public:
    CapsuleBoxAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                        const btCollisionObjectWrapper* first,
                        const btCollisionObjectWrapper* second, bool box_first)
        : OneManifoldAlgorithm(info, first, second,
                               (box_first ? second : first)->getCollisionObject(),
                               (box_first ? first : second)->getCollisionObject()),
          box_first_(box_first) {}

    void processCollision(const btCollisionObjectWrapper* first,
                          const btCollisionObjectWrapper* second, const btDispatcherInfo&,
                          btManifoldResult* result) override {
        if (!manifold_) return;
        const btCollisionObjectWrapper* capsule_wrap = box_first_ ? second : first;
        const btCollisionObjectWrapper* box_wrap = box_first_ ? first : second;
        const auto& capsule =
            static_cast<const btCapsuleShape&>(*capsule_wrap->getCollisionShape());
        const auto& box = static_cast<const btBoxShape&>(*box_wrap->getCollisionShape());
        const auto [a, b] = capsule_ends(capsule, capsule_wrap->getWorldTransform());

        result->setPersistentManifold(manifold_);
        const btTransform& box_pose = box_wrap->getWorldTransform();
        const btVector3 half = box.getHalfExtentsWithMargin();
        // The ball around the whole capsule is no nearer than the capsule: when even it is
        // beyond the manifold's reach, no point would be kept, so none is searched for
        // (most pairs of a hand in a pile; the search was 30 % of such a frame, callgrind).
        const btScalar bound = capsule.getHalfHeight() + capsule.getRadius();
        if (ball_box_contact((a + b) / 2, bound, box_pose, half).distance <=
            manifold_->getContactBreakingThreshold()) {
            const BallContact c = segment_box_contact(a, b, capsule.getRadius(), box_pose, half);
            // The manifold is (capsule, box): Bullet takes the point on the box and its normal.
            if (const auto point =
                    build_contact_point(*result, *manifold_, c.normal, c.on_collider, c.distance))
                insert_contact_point(*manifold_, *point);
        }
        if (manifold_->getNumContacts() > 0) result->refreshContactPoints();
    }

    struct CreateFunc : btCollisionAlgorithmCreateFunc {
        btCollisionAlgorithm* CreateCollisionAlgorithm(
            btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* first,
            const btCollisionObjectWrapper* second) override {
            void* memory =
                info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(CapsuleBoxAlgorithm));
            return new (memory) CapsuleBoxAlgorithm(info, first, second, m_swapped);
        }
    };

  private:
    bool box_first_;
};

}  // namespace

void register_capsule_box_collision(btCollisionDispatcher& dispatcher) {
    static CapsuleBoxAlgorithm::CreateFunc capsule_first;
    static CapsuleBoxAlgorithm::CreateFunc box_first = [] {
        CapsuleBoxAlgorithm::CreateFunc f;
        f.m_swapped = true;
        return f;
    }();
    dispatcher.registerCollisionCreateFunc(CAPSULE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE,
                                           &capsule_first);
    dispatcher.registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE,
                                           &box_first);
}

}  // namespace physhand
