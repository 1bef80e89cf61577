#include "capsule_collision.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <btBulletCollisionCommon.h>

#include <optional>

#include "ball_contact.h"
#include "contact_insertion.h"
#include "one_manifold_algorithm.h"
#include "segment_search.h"
#include "triangle_contact.h"

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
// a flat stretch of them).
BallContact segment_box_contact(const btVector3& a, const btVector3& b, btScalar radius,
                                const btTransform& box, const btVector3& half) {
    const btVector3 la = box.invXform(a);
    const btVector3 lab = box.invXform(b) - la;
    const btScalar t = least_along_segment(
        [&](btScalar s) { return signed_distance_squared(la + lab * s, half); });
    const BallContact inner = ball_box_contact(a + (b - a) * t, radius, box, half);
    const BallContact at_a = ball_box_contact(a, radius, box, half);
    const BallContact at_b = ball_box_contact(b, radius, box, half);
    const BallContact& end = at_a.distance <= at_b.distance ? at_a : at_b;
    return inner.distance < end.distance - kDeeper ? inner : end;
}

// The contact of the capsule's balls of `radius` along the segment from `a` to `b` with the
// collider `other`; none beyond `reach`.
using CapsuleContact = std::optional<BallContact> (*)(const btVector3& a, const btVector3& b,
                                                      btScalar radius,
                                                      const btCollisionObjectWrapper& other,
                                                      btScalar reach);

std::optional<BallContact> capsule_box_contact(const btVector3& a, const btVector3& b,
                                               btScalar radius,
                                               const btCollisionObjectWrapper& box_wrap,
                                               btScalar reach) {
    const auto& box = static_cast<const btBoxShape&>(*box_wrap.getCollisionShape());
    const btTransform& pose = box_wrap.getWorldTransform();
    const btVector3 half = box.getHalfExtentsWithMargin();
    // The ball around the whole capsule is no nearer than the capsule: when even it is beyond
    // reach, no point would be kept, so none is searched for (most pairs of a hand in a pile;
    // the search was 30 % of such a frame, callgrind).
    if (ball_box_contact((a + b) / 2, (b - a).length() / 2 + radius, pose, half).distance > reach)
        return std::nullopt;
    return segment_box_contact(a, b, radius, pose, half);
}

std::optional<BallContact> capsule_mesh_contact(const btVector3& a, const btVector3& b,
                                                btScalar radius,
                                                const btCollisionObjectWrapper& mesh_wrap,
                                                btScalar reach) {
    return mesh_capsule_contact(a, b, radius,
                                static_cast<const btConcaveShape&>(*mesh_wrap.getCollisionShape()),
                                mesh_wrap.getWorldTransform(), reach, (a + b) / 2);
}

class CapsuleAlgorithm : public OneManifoldAlgorithm {
  public:
    CapsuleAlgorithm(const btCollisionAlgorithmConstructionInfo& info,
                     const btCollisionObjectWrapper* first, const btCollisionObjectWrapper* second,
                     bool other_first, CapsuleContact contact)
        : OneManifoldAlgorithm(info, first, second,
                               (other_first ? second : first)->getCollisionObject(),
                               (other_first ? first : second)->getCollisionObject()),
          other_first_(other_first),
          contact_(contact) {}

    void processCollision(const btCollisionObjectWrapper* first,
                          const btCollisionObjectWrapper* second, const btDispatcherInfo&,
                          btManifoldResult* result) override {
        if (!manifold_) return;
        const btCollisionObjectWrapper* capsule_wrap = other_first_ ? second : first;
        const btCollisionObjectWrapper* other_wrap = other_first_ ? first : second;
        const auto& capsule =
            static_cast<const btCapsuleShape&>(*capsule_wrap->getCollisionShape());
        const auto [a, b] = capsule_ends(capsule, capsule_wrap->getWorldTransform());
        result->setPersistentManifold(manifold_);
        // The manifold is (capsule, other): Bullet takes the point on the other and its normal.
        if (const std::optional<BallContact> c = contact_(
                a, b, capsule.getRadius(), *other_wrap, manifold_->getContactBreakingThreshold())) {
            if (const auto point = build_contact_point(*result, *manifold_, c->normal,
                                                       c->on_collider, c->distance))
                insert_contact_point(*manifold_, *point);
        }
        if (manifold_->getNumContacts() > 0) result->refreshContactPoints();
    }

    struct CreateFunc : btCollisionAlgorithmCreateFunc {
        CreateFunc(CapsuleContact contact, bool other_first) : contact(contact) {
            m_swapped = other_first;
        }
        btCollisionAlgorithm* CreateCollisionAlgorithm(
            btCollisionAlgorithmConstructionInfo& info, const btCollisionObjectWrapper* first,
            const btCollisionObjectWrapper* second) override {
            void* memory = info.m_dispatcher1->allocateCollisionAlgorithm(sizeof(CapsuleAlgorithm));
            return new (memory) CapsuleAlgorithm(info, first, second, m_swapped, contact);
        }
        CapsuleContact contact;
    };

  private:
    bool other_first_;
    CapsuleContact contact_;
};

}  // namespace

void register_capsule_collision(btCollisionDispatcher& dispatcher) {
    static CapsuleAlgorithm::CreateFunc capsule_box(capsule_box_contact, false);
    static CapsuleAlgorithm::CreateFunc box_capsule(capsule_box_contact, true);
    static CapsuleAlgorithm::CreateFunc capsule_mesh(capsule_mesh_contact, false);
    static CapsuleAlgorithm::CreateFunc mesh_capsule(capsule_mesh_contact, true);
    dispatcher.registerCollisionCreateFunc(CAPSULE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE,
                                           &capsule_box);
    dispatcher.registerCollisionCreateFunc(BOX_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE,
                                           &box_capsule);
    dispatcher.registerCollisionCreateFunc(CAPSULE_SHAPE_PROXYTYPE, TRIANGLE_MESH_SHAPE_PROXYTYPE,
                                           &capsule_mesh);
    dispatcher.registerCollisionCreateFunc(TRIANGLE_MESH_SHAPE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE,
                                           &mesh_capsule);
}

}  // namespace physhand
