#pragma once

#include <BulletCollision/NarrowPhaseCollision/btManifoldPoint.h>
#include <LinearMath/btScalar.h>

#include <optional>

class btManifoldResult;
class btPersistentManifold;

namespace physhand {

// A friction anchor gives way to a fresh point near it that is deeper by more than this (m).
// Bullet keeps an old point in place of a new one near it while its friction holds (a
// friction anchor), so a grip stays put, and measures the old point along its old normal: a
// thumb squeezed into a held cube slid 20 mm into it while its anchor read 1-2 mm, and
// nothing pushed it out. Anchors that yield to any deeper point (1-4 mm) show the squeeze as
// 3-9 mm deep but lose grips that the sunk fingers held (robustness benchmark, bones/1:
// 62-70 % against 78 %); at 12 mm every drive's benchmark is as before within its spread
// and the squeeze's shown depth is halved or better (BENCHMARKS.md). Also measured (bones/1,
// 200 variants at 4 shifts, 635 of 800 succeeding with this): keeping the anchor and adding
// a fresh point 1 mm deeper beside it took lift_hold squeezed to curls 0.5-1.0 from 7.7-14 mm
// shown to 3.1-4.8 mm, but 539 of 800 succeeded (throw 33 of 160 against 111, the thumb's
// release kick turned more sideways; displacement 51 against 82); yielding only for parts
// whose goal lies over 5-10 mm inside what they hold (a deliberate squeeze), 3.3-6.2 mm
// shown, but the squeezed cube slipped out at most curls: capsules across a cube's edges and
// corners push it out along their slanted normals once nothing hides how deep they are.
inline constexpr btScalar kAnchorSlack = 0.012f;

// Puts a freshly found point into `manifold` as Bullet does (it takes the place of the
// nearest point, if any is near enough, else is added), except that a friction anchor does
// not hide a contact kAnchorSlack deeper.
void insert_contact_point(btPersistentManifold& manifold, const btManifoldPoint& point);

// The point `result` builds for `manifold`'s pair as Bullet would (friction, restitution,
// local points), in a manifold of its own so that insert_contact_point decides where it goes;
// none beyond the manifold's reach. `result` is left writing to `manifold`. Arguments as
// btManifoldResult::addContactPoint takes them.
std::optional<btManifoldPoint> build_contact_point(btManifoldResult& result,
                                                   btPersistentManifold& manifold,
                                                   const btVector3& normal_on_b,
                                                   const btVector3& point_on_b, btScalar distance);

}  // namespace physhand
