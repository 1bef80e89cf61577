#pragma once

// CPU side of the drawing: the one mesh every joint and bone is drawn with, and the
// per-primitive instance data built from a frame's hands.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "overlay_renderer.h"

namespace physhand::overlay {

// A capsule in its own frame: xyz is the unit direction from the centre of one end
// (z along the axis toward the second end), w selects the end (0 first, 1 second). The
// vertex shader places vertex = centre[w] + radius[w] * xyz, so a capsule with both ends
// at one point is a sphere and one mesh serves joints and bones.
struct MeshVertex {
    std::array<float, 4> local;
};

struct CapsuleMesh {
    std::vector<MeshVertex> vertices;
    std::vector<uint16_t> indices;  // triangle list, counter-clockwise seen from outside
};

// `segments` around the axis, `rings_per_cap` from each pole to its equator.
CapsuleMesh build_capsule_mesh(int segments, int rings_per_cap);

// One joint (both ends equal) or bone: end centres and radii, linear colour and alpha.
struct CapsuleInstance {
    std::array<float, 4> start;  // xyz centre, w radius
    std::array<float, 4> end;
    std::array<float, 4> color;  // linear rgb, alpha (not premultiplied)
};

// Per hand: ghost and physical, each 26 joints and at most 26 bones.
inline constexpr int kMaxInstances = 2 * 2 * 2 * kJointCount;

// The instances are written physical first (opaque), then ghost (translucent).
struct DrawCounts {
    uint32_t physical = 0;
    uint32_t ghost = 0;
};

// Joints with a non-finite centre or a non-positive radius, and bones touching one or
// with an invalid parent index, are left out (tracking loss must not draw garbage).
// Ghost joints and bones exactly where their physical counterparts are drawn are left
// out too: the physical hand hides them (pipeline.h), and without contact that is the
// whole ghost.
DrawCounts build_instances(const Frame& frame, std::span<CapsuleInstance, kMaxInstances> out);

float srgb_to_linear(float encoded);

}  // namespace physhand::overlay
