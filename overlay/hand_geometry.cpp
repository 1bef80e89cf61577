#include "hand_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace physhand::overlay {

Mesh build_capsule_mesh(int segments, int rings_per_cap) {
    // Rings run from the first end's pole (z = -1) to its equator, then from the second
    // end's equator to its pole (z = +1); the band between the equators is the side.
    const int ring_count = 2 * (rings_per_cap + 1);
    Mesh mesh;
    mesh.vertices.reserve(static_cast<size_t>(ring_count * segments));
    for (int ring = 0; ring < ring_count; ++ring) {
        const bool second = ring > rings_per_cap;
        const int k = second ? ring - (rings_per_cap + 1) : ring;
        const double theta = 0.5 * std::numbers::pi * k / rings_per_cap;
        const double radial = second ? std::cos(theta) : std::sin(theta);
        const double z = second ? std::sin(theta) : -std::cos(theta);
        for (int s = 0; s < segments; ++s) {
            const double phi = 2.0 * std::numbers::pi * s / segments;
            const std::array<float, 4> direction = {static_cast<float>(radial * std::cos(phi)),
                                                    static_cast<float>(radial * std::sin(phi)),
                                                    static_cast<float>(z), 0.0f};
            std::array<float, 4> local = direction;
            local[3] = second ? 1.0f : 0.0f;
            mesh.vertices.push_back({local, direction});
        }
    }
    const auto index = [segments](int ring, int s) {
        return static_cast<uint16_t>(ring * segments + s % segments);
    };
    for (int ring = 0; ring + 1 < ring_count; ++ring) {
        for (int s = 0; s < segments; ++s) {
            const uint16_t a = index(ring, s), b = index(ring, s + 1);
            const uint16_t c = index(ring + 1, s), d = index(ring + 1, s + 1);
            // At the poles one of the two triangles of the quad has no area.
            if (ring != 0) {
                mesh.indices.insert(mesh.indices.end(), {a, b, c});
            }
            if (ring + 2 != ring_count) {
                mesh.indices.insert(mesh.indices.end(), {b, d, c});
            }
        }
    }
    return mesh;
}

Mesh build_box_mesh() {
    Mesh mesh;
    for (int axis = 0; axis < 3; ++axis) {
        // (u, v, axis) is right-handed, so corners in this order run counter-clockwise seen
        // from the + face; the - face takes them reversed.
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (const float side : {1.0f, -1.0f}) {
            const auto first = static_cast<uint16_t>(mesh.vertices.size());
            std::array<float, 4> normal{};
            normal[axis] = side;
            for (const auto& [a, b] :
                 {std::pair{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}}) {
                std::array<float, 4> corner{};
                corner[axis] = side;
                corner[u] = a;
                corner[v] = side * b;
                corner[3] = kBoxVertex;
                mesh.vertices.push_back({corner, normal});
            }
            mesh.indices.insert(
                mesh.indices.end(),
                {first, static_cast<uint16_t>(first + 1), static_cast<uint16_t>(first + 2), first,
                 static_cast<uint16_t>(first + 2), static_cast<uint16_t>(first + 3)});
        }
    }
    return mesh;
}

float srgb_to_linear(float encoded) {
    const float c = std::clamp(encoded, 0.0f, 1.0f);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

namespace {

bool finite(const Vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

bool usable(const Joints& joints, int j) {
    const float r = joints.radii[j];
    return finite(joints.positions[j]) && std::isfinite(r) && r > 0.0f;
}

bool usable(const Solid& solid) {
    if (solid.kind == Solid::Kind::Capsule) {
        return finite(solid.start) && finite(solid.end) && std::isfinite(solid.radius) &&
               solid.radius > 0.0f;
    }
    const Vec3& h = solid.half_extents;
    const Quat& q = solid.orientation;
    const float norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    return finite(solid.start) && finite(h) && h.x > 0.0f && h.y > 0.0f && h.z > 0.0f &&
           std::isfinite(norm) && norm > 0.5f;
}

std::array<float, 4> sphere(const Vec3& centre, float radius) {
    return {centre.x, centre.y, centre.z, radius};
}

constexpr std::array<float, 4> kNoTurn = {0.0f, 0.0f, 0.0f, 1.0f};

std::array<float, 4> linear(const Color& color, float alpha) {
    return {srgb_to_linear(color.r), srgb_to_linear(color.g), srgb_to_linear(color.b), alpha};
}

bool same(const Joints& a, const Joints& b, int j) {
    const Vec3 &p = a.positions[j], &q = b.positions[j];
    return p.x == q.x && p.y == q.y && p.z == q.z && a.radii[j] == b.radii[j];
}

// One hand's joints and bones in one look.
struct HandLayer {
    const Joints& joints;
    std::array<float, 4> color;
    const std::array<bool, kJointCount>* tinted = nullptr;  // these joints take `tint`
    std::array<float, 4> tint{};
    float thickness = 1.0f;  // of joints and bones, times their radii
    // Joints exactly as in `hidden_by`, and bones between two such, are skipped.
    const Joints* hidden_by = nullptr;
};

// Appends the layer's instances at out[count...] and returns the new count.
uint32_t append_joints(const Frame& frame, const HandLayer& layer,
                       std::span<PrimitiveInstance, kMaxInstances> out, uint32_t count) {
    const Joints& joints = layer.joints;
    const auto hidden = [&](int j) {
        return layer.hidden_by != nullptr && same(joints, *layer.hidden_by, j);
    };
    const auto tinted = [&](int j) { return layer.tinted != nullptr && (*layer.tinted)[j]; };
    for (int j = 0; j < kJointCount; ++j) {
        if (usable(joints, j) && !hidden(j)) {
            const auto centre = sphere(joints.positions[j], layer.thickness * joints.radii[j]);
            out[count++] = {centre, centre, kNoTurn, tinted(j) ? layer.tint : layer.color};
        }
    }
    const float scale = layer.thickness * frame.settings.bone_radius_scale;
    const bool bones = std::isfinite(scale) && scale > 0.0f;
    for (int j = 0; bones && j < kJointCount; ++j) {
        const int parent = frame.parents[j];
        if (parent < 0 || parent >= kJointCount || parent == j || !usable(joints, j) ||
            !usable(joints, parent) || (hidden(j) && hidden(parent))) {
            continue;
        }
        // A bone touches what either of its end joints touches.
        out[count++] = {sphere(joints.positions[parent], scale * joints.radii[parent]),
                        sphere(joints.positions[j], scale * joints.radii[j]), kNoTurn,
                        tinted(j) || tinted(parent) ? layer.tint : layer.color};
    }
    return count;
}

// Appends the hand's solids of one kind.
uint32_t append_solids(const Hand& hand, Solid::Kind kind, const std::array<float, 4>& color,
                       const std::array<float, 4>* tint,
                       std::span<PrimitiveInstance, kMaxInstances> out, uint32_t count) {
    const uint32_t solids = std::min<uint32_t>(hand.solid_count, kMaxSolids);
    for (uint32_t i = 0; i < solids; ++i) {
        const Solid& solid = hand.solids[i];
        if (solid.kind != kind || !usable(solid)) continue;
        const std::array<float, 4>& look = tint != nullptr && solid.in_contact ? *tint : color;
        if (kind == Solid::Kind::Capsule) {
            out[count++] = {sphere(solid.start, solid.radius), sphere(solid.end, solid.radius),
                            kNoTurn, look};
        } else {
            const Quat& q = solid.orientation;
            const Vec3& h = solid.half_extents;
            out[count++] = {
                sphere(solid.start, 0.0f), {h.x, h.y, h.z, 0.0f}, {q.x, q.y, q.z, q.w}, look};
        }
    }
    return count;
}

}  // namespace

DrawCounts build_instances(const Frame& frame, std::span<PrimitiveInstance, kMaxInstances> out) {
    const Settings& settings = frame.settings;
    const std::array<float, 4> tint = linear(settings.contact_tint, 1.0f);
    const std::array<float, 4>* tint_or_none = settings.tint ? &tint : nullptr;
    DrawCounts counts;
    uint32_t count = 0;
    for (size_t side = 0; side < frame.hands.size(); ++side) {
        const Hand& hand = frame.hands[side];
        if (!hand.physical_active) continue;
        const std::array<float, 4> color = linear(settings.hand_colors[side], 1.0f);
        if (hand.solid_count > 0) {
            count = append_solids(hand, Solid::Kind::Capsule, color, tint_or_none, out, count);
        } else {
            count = append_joints(frame,
                                  {.joints = hand.physical,
                                   .color = color,
                                   .tinted = settings.tint ? &hand.in_contact : nullptr,
                                   .tint = tint},
                                  out, count);
        }
    }
    counts.physical_capsules = count;
    for (size_t side = 0; side < frame.hands.size(); ++side) {
        const Hand& hand = frame.hands[side];
        if (hand.physical_active && hand.solid_count > 0) {
            count = append_solids(hand, Solid::Kind::Box, linear(settings.hand_colors[side], 1.0f),
                                  tint_or_none, out, count);
        }
    }
    counts.physical_boxes = count - counts.physical_capsules;
    const float ghost_alpha = std::clamp(settings.ghost_alpha, 0.0f, 1.0f);
    for (size_t side = 0; side < frame.hands.size(); ++side) {
        const Hand& hand = frame.hands[side];
        if (hand.ghost_active && ghost_alpha > 0.0f) {
            count = append_joints(frame,
                                  {.joints = hand.ghost,
                                   .color = linear(settings.hand_colors[side], ghost_alpha),
                                   .thickness = kGhostThickness,
                                   .hidden_by = hand.physical_active ? &hand.physical : nullptr},
                                  out, count);
        }
    }
    counts.ghost = count - counts.physical_capsules - counts.physical_boxes;
    return counts;
}

}  // namespace physhand::overlay
