#pragma once

#include <optional>
#include <span>

#include "collider.h"
#include "json_node.h"

// The COLLIDER syntax (docs/scene-format.md), the one unit that reads colliders for scene
// files and for the layer's config alike.
namespace physhand::syntax {

// The unit quaternion of [x, y, z, w], or nullopt for one too short to have a direction.
std::optional<Quat> unit_quaternion(double x, double y, double z, double w);
Quat read_quaternion(const Node& node);
Pose read_pose(const Node& node);
// Three numbers > 0.
Vec3 read_half_extents(const Node& node);
// A collider; its id must differ from those of `earlier`. Throws FormatError naming the
// node's path, also for a collider the simulation would refuse.
Collider read_collider(const Node& node, std::span<const Collider> earlier);

}  // namespace physhand::syntax
