#include "triangle_contact.h"

#include <btBulletCollisionCommon.h>
#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace physhand {
namespace {

constexpr btScalar kRadius = 0.008f;
constexpr btScalar kReach = 0.02f;

// A 20 cm square at y = 0 made of two triangles, split along one diagonal or the other.
class Square {
  public:
    explicit Square(bool other_diagonal)
        : indices_(other_diagonal ? std::array<int, 6>{0, 1, 2, 0, 2, 3}
                                  : std::array<int, 6>{0, 1, 3, 1, 2, 3}),
          data_(2, indices_.data(), 3 * sizeof(int), 4, vertices_.data(), 3 * sizeof(float)),
          shape_(&data_, true) {}
    const btConcaveShape& shape() const { return shape_; }

  private:
    std::array<float, 12> vertices_ = {-0.1f, 0, -0.1f, 0.1f,  0, -0.1f,
                                       0.1f,  0, 0.1f,  -0.1f, 0, 0.1f};
    std::array<int, 6> indices_;
    btTriangleIndexVertexArray data_;
    btBvhTriangleMeshShape shape_;
};

std::optional<BallContact> capsule_on(const Square& square, const btVector3& a,
                                      const btVector3& b) {
    return mesh_capsule_contact(a, b, kRadius, square.shape(), btTransform::getIdentity(), kReach,
                                (a + b) / 2);
}

// A capsule lying across the edge between the two triangles meets the flat square as one face,
// whichever way it is split: Bullet's pair gave it the edge's tilted normal.
TEST(TriangleContact, ACapsuleAcrossTheSplitMeetsOneFlatFace) {
    for (const bool other : {false, true}) {
        const Square square(other);
        for (const btScalar height : {0.002f, -0.003f}) {
            const btScalar y = kRadius + height;
            const auto c =
                capsule_on(square, btVector3(-0.03f, y, 0.02f), btVector3(0.03f, y, -0.01f));
            ASSERT_TRUE(c.has_value());
            EXPECT_NEAR(c->distance, height, 1e-5);
            EXPECT_NEAR(c->normal.y(), 1.0, 1e-5);
        }
    }
}

// A capsule dipping one end through the square is that deep on its middle's side, pushed back
// up, not on through (its end ball's nearest point alone points down).
TEST(TriangleContact, AnEndThroughTheFaceIsDeepOnTheSideTheMiddleLiesOn) {
    const Square square(false);
    const auto c = capsule_on(square, btVector3(0, -0.005f, 0), btVector3(0, 0.03f, 0.01f));
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(c->distance, -0.005f - kRadius, 1e-5);
    EXPECT_NEAR(c->normal.y(), 1.0, 1e-5);
}

// Beyond the square's rim the nearest point is on its edge, and past reach there is none.
TEST(TriangleContact, BeyondTheRimTheEdgeIsNearestAndPastReachNothing) {
    const Square square(true);
    const auto rim =
        mesh_ball_contact(btVector3(0.11f, 0.0f, 0.0f), kRadius, square.shape(),
                          btTransform::getIdentity(), kReach, btVector3(0.2f, 0.1f, 0));
    ASSERT_TRUE(rim.has_value());
    EXPECT_NEAR(rim->distance, 0.01f - kRadius, 1e-5);
    EXPECT_NEAR(rim->normal.x(), 1.0, 1e-5);
    EXPECT_FALSE(mesh_ball_contact(btVector3(0, 0.05f, 0), kRadius, square.shape(),
                                   btTransform::getIdentity(), kReach, btVector3(0, 0.1f, 0))
                     .has_value());
}

}  // namespace
}  // namespace physhand
