#include "speed_limit.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace physhand {

namespace {
constexpr double kLimitRounding = 1e-5;  // a hundred times float's relative precision
}  // namespace

double max_point_speed(const btRigidBody& body) {
    return body.getLinearVelocity().length() +
           body.getAngularVelocity().length() * body.getCollisionShape()->getAngularMotionDisc();
}

void SpeedCheck::add(const SpeedCheck& other) {
    clamped += other.clamped;
    requested = std::max(requested, other.requested);
    fastest = std::max(fastest, other.fastest);
}

SpeedCheck limit_speeds(btRigidBody& body, double max_linear) {
    SpeedCheck check;
    const btScalar w = body.getAngularVelocity().length();
    if (!std::isfinite(w) || w > kMaxAngularSpeed) {
        body.setAngularVelocity(std::isfinite(w) ? body.getAngularVelocity() *
                                                       static_cast<btScalar>(kMaxAngularSpeed / w)
                                                 : btVector3(0, 0, 0));
        check.clamped = 1;
    }
    const btScalar v = body.getLinearVelocity().length();
    check.requested = std::isfinite(v) ? double{v} : std::numeric_limits<double>::infinity();
    if (!std::isfinite(v) || v > max_linear) {
        // Just under the limit: scaled exactly to it, float rounding leaves some bodies over.
        const double scale = max_linear / v * (1.0 - kLimitRounding);
        body.setLinearVelocity(std::isfinite(v)
                                   ? body.getLinearVelocity() * static_cast<btScalar>(scale)
                                   : btVector3(0, 0, 0));
        check.clamped = 1;
    }
    check.fastest = body.getLinearVelocity().length();
    return check;
}

}  // namespace physhand
