#pragma once

// CPU side of the drawing: the one mesh every joint and bone is drawn with, and the
// per-primitive instance data built from a frame's hands.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "overlay_renderer.h"

namespace physhand::overlay {

// A vertex of the two shared meshes. Capsule mesh: xyz of `local` is the unit direction
// from the centre of one end (z along the axis toward the second end), w selects the end (0
// first, 1 second); the vertex shader places vertex = centre[w] + radius[w] * xyz, so a
// capsule with both ends at one point is a sphere and one mesh serves joints and bones.
// Box mesh: xyz is a corner of the unit cube (each coordinate +-1) and w is kBoxVertex;
// the shader scales it by the half extents and turns it. `normal` is the surface normal in
// the same frame (a capsule's equals its direction; a box's is its face's).
struct MeshVertex {
    std::array<float, 4> local;
    std::array<float, 4> normal;
};

inline constexpr float kBoxVertex = 2.0f;

struct Mesh {
    std::vector<MeshVertex> vertices;
    std::vector<uint16_t> indices;  // triangle list, counter-clockwise seen from outside
};

// `segments` around the axis, `rings_per_cap` from each pole to its equator.
Mesh build_capsule_mesh(int segments, int rings_per_cap);
// Six faces of four vertices each, so that each face has its own normal.
Mesh build_box_mesh();

// One joint (both ends equal), bone or capsule: end centres and radii; or one box: centre
// in start, half extents in end, unit quaternion (xyzw) in orientation. Colour linear,
// alpha not premultiplied.
struct PrimitiveInstance {
    std::array<float, 4> start;  // xyz centre, w radius
    std::array<float, 4> end;
    std::array<float, 4> orientation;
    std::array<float, 4> color;
};

// Per hand: ghost and physical, each 26 joints and at most 26 bones.
inline constexpr int kMaxInstances = 2 * 2 * 2 * kJointCount;

// The instances are written physical capsules first, then physical boxes (both opaque),
// then the ghost (translucent capsules).
struct DrawCounts {
    uint32_t physical_capsules = 0;
    uint32_t physical_boxes = 0;
    uint32_t ghost = 0;
    uint32_t total() const { return physical_capsules + physical_boxes + ghost; }
};

// The ghost's joints and bones are drawn this much thinner than the physical hand's, so
// that where the two coincide the ghost lies inside the physical hand, and where they part
// it reads as a thinner, see-through hand.
inline constexpr float kGhostThickness = 0.6f;

// Joints with a non-finite centre or a non-positive radius, and bones touching one or
// with an invalid parent index, are left out (tracking loss must not draw garbage), and so
// are solids with a non-finite or non-positive size or place. Ghost joints and bones
// exactly where their physical counterparts are drawn are left out too: without contact
// that is the whole ghost.
DrawCounts build_instances(const Frame& frame, std::span<PrimitiveInstance, kMaxInstances> out);

float srgb_to_linear(float encoded);

}  // namespace physhand::overlay
