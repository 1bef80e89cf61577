#include "app_engine.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>

#include "bullet_convert.h"
#include "collider_shape.h"

namespace physhand {

struct AppEngine::Object {
    ColliderShape shape;
    std::unique_ptr<btRigidBody> body;
};

AppEngine::AppEngine(const Scene& scene)
    : configuration_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<btCollisionDispatcher>(configuration_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btSequentialImpulseConstraintSolver>()),
      world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                       solver_.get(), configuration_.get())) {
    world_->setGravity(to_bt(scene.gravity));
    if (scene.app_engine.empty()) return;  // nothing of the app's to simulate
    for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
        const Collider& c = scene.colliders[i];
        const bool own = std::find(scene.app_engine.begin(), scene.app_engine.end(), c.id) !=
                         scene.app_engine.end();
        if (!own && c.motion != Motion::Static) continue;
        auto object = std::make_unique<Object>();
        object->shape = make_collider_shape(c);
        const auto mass = static_cast<btScalar>(own ? c.mass : 0.0);
        btVector3 inertia(0, 0, 0);
        if (own) object->shape.shape->calculateLocalInertia(mass, inertia);
        btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, object->shape.shape.get(),
                                                      inertia);
        info.m_startWorldTransform = to_bt(c.pose);
        info.m_friction = static_cast<btScalar>(c.friction);
        info.m_restitution = static_cast<btScalar>(c.restitution);
        object->body = std::make_unique<btRigidBody>(info);
        // An app's objects stay awake while a hand may push them at any moment.
        if (own) object->body->setActivationState(DISABLE_DEACTIVATION);
        world_->addRigidBody(object->body.get());
        if (own) {
            objects_.emplace(i, std::move(object));
        } else {
            scenery_.push_back(std::move(object));
        }
    }
}

AppEngine::~AppEngine() {
    for (auto& [index, object] : objects_) world_->removeRigidBody(object->body.get());
    for (auto& object : scenery_) world_->removeRigidBody(object->body.get());
}

void AppEngine::step(double dt) {
    if (objects_.empty()) return;
    world_->stepSimulation(static_cast<btScalar>(dt), 0);
}

void AppEngine::apply(std::size_t index, const Vec3& linear, const Vec3& angular) {
    btRigidBody& body = *objects_.at(index)->body;
    body.applyCentralImpulse(to_bt(linear));
    body.applyTorqueImpulse(to_bt(angular));
}

BodyState AppEngine::state(std::size_t index) const {
    const btRigidBody& body = *objects_.at(index)->body;
    BodyState s;
    s.pose = from_bt(body.getWorldTransform());
    s.linear_velocity = from_bt(body.getLinearVelocity());
    s.angular_velocity = from_bt(body.getAngularVelocity());
    return s;
}

Collider as_declared(const Scene& scene, std::size_t c) {
    Collider declared = scene.colliders[c];
    if (std::find(scene.app_engine.begin(), scene.app_engine.end(), declared.id) !=
        scene.app_engine.end()) {
        declared.motion = Motion::Kinematic;
        declared.mass = 0.0;
    }
    return declared;
}

}  // namespace physhand
