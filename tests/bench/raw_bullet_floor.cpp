#include "raw_bullet_floor.h"

#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <memory>
#include <vector>

#include "bullet_convert.h"
#include "frame_clock.h"
#include "quantile.h"
#include "tracking.h"

namespace physhand::bench {

namespace {

struct KinematicPart {
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btRigidBody> body;
    Joint from;
    Joint to;  // == from: the palm box, at the palm joint
};

class RawWorld {
  public:
    RawWorld()
        : dispatcher_(&configuration_),
          world_(&dispatcher_, &broadphase_, &solver_, &configuration_) {}

    ~RawWorld() {
        for (int i = world_.getNumCollisionObjects() - 1; i >= 0; --i)
            world_.removeCollisionObject(world_.getCollisionObjectArray()[i]);
    }

    void add(const Collider& c) {
        std::unique_ptr<btCollisionShape> shape;
        switch (c.shape.kind) {
            case ShapeKind::Box:
                shape = std::make_unique<btBoxShape>(to_bt(c.shape.half_extents));
                break;
            case ShapeKind::Sphere:
                shape = std::make_unique<btSphereShape>(static_cast<btScalar>(c.shape.radius));
                break;
            case ShapeKind::Plane:
                shape = std::make_unique<btStaticPlaneShape>(to_bt(c.shape.normal),
                                                             static_cast<btScalar>(c.shape.offset));
                break;
            default:
                return;  // the scaling piles have boxes and planes only
        }
        const btScalar mass = c.motion == Motion::Dynamic ? static_cast<btScalar>(c.mass) : 0;
        btVector3 inertia(0, 0, 0);
        if (mass > 0) shape->calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape.get(), inertia);
        info.m_startWorldTransform = to_bt(c.pose);
        info.m_friction = static_cast<btScalar>(c.friction);
        auto body = std::make_unique<btRigidBody>(info);
        world_.addRigidBody(body.get());
        shapes_.push_back(std::move(shape));
        bodies_.push_back(std::move(body));
    }

    void add_hand(const HandPose& ghost) {
        std::vector<KinematicPart>& parts = hands_.emplace_back();
        const auto kinematic = [&](std::unique_ptr<btCollisionShape> shape, Joint from, Joint to) {
            btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shape.get());
            auto body = std::make_unique<btRigidBody>(info);
            body->setCollisionFlags(body->getCollisionFlags() |
                                    btCollisionObject::CF_KINEMATIC_OBJECT);
            body->setActivationState(DISABLE_DEACTIVATION);
            world_.addRigidBody(body.get());
            parts.push_back({std::move(shape), std::move(body), from, to});
        };
        kinematic(std::make_unique<btBoxShape>(btVector3(0.045f, 0.012f, 0.05f)), Joint::Palm,
                  Joint::Palm);
        for (Joint first : kFingerFirstBone) {
            for (int bone = 0; bone < 3; ++bone) {
                const Joint a = static_cast<Joint>(index_of(first) + bone);
                const Joint b = static_cast<Joint>(index_of(a) + 1);
                const double length = (ghost[b].position - ghost[a].position).norm();
                kinematic(std::make_unique<btCapsuleShapeZ>(
                              static_cast<btScalar>(std::max(ghost.radii[index_of(b)], 0.004)),
                              static_cast<btScalar>(length)),
                          a, b);
            }
        }
    }

    void move_hand(std::size_t hand, const HandPose& ghost) {
        for (KinematicPart& part : hands_[hand]) {
            Pose pose = ghost[part.from];
            if (part.to != part.from) {
                const Vec3 along = ghost[part.to].position - ghost[part.from].position;
                pose.position = ghost[part.from].position + along / 2;
                pose.orientation = Quat::FromTwoVectors(Vec3::UnitZ(), along.normalized());
            }
            part.body->setWorldTransform(to_bt(pose));
        }
    }

    void step(double dt) { world_.stepSimulation(static_cast<btScalar>(dt), 0); }

  private:
    btDefaultCollisionConfiguration configuration_;
    btCollisionDispatcher dispatcher_;
    btDbvtBroadphase broadphase_;
    btSequentialImpulseConstraintSolver solver_;
    btDiscreteDynamicsWorld world_;
    std::vector<std::unique_ptr<btCollisionShape>> shapes_;
    std::vector<std::unique_ptr<btRigidBody>> bodies_;
    std::vector<std::vector<KinematicPart>> hands_;
};

}  // namespace

double raw_bullet_step_us(const Scene& scene) {
    RawWorld world;
    for (const Collider& c : scene.colliders) world.add(c);
    const TrackedHands tracked(scene);
    std::vector<HandSide> sides;
    for (HandSide side : kHandSides) {
        if (!scene.hand(side)) continue;
        sides.push_back(side);
        world.add_hand(tracked.ghost(side, 0.0));
    }
    const std::int64_t period_ns = frame_period_ns(90.0);
    std::vector<double> step_us;
    for (int f = 1;; ++f) {
        const double t = clock_seconds(f * period_ns);
        for (std::size_t h = 0; h < sides.size(); ++h) {
            const HandPose ghost = tracked.ghost(sides[h], t);
            if (ghost.active) world.move_hand(h, ghost);
        }
        const auto start = std::chrono::steady_clock::now();
        world.step(1.0 / 90.0);
        step_us.push_back(
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                .count());
        if (scene_over(t, scene.duration_s)) break;
    }
    return quantile(step_us, 0.5);
}

}  // namespace physhand::bench
