#include "contact_events.h"

#include <algorithm>
#include <stdexcept>

namespace physhand {

namespace {

ContactEvent event_of(ContactEvent::Kind kind, const ContactInfo& c, double time_s) {
    ContactEvent e;
    e.kind = kind;
    e.hand = c.hand;
    e.joint = c.joint;
    e.collider = c.collider;
    e.other = c.other;
    e.point = c.point;
    e.normal = c.normal;
    if (kind != ContactEvent::Kind::End) {
        e.impulse = c.impulse;
        e.impulse_on_collider = c.impulse_on_collider;
    }
    e.approach_speed = kind == ContactEvent::Kind::Begin ? c.approach_speed : 0.0;
    e.time_s = time_s;
    return e;
}

}  // namespace

void ContactEventLog::enable(bool persist, std::size_t capacity, bool between_colliders) {
    if (capacity < 1 || capacity > kMaxCapacity) {
        throw std::invalid_argument("contact events: capacity must be 1 to 65536");
    }
    persist_ = persist;
    between_colliders_ = between_colliders;
    capacity_ = capacity;
    if (events_.size() > capacity_) {  // as when they came to a full queue: the newest go
        lost_ += events_.size() - capacity_;
        events_.resize(capacity_);
    }
}

void ContactEventLog::record(const std::vector<ContactInfo>& hand_contacts,
                             const std::vector<ContactInfo>& collider_contacts, double time_s) {
    if (!enabled()) return;
    std::map<Key, ContactInfo> now;
    for (const ContactInfo& c : hand_contacts) {
        now.emplace(Key{static_cast<int>(c.hand), static_cast<int>(c.joint), c.collider, 0}, c);
    }
    if (between_colliders_) {
        for (const ContactInfo& c : collider_contacts)
            now.emplace(Key{-1, 0, c.collider, c.other}, c);
    }
    for (const auto& [key, c] : touching_) {
        if (now.count(key) == 0) push(event_of(ContactEvent::Kind::End, c, time_s));
    }
    for (const auto& [key, c] : now) {
        if (touching_.count(key) == 0) {
            push(event_of(ContactEvent::Kind::Begin, c, time_s));
        } else if (persist_) {
            push(event_of(ContactEvent::Kind::Persist, c, time_s));
        }
    }
    touching_ = std::move(now);
}

void ContactEventLog::drop_oldest(std::size_t count) {
    count = std::min(count, events_.size());
    events_.erase(events_.begin(), events_.begin() + static_cast<std::ptrdiff_t>(count));
}

void ContactEventLog::push(const ContactEvent& event) {
    if (events_.size() >= capacity_) {
        ++lost_;
        return;
    }
    events_.push_back(event);
}

}  // namespace physhand
