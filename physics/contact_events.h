#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <tuple>
#include <vector>

#include "hand_skeleton.h"
#include "pose.h"

namespace physhand {

using ColliderHandle = std::uint32_t;

// One hand body touching one collider over a physics frame, or (`other` set) two colliders
// touching each other.
struct ContactInfo {
    HandSide hand;
    Joint joint;  // the first joint the body carries (a bone's base joint, the palm)
    ColliderHandle collider;
    // Non-zero: the collider that touched `collider` (hand and joint then mean nothing).
    ColliderHandle other = 0;
    double impulse = 0.0;  // N·s of normal impulse over the frame
    // The impulse `collider` took (normal and friction) over the frame, N·s, world frame.
    Vec3 impulse_on_collider = Vec3::Zero();
    double penetration = 0.0;  // m, >= 0
    // Where they touch (on the collider's surface) and the normal from the collider toward
    // what touched it, world frame, at the frame's deepest contact point.
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();
    // The fastest the two approached along the normal at any of the frame's contact points,
    // before the solver stopped them, m/s.
    double approach_speed = 0.0;
};

struct ContactEvent {
    enum class Kind { Begin, Persist, End };
    Kind kind = Kind::Begin;
    HandSide hand = HandSide::Right;
    Joint joint = Joint::Palm;
    ColliderHandle collider = 0;
    ColliderHandle other = 0;    // as in ContactInfo
    Vec3 point = Vec3::Zero();   // world; an End's is where they last touched
    Vec3 normal = Vec3::Zero();  // world, from the collider toward what touched it
    double impulse = 0.0;        // N·s of normal impulse over the frame; 0 for End
    // The impulse the collider took, normal and friction, world; 0 for End.
    Vec3 impulse_on_collider = Vec3::Zero();
    double approach_speed = 0.0;  // m/s at impact (Begin); 0 otherwise
    double time_s = 0.0;          // end of the physics frame, the simulation's clock
};

// Turns each physics frame's contacts into begin / persist / end events, kept in a bounded
// queue the caller drains. Nothing is kept or compared until it is enabled: a scene nobody
// listens to pays nothing for it.
class ContactEventLog {
  public:
    static constexpr std::size_t kDefaultCapacity = 1024;
    static constexpr std::size_t kMaxCapacity = 65536;

    // Starts recording (from the next frame) with this queue capacity (1..kMaxCapacity),
    // persist events or not, contacts between colliders or not. Events that come to a full
    // queue are dropped and counted, and a smaller capacity drops the newest beyond it: what
    // the caller has not read is never reordered or overwritten.
    void enable(bool persist, std::size_t capacity, bool between_colliders = false);
    bool enabled() const { return capacity_ > 0; }
    bool between_colliders() const { return between_colliders_; }
    // The contacts of the physics frame that ended at `time_s`: the hands', and those
    // between colliders (ignored unless asked for).
    void record(const std::vector<ContactInfo>& hand_contacts,
                const std::vector<ContactInfo>& collider_contacts, double time_s);
    // Oldest first.
    const std::deque<ContactEvent>& events() const { return events_; }
    void drop_oldest(std::size_t count);
    // Events not kept because the queue was full, since the last clear_lost().
    std::uint64_t lost() const { return lost_; }
    void clear_lost() { lost_ = 0; }

  private:
    using Key = std::tuple<int, int, ColliderHandle, ColliderHandle>;
    void push(const ContactEvent& event);

    std::map<Key, ContactInfo> touching_;  // ordered: events come in the same order every run
    std::deque<ContactEvent> events_;
    std::size_t capacity_ = 0;
    bool persist_ = false;
    bool between_colliders_ = false;
    std::uint64_t lost_ = 0;
};

}  // namespace physhand
