#pragma once

class btRigidBody;

namespace physhand {

// Past this a body is spinning up toward an explosion, not moving (no hand part or held
// object turns 16 times a second).
inline constexpr double kMaxAngularSpeed = 100.0;  // rad/s

// What limiting the speeds of some bodies found.
struct SpeedCheck {
    int clamped = 0;         // bodies slowed down (linear or angular speed over, or not finite)
    double requested = 0.0;  // largest linear speed before limiting, m/s; inf if not finite
    double fastest = 0.0;    // largest linear speed after it: what the bodies move with
    void add(const SpeedCheck& other);
};

// The fastest any point of a body moves: its centre's speed plus its spin times its reach
// (the shape's bounding sphere about its centre).
double max_point_speed(const btRigidBody& body);

// Scales the body's linear speed down to `max_linear` and its angular speed to
// kMaxAngularSpeed, a non-finite one to zero, and reports what it found.
SpeedCheck limit_speeds(btRigidBody& body, double max_linear);

}  // namespace physhand
