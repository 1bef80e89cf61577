#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <vector>

#include "scene.h"
#include "simulation.h"

class btBroadphaseInterface;
class btCollisionDispatcher;
class btDefaultCollisionConfiguration;
class btDiscreteDynamicsWorld;
class btRigidBody;
class btSequentialImpulseConstraintSolver;

namespace physhand {

// The physics engine of an app that keeps some of its objects to itself (the scene's
// `app_engine`, docs/scene-format.md): a Bullet world of its own, holding the scene's static
// colliders and those objects. The hands' simulation sees each such object as a kinematic
// collider set every frame to where this engine has it, and this engine takes the hands'
// impulses on it (XrPhysicalColliderImpulsesPHYSHAND): the coupling recipe of
// XR_PHYSHAND_physical_hands, played the same by physhand-scene and physhand-sample.
class AppEngine {
  public:
    explicit AppEngine(const Scene& scene);
    ~AppEngine();
    AppEngine(const AppEngine&) = delete;
    AppEngine& operator=(const AppEngine&) = delete;

    // Whether scene collider `index` lives here; the hands' simulation must then have it
    // kinematic (as_declared gives the collider to declare there).
    bool simulates(std::size_t index) const { return objects_.count(index) != 0; }
    // Moves the objects on by `dt`, under gravity and the impulses applied since.
    void step(double dt);
    // An impulse on object `index` at its centre of mass, and a moment about it, world frame.
    void apply(std::size_t index, const Vec3& linear, const Vec3& angular);
    BodyState state(std::size_t index) const;

  private:
    struct Object;
    std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
    std::unique_ptr<btCollisionDispatcher> dispatcher_;
    std::unique_ptr<btBroadphaseInterface> broadphase_;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
    std::unique_ptr<btDiscreteDynamicsWorld> world_;
    std::map<std::size_t, std::unique_ptr<Object>> objects_;  // by scene collider index
    std::vector<std::unique_ptr<Object>> scenery_;            // the static colliders
};

// Scene collider `c` as the hands' simulation holds it: kinematic when the app simulates it.
Collider as_declared(const Scene& scene, std::size_t c);

}  // namespace physhand
