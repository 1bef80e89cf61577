#pragma once

#include <cstdint>
#include <vector>

#include "scene.h"

namespace physhand::sample {

struct Vertex {
    float position[3];
    float normal[3];
};

// Where a mesh lies in the shared vertex and index buffers.
struct MeshRange {
    std::uint32_t first_index = 0;
    std::uint32_t index_count = 0;
    std::int32_t vertex_offset = 0;
};

// Every mesh the sample draws, in one vertex and one index list.
class MeshSet {
  public:
    // A collider's shape in its own frame, at its size. A plane is a 20 m square around
    // the point nearest the frame's origin; a convex hull is drawn as its bounding box (the
    // sample builds no hulls: no paper scene has one).
    MeshRange add_shape(const Shape& shape);
    // A sphere of radius 1, a cylinder of radius 1 along Y from -1 to 1, and a cube from -1
    // to 1, to be scaled.
    MeshRange add_unit_sphere();
    MeshRange add_unit_cylinder();
    MeshRange add_unit_box();

    const std::vector<Vertex>& vertices() const { return vertices_; }
    const std::vector<std::uint32_t>& indices() const { return indices_; }

  private:
    MeshRange add_box(const Vec3& half_extents, const Vec3& centre);
    MeshRange add_capsule(double radius, double half_height);
    MeshRange add_cylinder(double radius, double half_height);
    // Starts a mesh; vertices and indices pushed until finish() belong to it.
    void begin();
    MeshRange finish();
    std::uint32_t vertex(const Vec3& position, const Vec3& normal);
    void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d);

    std::vector<Vertex> vertices_;
    std::vector<std::uint32_t> indices_;
    std::size_t first_vertex_ = 0;
    std::size_t first_index_ = 0;
};

}  // namespace physhand::sample
