#include "hand_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace physhand::overlay {

CapsuleMesh build_capsule_mesh(int segments, int rings_per_cap) {
    // Rings run from the first end's pole (z = -1) to its equator, then from the second
    // end's equator to its pole (z = +1); the band between the equators is the side.
    const int ring_count = 2 * (rings_per_cap + 1);
    CapsuleMesh mesh;
    mesh.vertices.reserve(static_cast<size_t>(ring_count * segments));
    for (int ring = 0; ring < ring_count; ++ring) {
        const bool second = ring > rings_per_cap;
        const int k = second ? ring - (rings_per_cap + 1) : ring;
        const double theta = 0.5 * std::numbers::pi * k / rings_per_cap;
        const double radial = second ? std::cos(theta) : std::sin(theta);
        const double z = second ? std::sin(theta) : -std::cos(theta);
        for (int s = 0; s < segments; ++s) {
            const double phi = 2.0 * std::numbers::pi * s / segments;
            mesh.vertices.push_back({{static_cast<float>(radial * std::cos(phi)),
                                      static_cast<float>(radial * std::sin(phi)),
                                      static_cast<float>(z), second ? 1.0f : 0.0f}});
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

float srgb_to_linear(float encoded) {
    const float c = std::clamp(encoded, 0.0f, 1.0f);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

namespace {

bool usable(const Joints& joints, int j) {
    const Vec3& p = joints.positions[j];
    const float r = joints.radii[j];
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(r) &&
           r > 0.0f;
}

std::array<float, 4> sphere(const Vec3& centre, float radius) {
    return {centre.x, centre.y, centre.z, radius};
}

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
    // Joints exactly as in `hidden_by`, and bones between two such, are skipped.
    const Joints* hidden_by = nullptr;
};

// Appends the layer's instances at out[count...] and returns the new count.
uint32_t append_hand(const Frame& frame, const HandLayer& layer,
                     std::span<CapsuleInstance, kMaxInstances> out, uint32_t count) {
    const Joints& joints = layer.joints;
    const auto hidden = [&](int j) {
        return layer.hidden_by != nullptr && same(joints, *layer.hidden_by, j);
    };
    const auto tinted = [&](int j) { return layer.tinted != nullptr && (*layer.tinted)[j]; };
    for (int j = 0; j < kJointCount; ++j) {
        if (usable(joints, j) && !hidden(j)) {
            const auto centre = sphere(joints.positions[j], joints.radii[j]);
            out[count++] = {centre, centre, tinted(j) ? layer.tint : layer.color};
        }
    }
    const float scale = frame.settings.bone_radius_scale;
    const bool bones = std::isfinite(scale) && scale > 0.0f;
    for (int j = 0; bones && j < kJointCount; ++j) {
        const int parent = frame.parents[j];
        if (parent < 0 || parent >= kJointCount || parent == j || !usable(joints, j) ||
            !usable(joints, parent) || (hidden(j) && hidden(parent))) {
            continue;
        }
        // A bone touches what either of its end joints touches.
        out[count++] = {sphere(joints.positions[parent], scale * joints.radii[parent]),
                        sphere(joints.positions[j], scale * joints.radii[j]),
                        tinted(j) || tinted(parent) ? layer.tint : layer.color};
    }
    return count;
}

}  // namespace

DrawCounts build_instances(const Frame& frame, std::span<CapsuleInstance, kMaxInstances> out) {
    const Settings& settings = frame.settings;
    uint32_t count = 0;
    for (size_t side = 0; side < frame.hands.size(); ++side) {
        const Hand& hand = frame.hands[side];
        if (hand.physical_active) {
            count = append_hand(frame,
                                {.joints = hand.physical,
                                 .color = linear(settings.hand_colors[side], 1.0f),
                                 .tinted = settings.tint ? &hand.in_contact : nullptr,
                                 .tint = linear(settings.contact_tint, 1.0f)},
                                out, count);
        }
    }
    const uint32_t physical_count = count;
    const float ghost_alpha = std::clamp(settings.ghost_alpha, 0.0f, 1.0f);
    for (size_t side = 0; side < frame.hands.size(); ++side) {
        const Hand& hand = frame.hands[side];
        if (hand.ghost_active && ghost_alpha > 0.0f) {
            count = append_hand(frame,
                                {.joints = hand.ghost,
                                 .color = linear(settings.hand_colors[side], ghost_alpha),
                                 .hidden_by = hand.physical_active ? &hand.physical : nullptr},
                                out, count);
        }
    }
    return {.physical = physical_count, .ghost = count - physical_count};
}

}  // namespace physhand::overlay
