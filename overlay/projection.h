#pragma once

#include <array>

#include "overlay_renderer.h"

namespace physhand::overlay {

// Column-major, as GLSL reads a mat4.
using Mat4 = std::array<float, 16>;

// Nearest distance drawn; a hand joint closer than this to the eye is clipped.
inline constexpr float kNearZ = 0.01f;

// World-to-clip transform of an eye for Vulkan clip space (+Y down, depth in [0, 1]) with
// reversed, infinite-far depth: depth = kNearZ / distance, 1 at the near plane, falling
// toward 0 far away, so the depth test is GREATER and the buffer clears to 0. With a
// floating-point depth buffer this keeps about the same relative precision at every
// distance (float's steps shrink toward 0 as 1/distance does); fixed-point formats (16-
// and 24-bit) have evenly spaced steps either way, so reversing gains them nothing.
Mat4 view_projection(const Eye& eye);

}  // namespace physhand::overlay
