#pragma once

// The overlay renderer: draws the ghost hands and the physical hands (contact joints
// tinted) into images the caller owns, with the caller's Vulkan device and queue. It
// knows nothing of OpenXR or physics: everything arrives in the plain structs below.
//
// Output: premultiplied-alpha colour over a transparent background (alpha 0 where no
// hand is). As an OpenXR projection layer: XR_COMPOSITION_LAYER_BLEND_TEXTURE_SOURCE_ALPHA_BIT
// set, XR_COMPOSITION_LAYER_UNPREMULTIPLIED_ALPHA_BIT not set.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <span>

namespace physhand::overlay {

inline constexpr int kJointCount = 26;

struct Vec3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;
};
struct Quat {
    float x = 0.0f, y = 0.0f, z = 0.0f, w = 1.0f;
};
// Colours are sRGB-encoded display values in [0, 1], as a user would pick them.
struct Color {
    float r = 0.0f, g = 0.0f, b = 0.0f;
};

// An eye: pose of the view in the caller's space (OpenXR view axes: -Z forward, +Y up;
// unit quaternion) and field of view in radians (OpenXR convention: angleLeft and
// angleDown negative), as XrView gives them.
struct Eye {
    Vec3 position;
    Quat orientation;
    float angle_left = 0.0f, angle_right = 0.0f, angle_up = 0.0f, angle_down = 0.0f;
};

// One view to draw: its eye and one layer of a target image. The image has the
// renderer's colour format, COLOR_ATTACHMENT usage and at least `extent`; every pixel of
// `extent` is overwritten, whatever the image held (its layout on entry does not matter).
struct View {
    Eye eye;
    VkImage image = VK_NULL_HANDLE;
    uint32_t array_layer = 0;
    VkExtent2D extent{};
};

// Joint centres (in the same space as the eyes) and sphere radii, in metres.
struct Joints {
    std::array<Vec3, kJointCount> positions{};
    std::array<float, kJointCount> radii{};
};

// A part of the physical hand as it collides, in the eyes' space: a capsule (the centres of
// its two ends and its radius; a sphere where they coincide) or a box.
struct Solid {
    enum class Kind { Capsule, Box };
    Kind kind = Kind::Capsule;
    Vec3 start, end;  // capsule: the ends' centres; box: its centre in start
    float radius = 0.0f;
    Quat orientation;   // box
    Vec3 half_extents;  // box
    bool in_contact = false;
};

inline constexpr int kMaxSolids = kJointCount;

// Joints with a non-finite centre or a radius <= 0 are not drawn, nor their bones; solids
// with a non-finite or non-positive size or place are not drawn. The ghost is drawn thinner
// than the joints' radii, lit at its rim, and only where it differs from the physical
// hand's joints.
struct Hand {
    bool ghost_active = false;     // draw the ghost (tracked) hand, translucent
    bool physical_active = false;  // draw the physical (simulated) hand, opaque
    Joints ghost;
    Joints physical;
    // The physical hand is drawn as these, the shapes that collide, each tinted where it
    // touches; a caller that knows only the joints leaves them out, and the physical joints
    // and bones are drawn instead, tinted as `in_contact` says.
    std::array<Solid, kMaxSolids> solids{};
    uint32_t solid_count = 0;
    std::array<bool, kJointCount> in_contact{};  // physical joint touches something
};

struct Settings {
    std::array<Color, 2> hand_colors{{{0.9f, 0.15f, 0.15f}, {0.15f, 0.8f, 0.2f}}};  // left, right
    Color contact_tint{0.55f, 0.8f, 1.0f};
    float ghost_alpha = 0.6f;  // at the ghost's outline; a quarter of it where it faces the eye
    bool tint = true;
    float bone_radius_scale = 0.6f;  // bone radius at each end = scale x that joint's radius
};

struct Frame {
    std::span<const View> views;
    std::array<Hand, 2> hands;  // left, right
    // Parent joint of each joint, -1 for a root: one bone is drawn per joint with a parent.
    std::array<int, kJointCount> parents{};
    Settings settings;
    // Layout the target images are left in (OpenXR swapchain images: colour attachment).
    VkImageLayout final_layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
};

struct CreateInfo {
    // Optional. With it, physical-device queries go through get_instance_proc_addr(instance)
    // (null: the linked loader's); without it, through the linked loader's exports.
    // Device functions always come from vkGetDeviceProcAddr(device).
    VkInstance instance = VK_NULL_HANDLE;
    PFN_vkGetInstanceProcAddr get_instance_proc_addr = nullptr;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queue_family_index = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkFormat color_format = VK_FORMAT_R8G8B8A8_SRGB;  // format of the target images
    // Format of the renderer's own depth buffer; VK_FORMAT_UNDEFINED picks one. It and a
    // colour buffer, both 4x multisampled, are as large as the largest view: 32 bytes a
    // pixel with 32-bit depth.
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
    bool gpu_timestamps = false;  // measure GPU time per frame with a query pool
};

struct Timings {
    double cpu_ms = 0.0;  // the last render() call, on the calling thread
    // GPU time of the newest frame seen complete (when render() reuses its slot, or by
    // wait_idle()); -1 without gpu_timestamps or when the queue cannot time.
    double gpu_ms = -1.0;
    // Frames whose GPU time has been read: gpu_ms is a new frame's whenever this grows.
    uint64_t gpu_frames = 0;
};

// The most pixels the overlay draws a view with: its 4x multisampled colour and depth, 8
// bytes a sample, then take at most 40 MB (1052 x 1140 for a headset's 2064 x 2208 view).
// A larger view is drawn smaller, and the runtime scales the layer up to it.
inline constexpr uint64_t kMaxDrawnPixels = 1'200'000;
// The size the overlay draws a view of `view` pixels at: that size, or both sides scaled
// alike to at most kMaxDrawnPixels.
VkExtent2D drawn_extent(VkExtent2D view);

// Not thread-safe; the caller synchronises access to the queue (as OpenXR requires of
// the app around xrEndFrame). A failed Vulkan call throws std::runtime_error naming it
// and its VkResult; null handles or an empty view throw std::invalid_argument.
class Renderer {
  public:
    explicit Renderer(const CreateInfo& info);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Records and submits one frame on the queue (one render pass per view, views in
    // order). Returns false, with no GPU work and the images untouched, when there is
    // nothing to draw: no active hand with a drawable joint, or no view (then submit no
    // overlay layer). The first frame into a new image waits for the frames in flight.
    bool render(const Frame& frame);

    // Blocks until every submitted frame has finished on the GPU.
    void wait_idle();

    // Drops what the renderer caches for `image` (views, framebuffers) after waiting for
    // its frames; call before the image is destroyed (xrDestroySwapchain).
    void forget_image(VkImage image);

    Timings timings() const;
    // The device memory the renderer holds (its attachments and buffers, not the images it
    // draws into), bytes.
    uint64_t memory_bytes() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace physhand::overlay
