#include "hand_point_contacts.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <btBulletCollisionCommon.h>

#include <algorithm>
#include <array>
#include <optional>
#include <utility>

#include "ball_contact.h"
#include "contact_insertion.h"
#include "world.h"

namespace physhand {

namespace {

bool is_hand(const btCollisionObject& o) {
    return static_cast<BodyRole>(o.getUserIndex()) == BodyRole::Hand;
}

// A ball at which a hand part meets a surface first: an end of a capsule, a corner of a box
// (a point: sharp, as Bullet's box-box and box-plane contacts take it), or a joint sphere.
struct Ball {
    btVector3 centre;
    btScalar radius;
};

// The part's balls in world space; none for a part of another shape.
int balls_of(const btCollisionObject& part, std::array<Ball, 8>& out) {
    const btCollisionShape& shape = *part.getCollisionShape();
    const btTransform& t = part.getWorldTransform();
    if (shape.getShapeType() == CAPSULE_SHAPE_PROXYTYPE) {
        const auto& capsule = static_cast<const btCapsuleShape&>(shape);
        const auto [a, b] = capsule_ends(capsule, t);
        out[0] = {a, capsule.getRadius()};
        out[1] = {b, capsule.getRadius()};
        return 2;
    }
    if (shape.getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
        out[0] = {t.getOrigin(), static_cast<const btSphereShape&>(shape).getRadius()};
        return 1;
    }
    if (shape.getShapeType() == BOX_SHAPE_PROXYTYPE) {
        const auto& box = static_cast<const btBoxShape&>(shape);
        const btVector3 half = box.getHalfExtentsWithMargin();
        for (int i = 0; i < 8; ++i) {
            const btVector3 corner(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(),
                                   i & 4 ? half.z() : -half.z());
            out[static_cast<std::size_t>(i)] = {t * corner, 0};
        }
        return 8;
    }
    return 0;
}

// A ball's point takes the place of the manifold's nearest point, as Bullet's own insertion
// does, unless that point is deeper and elsewhere on the ball's part (further than the ball's
// radius; `part_first`: the part is the manifold's first): the distance to a convex collider
// is least at a capsule's end or a box's corner unless the part crosses an edge or a curved
// surface, whose contact it then keeps beside the balls'.
void merge_ball_contact(const btManifoldPoint& point, bool part_first, btScalar radius,
                        btPersistentManifold& manifold) {
    const auto on_part = [part_first](const btManifoldPoint& p) {
        return part_first ? p.m_localPointA : p.m_localPointB;
    };
    const int nearest = manifold.getCacheEntry(point);
    if (nearest >= 0) {
        const btManifoldPoint& there = manifold.getContactPoint(nearest);
        if (there.getDistance() < point.getDistance() - kDeeper &&
            (on_part(there) - on_part(point)).length2() > radius * radius) {
            manifold.addManifoldPoint(point);
            return;
        }
    }
    insert_contact_point(manifold, point);
}

// The balls of `part` (one of the manifold's pair; `part_first`: its first) against `other`,
// each merged into `manifold` at most kCornersKept of a box's corners, the nearest.
void add_ball_contacts(const btCollisionObject& part, const btCollisionObject& other,
                       bool part_first, btScalar reach, const btCollisionObjectWrapper& part_wrap,
                       const btCollisionObjectWrapper& other_wrap, btPersistentManifold& manifold) {
    // A manifold holds four points: a box keeps its four corners nearest the collider.
    constexpr std::size_t kCornersKept = 4;
    std::array<Ball, 8> balls;
    const int count = balls_of(part, balls);
    std::array<std::pair<BallContact, btScalar>, 8> found;  // with the ball's radius
    std::size_t n = 0;
    for (int b = 0; b < count; ++b) {
        const Ball& ball = balls[static_cast<std::size_t>(b)];
        const std::optional<BallContact> c = ball_contact(ball.centre, ball.radius, other, reach,
                                                          part.getWorldTransform().getOrigin());
        if (c && c->distance < reach) found[n++] = {*c, ball.radius};
    }
    if (part.getCollisionShape()->getShapeType() == BOX_SHAPE_PROXYTYPE && n > kCornersKept) {
        std::partial_sort(
            found.begin(), found.begin() + kCornersKept, found.begin() + n,
            [](const auto& a, const auto& b) { return a.first.distance < b.first.distance; });
        n = kCornersKept;
    }
    for (std::size_t k = 0; k < n; ++k) {
        const auto& [c, radius] = found[k];
        // In the real manifold's order; merge_ball_contact says where the point goes.
        btManifoldResult result(part_first ? &part_wrap : &other_wrap,
                                part_first ? &other_wrap : &part_wrap);
        const std::optional<btManifoldPoint> point =
            part_first ? build_contact_point(result, manifold, c.normal, c.on_collider, c.distance)
                       : build_contact_point(result, manifold, -c.normal,
                                             c.on_collider + c.normal * c.distance, c.distance);
        if (point) merge_ball_contact(*point, part_first, radius, manifold);
    }
}

}  // namespace

void add_hand_point_contacts(btCollisionDispatcher& dispatcher) {
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
        btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(i);
        const btCollisionObject* hand = manifold->getBody0();
        const btCollisionObject* other = manifold->getBody1();
        const bool hand_first = is_hand(*hand);
        if (!hand_first) std::swap(hand, other);
        if (!is_hand(*hand)) continue;
        const btCollisionShape* other_shape = other->getCollisionShape();
        const int other_type = other_shape->getShapeType();
        if (other_type != STATIC_PLANE_PROXYTYPE && other_type != TRIANGLE_MESH_SHAPE_PROXYTYPE &&
            !other_shape->isConvex())
            continue;
        const int hand_type = hand->getCollisionShape()->getShapeType();
        // Bullet finds a point of any convex pair within reach but two boxes, which it finds
        // only overlapping: nothing of such a part within reach, none of its balls is.
        const bool two_boxes =
            hand_type == BOX_SHAPE_PROXYTYPE && other_type == BOX_SHAPE_PROXYTYPE;
        if (manifold->getNumContacts() == 0 && !two_boxes) continue;

        const btScalar reach = manifold->getContactBreakingThreshold();
        const btCollisionObjectWrapper hand_wrap(nullptr, hand->getCollisionShape(), hand,
                                                 hand->getWorldTransform(), -1, -1);
        const btCollisionObjectWrapper other_wrap(nullptr, other_shape, other,
                                                  other->getWorldTransform(), -1, -1);
        // The hand part's balls against the collider, and for two boxes the collider's
        // corners against the hand's box as well: a small box falling flat onto the palm
        // has no corner of the palm within reach, and fell through it at 2 m/s.
        add_ball_contacts(*hand, *other, hand_first, reach, hand_wrap, other_wrap, *manifold);
        if (two_boxes)
            add_ball_contacts(*other, *hand, !hand_first, reach, other_wrap, hand_wrap, *manifold);
    }
}

}  // namespace physhand
