#pragma once

#include <LinearMath/btTransform.h>

#include "pose.h"

namespace physhand {

inline btVector3 to_bt(const Vec3& v) {
    return {static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
            static_cast<btScalar>(v.z())};
}
inline btQuaternion to_bt(const Quat& q) {
    return {static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
            static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())};
}
inline btTransform to_bt(const Pose& p) {
    return btTransform(to_bt(p.orientation), to_bt(p.position));
}

inline Vec3 from_bt(const btVector3& v) {
    return {v.x(), v.y(), v.z()};
}
inline Quat from_bt(const btQuaternion& q) {
    return Quat(q.w(), q.x(), q.y(), q.z()).normalized();
}
inline Pose from_bt(const btTransform& t) {
    return {from_bt(t.getOrigin()), from_bt(t.getRotation())};
}

}  // namespace physhand
