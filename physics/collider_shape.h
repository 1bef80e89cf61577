#pragma once

#include <memory>

#include "collider.h"

class btCollisionShape;
class btTriangleIndexVertexArray;

namespace physhand {

// A Bullet shape and whatever it borrows memory from (mesh data).
struct ColliderShape {
    std::unique_ptr<btCollisionShape> shape;
    std::unique_ptr<btTriangleIndexVertexArray> mesh_interface;
    std::vector<float> mesh_vertices;
    std::vector<int> mesh_indices;

    ColliderShape();
    ~ColliderShape();
    ColliderShape(ColliderShape&&) noexcept;
    ColliderShape& operator=(ColliderShape&&) noexcept;
};

// Validates the collider (sizes > 0 and finite, mass rules, mesh/plane static) and builds
// its shape; throws std::invalid_argument naming the offending field.
ColliderShape make_collider_shape(const Collider& collider);
void validate_collider(const Collider& collider);

// Smallest half-size of the shape's local bounds, for CCD thresholds.
double min_half_extent(const btCollisionShape& shape);

}  // namespace physhand
