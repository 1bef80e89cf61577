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
// toward 0 far away, so the depth test is GREATER and the buffer clears to 0. Reversed
// depth keeps float and 16-bit depth precise at arm's length.
Mat4 view_projection(const Eye& eye);

}  // namespace physhand::overlay
