#pragma once

#include <LinearMath/btScalar.h>

class btManifoldPoint;
class btPersistentManifold;

namespace physhand {

// A friction anchor gives way to a fresh point near it that is deeper by more than this (m).
// Bullet keeps an old point in place of a new one near it while its friction holds (a
// friction anchor), so a grip stays put, and measures the old point along its old normal: a
// thumb squeezed into a held cube slid 20 mm into it while its anchor read 1-2 mm, and
// nothing pushed it out. Anchors that yield to any deeper point (1-4 mm) show the squeeze as
// 3-9 mm deep but lose grips that the sunk fingers held (robustness benchmark, bones/1:
// 62-70 % against 78 %); at 12 mm every drive's benchmark is as before within its spread
// and the squeeze's shown depth is halved or better (BENCHMARKS.md).
inline constexpr btScalar kAnchorSlack = 0.012f;

// Puts a freshly found point into `manifold` as Bullet does (it takes the place of the
// nearest point, if any is near enough, else is added), except that a friction anchor does
// not hide a contact kAnchorSlack deeper.
void insert_contact_point(btPersistentManifold& manifold, const btManifoldPoint& point);

}  // namespace physhand
