#include "triangle_contact.h"

#include <btBulletCollisionCommon.h>

#include "segment_search.h"

namespace physhand {

namespace {

// The point of triangle (a, b, c) nearest p, by the region of the triangle p projects into
// (Ericson, Real-Time Collision Detection, 5.1.5).
btVector3 nearest_on_triangle(const btVector3& p, const btVector3& a, const btVector3& b,
                              const btVector3& c) {
    const btVector3 ab = b - a, ac = c - a, ap = p - a;
    const btScalar d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const btVector3 bp = p - b;
    const btScalar d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const btScalar vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const btVector3 cp = p - c;
    const btScalar d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const btScalar vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const btScalar va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const btScalar scale = 1 / (va + vb + vc);
    return a + ab * (vb * scale) + ac * (vc * scale);
}

// The nearest of a mesh's triangles to the segment from `a` to `b` (the mesh's frame), as a
// contact of the segment's balls of `radius`. A triangle's face counts from the side
// `outside` lies on: a point over the face but behind it is that deep in.
class NearestTriangle : public btTriangleCallback {
  public:
    NearestTriangle(const btVector3& a, const btVector3& b, btScalar radius,
                    const btVector3& outside)
        : a_(a), b_(b), radius_(radius), outside_(outside) {}

    void processTriangle(btVector3* t, int, int) override {
        btVector3 face = (t[1] - t[0]).cross(t[2] - t[0]);
        if (face.length2() <= SIMD_EPSILON * SIMD_EPSILON) return;  // no area: no face
        face.normalize();
        if (face.dot(outside_ - t[0]) < 0) face = -face;
        // A ball (no segment) has nothing to search along.
        const btScalar nearest = a_ == b_ ? btScalar(0) : least_along_segment([&](btScalar s) {
            const btVector3 p = a_.lerp(b_, s);
            return (p - nearest_on_triangle(p, t[0], t[1], t[2])).length2();
        });
        // The nearest point, and the ends: behind the face the deepest point is an end.
        for (const btScalar s : {nearest, btScalar(0), btScalar(1)}) {
            const btVector3 p = a_.lerp(b_, s);
            const btVector3 q = nearest_on_triangle(p, t[0], t[1], t[2]);
            const btVector3 off = p - q;
            const btScalar along = off.dot(face);
            if ((off - face * along).length2() <= btScalar(1e-6) * off.length2() + btScalar(1e-12))
                keep(face, q, along - radius_);  // over the face
            else
                keep(off.normalized(), q, off.length() - radius_);
        }
    }

    const std::optional<BallContact>& found() const { return found_; }

  private:
    void keep(const btVector3& normal, const btVector3& on_triangle, btScalar distance) {
        if (!found_ || distance < found_->distance)
            found_ = BallContact{normal, on_triangle, distance};
    }

    btVector3 a_, b_;
    btScalar radius_;
    btVector3 outside_;
    std::optional<BallContact> found_;
};

}  // namespace

std::optional<BallContact> mesh_capsule_contact(const btVector3& a, const btVector3& b,
                                                btScalar radius, const btConcaveShape& mesh,
                                                const btTransform& pose, btScalar reach,
                                                const btVector3& outside) {
    const btVector3 la = pose.invXform(a), lb = pose.invXform(b);
    const btScalar far = radius + reach;
    btVector3 lo = la, hi = la;
    lo.setMin(lb);
    hi.setMax(lb);
    const btVector3 pad(far, far, far);
    NearestTriangle nearest(la, lb, radius, pose.invXform(outside));
    mesh.processAllTriangles(&nearest, lo - pad, hi + pad);
    if (!nearest.found() || nearest.found()->distance > reach) return std::nullopt;
    const BallContact& c = *nearest.found();
    return BallContact{pose.getBasis() * c.normal, pose * c.on_collider, c.distance};
}

std::optional<BallContact> mesh_ball_contact(const btVector3& centre, btScalar radius,
                                             const btConcaveShape& mesh, const btTransform& pose,
                                             btScalar reach, const btVector3& outside) {
    return mesh_capsule_contact(centre, centre, radius, mesh, pose, reach, outside);
}

}  // namespace physhand
