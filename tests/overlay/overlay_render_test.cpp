// Renders known hands with a known camera on a real Vulkan device (lavapipe in CI) and
// checks the pixels. Camera: at the origin looking down -Z, 45 degree field of view,
// 256 x 256 pixels; joints 50 cm away, so a 2 cm radius spans about 12 pixels.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "headless_vulkan.h"
#include "overlay_renderer.h"
#include "physics_hands.h"

namespace physhand::overlay {
namespace {

using testing::HeadlessVulkan;
using testing::OffscreenImage;
using testing::Pixels;
using testing::Rgba;
using testing::ValidationMessages;

constexpr VkExtent2D kExtent{256, 256};
constexpr float kHalfFov = 22.5f * std::numbers::pi_v<float> / 180.0f;
constexpr VkImageLayout kAttachment = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;

constexpr Color kLeftColor{0.9f, 0.15f, 0.15f};
constexpr Color kRightColor{0.15f, 0.8f, 0.2f};
constexpr Color kTint{0.55f, 0.8f, 1.0f};
constexpr float kGhostAlpha = 0.35f;
// Where the ghost faces the eye it shows this share of its alpha (ghost.frag), and its
// joints are drawn kGhostThickness times their radii (hand_geometry.h).
constexpr float kGhostCentreAlpha = kGhostAlpha * 0.25f;
constexpr float kGhostThickness = 0.6f;

// At a joint's centre the surface faces the eye, so it shows its full colour; the
// tessellation and the half-pixel offset of the sample darken it by well under 1%.
constexpr int kTolerance = 4;

// The sRGB transfer functions, written here again so that the test does not trust the
// renderer's own.
float decode(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
int encode(float linear) {
    const float c =
        linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return static_cast<int>(std::lround(c * 255.0f));
}

// `top` with alpha `alpha` over `bottom` (opacity `bottom_alpha`), premultiplied.
Rgba over(Color top, float alpha, Color bottom, float bottom_alpha) {
    const auto channel = [&](float t, float b) {
        return encode(decode(t) * alpha + decode(b) * bottom_alpha * (1.0f - alpha));
    };
    return {channel(top.r, bottom.r), channel(top.g, bottom.g), channel(top.b, bottom.b),
            static_cast<int>(std::lround((alpha + bottom_alpha * (1.0f - alpha)) * 255.0f))};
}
Rgba opaque(Color color) {
    return over(color, 1.0f, {}, 0.0f);
}
Rgba translucent(Color color, float alpha) {
    return over(color, alpha, {}, 0.0f);
}

::testing::AssertionResult near(const Rgba& actual, const Rgba& expected) {
    const bool ok = std::abs(actual.r - expected.r) <= kTolerance &&
                    std::abs(actual.g - expected.g) <= kTolerance &&
                    std::abs(actual.b - expected.b) <= kTolerance &&
                    std::abs(actual.a - expected.a) <= kTolerance;
    if (ok) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure()
           << "pixel (" << actual.r << ", " << actual.g << ", " << actual.b << ", " << actual.a
           << "), expected (" << expected.r << ", " << expected.g << ", " << expected.b << ", "
           << expected.a << ") +-" << kTolerance;
}

struct PixelPosition {
    uint32_t x, y;
};

// Pixel under a point, for an eye at `eye_x` on the X axis looking down -Z.
PixelPosition project(Vec3 p, float eye_x = 0.0f) {
    const float t = std::tan(kHalfFov);
    const float u = ((p.x - eye_x) / -p.z / t + 1.0f) * 0.5f * kExtent.width;
    const float v = (1.0f - p.y / -p.z / t) * 0.5f * kExtent.height;
    return {static_cast<uint32_t>(u), static_cast<uint32_t>(v)};
}

// Radius in pixels of a sphere seen straight ahead (close enough near the centre).
float projected_radius(Vec3 p, float r) {
    return r / -p.z / std::tan(kHalfFov) * 0.5f * kExtent.width;
}

void put_joint(Joints& joints, int j, Vec3 position, float radius) {
    joints.positions[j] = position;
    joints.radii[j] = radius;
}

class OverlayRenderTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string reason;
        vulkan_ = HeadlessVulkan::create(true, &messages_, reason);
        ASSERT_NE(vulkan_, nullptr) << "no Vulkan device can be created: " << reason;
        if (!vulkan_->validating()) {
            ASSERT_FALSE(PHYSHAND_VULKAN_VALIDATION_REQUIRED)
                << "VK_LAYER_KHRONOS_validation, which the build found, is not active";
            std::cout << "note: VK_LAYER_KHRONOS_validation not installed; running without\n";
        }
        make_renderer(VK_FORMAT_R8G8B8A8_SRGB, false);
        target_ = new_target(VK_FORMAT_R8G8B8A8_SRGB, 1);
        views_ = {camera(0.0f, 0)};
        frame_.views = views_;
        frame_.parents.fill(-1);
        frame_.settings.hand_colors = {kLeftColor, kRightColor};
        frame_.settings.contact_tint = kTint;
        frame_.settings.ghost_alpha = kGhostAlpha;
    }

    void TearDown() override {
        if (!vulkan_) {
            return;
        }
        renderer_.reset();
        for (OffscreenImage& image : images_) {
            vulkan_->destroy_image(image);
        }
        vulkan_.reset();  // validation reports leaked objects at vkDestroyDevice
        std::ostringstream text;
        for (const std::string& message : messages_.take()) {
            text << "\n  " << message;
        }
        EXPECT_TRUE(text.str().empty()) << "validation messages:" << text.str();
    }

    void make_renderer(VkFormat format, bool timestamps) {
        renderer_.reset();
        CreateInfo info;
        info.instance = vulkan_->instance();
        info.physical_device = vulkan_->physical_device();
        info.device = vulkan_->device();
        info.queue_family_index = vulkan_->queue_family();
        info.queue = vulkan_->queue();
        info.color_format = format;
        info.gpu_timestamps = timestamps;
        renderer_ = std::make_unique<Renderer>(info);
    }

    // Like an OpenXR swapchain image after xrWaitSwapchainImage: colour-attachment
    // layout, stale contents (a colour no test expects).
    OffscreenImage& new_target(VkFormat format, uint32_t layers) {
        OffscreenImage& image =
            images_.emplace_back(vulkan_->create_image(format, kExtent, layers));
        vulkan_->fill(image, {0.3f, 0.1f, 0.7f, 0.6f}, kAttachment);
        return image;
    }

    View camera(float eye_x, uint32_t layer) const {
        View view;
        view.eye.position = {eye_x, 0.0f, 0.0f};
        view.eye.angle_left = -kHalfFov;
        view.eye.angle_right = kHalfFov;
        view.eye.angle_up = kHalfFov;
        view.eye.angle_down = -kHalfFov;
        view.image = target_.image;
        view.array_layer = layer;
        view.extent = kExtent;
        return view;
    }

    Hand& left() { return frame_.hands[0]; }
    Hand& right() { return frame_.hands[1]; }

    // Renders frame_ (which must show something) and reads layer `layer` back.
    Pixels draw(uint32_t layer = 0) {
        EXPECT_TRUE(renderer_->render(frame_));
        renderer_->wait_idle();
        return vulkan_->read(target_, layer, frame_.final_layout);
    }

    ValidationMessages messages_;
    std::unique_ptr<HeadlessVulkan> vulkan_;
    std::unique_ptr<Renderer> renderer_;
    std::vector<OffscreenImage> images_;  // destroyed in TearDown
    OffscreenImage target_;
    std::vector<View> views_;
    Frame frame_;
};

TEST_F(OverlayRenderTest, GhostOnlyJointIsTranslucentHandColourOverTransparent) {
    const Vec3 p{0.0f, 0.0f, -0.5f};
    left().ghost_active = true;
    put_joint(left().ghost, 0, p, 0.02f);
    const Pixels pixels = draw();
    const auto [x, y] = project(p);
    const Rgba centre = pixels.at(x, y);
    EXPECT_GT(centre.a, 0);
    EXPECT_LT(centre.a, 255);
    EXPECT_TRUE(near(centre, translucent(kLeftColor, kGhostCentreAlpha)));
}

TEST_F(OverlayRenderTest, TouchingPhysicalJointIsOpaqueTint) {
    const Vec3 touching{-0.06f, 0.0f, -0.5f}, untouched{0.06f, 0.0f, -0.5f};
    right().physical_active = true;
    put_joint(right().physical, 9, touching, 0.02f);
    put_joint(right().physical, 10, untouched, 0.02f);
    right().in_contact[9] = true;
    const Pixels pixels = draw();
    EXPECT_TRUE(near(pixels.at(project(touching).x, project(touching).y), opaque(kTint)));
    EXPECT_TRUE(near(pixels.at(project(untouched).x, project(untouched).y), opaque(kRightColor)));
}

TEST_F(OverlayRenderTest, TintOffKeepsTheHandColour) {
    const Vec3 p{0.0f, 0.0f, -0.5f};
    right().physical_active = true;
    put_joint(right().physical, 9, p, 0.02f);
    right().in_contact[9] = true;
    frame_.settings.tint = false;
    const Pixels pixels = draw();
    EXPECT_TRUE(near(pixels.at(project(p).x, project(p).y), opaque(kRightColor)));
}

TEST_F(OverlayRenderTest, EverythingAwayFromTheJointsIsTransparent) {
    const std::vector<Vec3> joints = {{-0.07f, 0.05f, -0.5f}, {0.08f, -0.03f, -0.4f}};
    left().physical_active = true;
    left().ghost_active = true;
    put_joint(left().physical, 0, joints[0], 0.02f);
    put_joint(left().ghost, 0, joints[1], 0.02f);
    const Pixels pixels = draw();
    int transparent = 0, covered = 0;
    for (uint32_t y = 0; y < kExtent.height; ++y) {
        for (uint32_t x = 0; x < kExtent.width; ++x) {
            bool near_joint = false;
            for (const Vec3& joint : joints) {
                const auto [jx, jy] = project(joint);
                const float dx = static_cast<float>(x) - static_cast<float>(jx);
                const float dy = static_cast<float>(y) - static_cast<float>(jy);
                near_joint |= std::hypot(dx, dy) < projected_radius(joint, 0.02f) + 2.0f;
            }
            const Rgba pixel = pixels.at(x, y);
            if (near_joint) {
                covered += pixel.a > 0;
            } else {
                ASSERT_EQ(pixel.r + pixel.g + pixel.b + pixel.a, 0)
                    << "at (" << x << ", " << y << ")";
                ++transparent;
            }
        }
    }
    EXPECT_GT(transparent, 60000);
    EXPECT_GT(covered, 500);  // both joints were drawn (about 2 x 300 + 470 pixels)
}

TEST_F(OverlayRenderTest, PhysicalJointInFrontHidesTheGhost) {
    // A larger ghost behind: hidden at the centre, visible in a ring around the joint.
    const Vec3 physical{0.0f, 0.0f, -0.5f}, ghost{0.0f, 0.0f, -0.6f};
    left().physical_active = true;
    left().ghost_active = true;
    put_joint(left().physical, 0, physical, 0.015f);
    put_joint(left().ghost, 0, ghost, 0.04f / kGhostThickness);
    const Pixels pixels = draw();
    const auto [x, y] = project(physical);
    EXPECT_TRUE(near(pixels.at(x, y), opaque(kLeftColor)));
    const uint32_t ring = x + static_cast<uint32_t>(projected_radius(physical, 0.015f)) + 4;
    const Rgba around = pixels.at(ring, y);
    EXPECT_GT(around.a, 0);
    EXPECT_LT(around.a, 255);
}

TEST_F(OverlayRenderTest, GhostInFrontIsBlendedOverThePhysicalJoint) {
    // A tinted physical joint inside a larger ghost: the eye sees the ghost's near side
    // first (this fails if back faces were drawn instead of front faces).
    const Vec3 p{0.0f, 0.0f, -0.5f};
    left().physical_active = true;
    left().ghost_active = true;
    put_joint(left().physical, 0, p, 0.01f);
    left().in_contact[0] = true;
    put_joint(left().ghost, 0, p, 0.03f / kGhostThickness);
    const Pixels pixels = draw();
    EXPECT_TRUE(near(pixels.at(project(p).x, project(p).y),
                     over(kLeftColor, kGhostCentreAlpha, kTint, 1.0f)));
}

TEST_F(OverlayRenderTest, GhostWhereThePhysicalJointIsLeavesItUntouched) {
    // No contact pressed the ghost away: both are at the same place, and the tint must
    // show unblended.
    const Vec3 p{0.0f, 0.0f, -0.5f};
    right().physical_active = true;
    right().ghost_active = true;
    put_joint(right().physical, 5, p, 0.02f);
    put_joint(right().ghost, 5, p, 0.02f);
    right().in_contact[5] = true;
    const Pixels pixels = draw();
    EXPECT_TRUE(near(pixels.at(project(p).x, project(p).y), opaque(kTint)));
}

TEST_F(OverlayRenderTest, OverlappingGhostPartsBlendOnce) {
    // Two ghost joints overlapping on screen: one translucent layer, not two.
    left().ghost_active = true;
    put_joint(left().ghost, 1, {0.0f, 0.0f, -0.5f}, 0.03f);
    put_joint(left().ghost, 2, {0.01f, 0.0f, -0.52f}, 0.03f);
    const Pixels pixels = draw();
    const auto [x, y] = project({0.005f, 0.0f, -0.5f});
    EXPECT_NEAR(pixels.at(x, y).a, std::lround(kGhostCentreAlpha * 255.0f), kTolerance);
}

TEST_F(OverlayRenderTest, BonesJoinAJointToItsParent) {
    const Vec3 a{-0.06f, 0.0f, -0.5f}, b{0.06f, 0.0f, -0.5f}, middle{0.0f, 0.0f, -0.5f};
    right().physical_active = true;
    put_joint(right().physical, 6, a, 0.015f);
    put_joint(right().physical, 7, b, 0.015f);
    const auto [x, y] = project(middle);
    EXPECT_EQ(draw().at(x, y).a, 0) << "no parent, no bone";
    frame_.parents[7] = 6;
    EXPECT_TRUE(near(draw().at(x, y), opaque(kRightColor)));
}

TEST_F(OverlayRenderTest, EdgesAreAntialiased) {
    const Vec3 p{0.0f, 0.0f, -0.5f};
    left().physical_active = true;
    put_joint(left().physical, 0, p, 0.02f);
    const Pixels pixels = draw();
    const auto [x, y] = project(p);
    int partial = 0;
    for (uint32_t column = 0; column < kExtent.width; ++column) {
        const int a = pixels.at(column, y).a;
        partial += a > 0 && a < 255;
    }
    for (uint32_t row = 0; row < kExtent.height; ++row) {
        const int a = pixels.at(x, row).a;
        partial += a > 0 && a < 255;
    }
    EXPECT_GE(partial, 4) << "an edge pixel with partial coverage on each side";
}

TEST_F(OverlayRenderTest, NoActiveHandRendersNothingAndLeavesTheImageAlone) {
    const Pixels before = vulkan_->read(target_, 0, kAttachment);
    EXPECT_FALSE(renderer_->render(frame_));
    // Active, but every joint is unusable (tracking lost): still nothing to show.
    left().ghost_active = true;
    left().ghost.positions[3] = {std::numeric_limits<float>::quiet_NaN(), 0.0f, -0.5f};
    left().ghost.radii[3] = 0.02f;
    EXPECT_FALSE(renderer_->render(frame_));
    renderer_->wait_idle();
    EXPECT_TRUE(vulkan_->read(target_, 0, kAttachment) == before);
}

TEST_F(OverlayRenderTest, EachViewGoesToItsArrayLayer) {
    target_ = new_target(VK_FORMAT_R8G8B8A8_SRGB, 2);
    constexpr float kHalfIpd = 0.032f;
    views_ = {camera(-kHalfIpd, 0), camera(kHalfIpd, 1)};
    frame_.views = views_;
    const Vec3 p{0.0f, 0.0f, -0.5f};
    left().physical_active = true;
    put_joint(left().physical, 0, p, 0.012f);
    EXPECT_TRUE(renderer_->render(frame_));
    renderer_->wait_idle();
    for (uint32_t layer = 0; layer < 2; ++layer) {
        const Pixels pixels = vulkan_->read(target_, layer, kAttachment);
        const float eye = layer == 0 ? -kHalfIpd : kHalfIpd;
        const PixelPosition seen = project(p, eye), other = project(p, -eye);
        EXPECT_TRUE(near(pixels.at(seen.x, seen.y), opaque(kLeftColor))) << "layer " << layer;
        EXPECT_EQ(pixels.at(other.x, other.y).a, 0) << "layer " << layer;
    }
}

TEST_F(OverlayRenderTest, LeavesTheImageInTheLayoutAsked) {
    // The validation layer checks the layout the readback assumes.
    frame_.final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const Vec3 p{0.0f, 0.0f, -0.5f};
    left().physical_active = true;
    put_joint(left().physical, 0, p, 0.02f);
    EXPECT_TRUE(near(draw().at(project(p).x, project(p).y), opaque(kLeftColor)));
}

TEST_F(OverlayRenderTest, BgraTargetsGetTheSameColours) {
    make_renderer(VK_FORMAT_B8G8R8A8_SRGB, false);
    target_ = new_target(VK_FORMAT_B8G8R8A8_SRGB, 1);
    views_ = {camera(0.0f, 0)};
    frame_.views = views_;
    const Vec3 p{0.0f, 0.0f, -0.5f};
    right().physical_active = true;
    put_joint(right().physical, 4, p, 0.02f);
    right().in_contact[4] = true;
    const Rgba bgra = draw().at(project(p).x, project(p).y);
    EXPECT_TRUE(near({bgra.b, bgra.g, bgra.r, bgra.a}, opaque(kTint)));
}

TEST_F(OverlayRenderTest, FramesInFlightKeepTheirOwnData) {
    // Several frames submitted without waiting: each must use its own instances; the
    // image ends with the last one.
    left().physical_active = true;
    for (const float x : {-0.1f, -0.05f, 0.0f, 0.05f}) {
        put_joint(left().physical, 0, {x, 0.0f, -0.5f}, 0.015f);
        EXPECT_TRUE(renderer_->render(frame_));
    }
    renderer_->wait_idle();
    const Pixels pixels = vulkan_->read(target_, 0, kAttachment);
    const PixelPosition last = project({0.05f, 0.0f, -0.5f});
    const PixelPosition first = project({-0.1f, 0.0f, -0.5f});
    EXPECT_TRUE(near(pixels.at(last.x, last.y), opaque(kLeftColor)));
    EXPECT_EQ(pixels.at(first.x, first.y).a, 0);
}

TEST_F(OverlayRenderTest, ForgottenImagesCanBeDestroyedAndReplaced) {
    const Vec3 p{0.0f, 0.0f, -0.5f};
    left().physical_active = true;
    put_joint(left().physical, 0, p, 0.02f);
    EXPECT_TRUE(renderer_->render(frame_));
    // Like xrDestroySwapchain and a new swapchain: the validation layer would report a
    // view or framebuffer of a destroyed image.
    renderer_->forget_image(target_.image);
    vulkan_->destroy_image(images_.back());
    images_.pop_back();
    target_ = new_target(VK_FORMAT_R8G8B8A8_SRGB, 1);
    views_ = {camera(0.0f, 0)};
    frame_.views = views_;
    EXPECT_TRUE(near(draw().at(project(p).x, project(p).y), opaque(kLeftColor)));
}

TEST_F(OverlayRenderTest, ReportsCpuAndGpuTime) {
    left().physical_active = true;
    put_joint(left().physical, 0, {0.0f, 0.0f, -0.5f}, 0.02f);
    draw();
    EXPECT_GT(renderer_->timings().cpu_ms, 0.0);
    EXPECT_EQ(renderer_->timings().gpu_ms, -1.0) << "not asked for";
    EXPECT_EQ(renderer_->timings().gpu_frames, 0u);
    make_renderer(VK_FORMAT_R8G8B8A8_SRGB, true);
    draw();
    EXPECT_GT(renderer_->timings().gpu_ms, 0.0);
    EXPECT_EQ(renderer_->timings().gpu_frames, 1u);
    // One more frame, one more time, whether read when its slot comes round or on waiting.
    EXPECT_TRUE(renderer_->render(frame_));
    EXPECT_TRUE(renderer_->render(frame_));
    EXPECT_EQ(renderer_->timings().gpu_frames, 1u) << "no slot came round yet";
    EXPECT_TRUE(renderer_->render(frame_));
    EXPECT_EQ(renderer_->timings().gpu_frames, 2u);
    renderer_->wait_idle();
    EXPECT_EQ(renderer_->timings().gpu_frames, 4u);
}

// A headset's 2064 x 2208 views, drawn at drawn_extent of them, cost the renderer at most
// 40 MB of device memory (its multisampled attachments and buffers).
TEST_F(OverlayRenderTest, AHeadsetsViewsTakeAtMost40MB) {
    const VkExtent2D drawn = drawn_extent({2064, 2208});
    OffscreenImage& image =
        images_.emplace_back(vulkan_->create_image(VK_FORMAT_R8G8B8A8_SRGB, drawn, 2));
    vulkan_->fill(image, {0.0f, 0.0f, 0.0f, 0.0f}, kAttachment);
    views_ = {camera(-0.032f, 0), camera(0.032f, 1)};
    for (View& view : views_) {
        view.image = image.image;
        view.extent = drawn;
    }
    frame_.views = views_;
    left().physical_active = true;
    put_joint(left().physical, 0, {0.0f, 0.0f, -0.5f}, 0.02f);
    EXPECT_TRUE(renderer_->render(frame_));
    renderer_->wait_idle();
    EXPECT_LE(renderer_->memory_bytes(), 40'000'000u);
    EXPECT_GT(renderer_->memory_bytes(), 0u);
}

// A box solid is drawn as a box, turned as its orientation says: 8 x 4 cm turned a
// quarter about the view axis shows 4 cm wide and 8 cm tall, to its corners.
TEST_F(OverlayRenderTest, ABoxSolidIsDrawnToItsCornersAndTurned) {
    right().physical_active = true;
    right().solid_count = 1;
    Solid& box = right().solids[0];
    box.kind = Solid::Kind::Box;
    box.start = {0.0f, 0.0f, -0.5f};
    box.half_extents = {0.04f, 0.02f, 0.01f};
    const float half_turn = std::sin(std::numbers::pi_v<float> / 4);
    box.orientation = {0.0f, 0.0f, half_turn, half_turn};
    const Pixels pixels = draw();
    const Vec3 front_corner{0.018f, 0.038f, -0.49f};
    const auto corner = project(front_corner);
    EXPECT_EQ(pixels.at(corner.x, corner.y).a, 255) << "a sphere or capsule would miss the corner";
    EXPECT_GT(pixels.at(corner.x, corner.y).g, 2 * pixels.at(corner.x, corner.y).r);
    for (const Vec3 outside : {Vec3{0.025f, 0.0f, -0.49f}, Vec3{0.0f, 0.045f, -0.49f}}) {
        const auto [x, y] = project(outside);
        EXPECT_EQ(pixels.at(x, y).a, 0);
    }
}

TEST_F(OverlayRenderTest, ATouchingSolidIsTinted) {
    const Vec3 p{0.0f, 0.0f, -0.5f};
    left().physical_active = true;
    left().solid_count = 2;
    left().solids[0].start = {-0.02f, 0.0f, -0.5f};
    left().solids[0].end = {0.02f, 0.0f, -0.5f};
    left().solids[0].radius = 0.01f;
    left().solids[0].in_contact = true;
    left().solids[1].start = left().solids[1].end = {0.0f, 0.05f, -0.5f};
    left().solids[1].radius = 0.01f;
    const Pixels pixels = draw();
    EXPECT_TRUE(near(pixels.at(project(p).x, project(p).y), opaque(kTint)));
    const auto [x, y] = project({0.0f, 0.05f, -0.5f});
    EXPECT_TRUE(near(pixels.at(x, y), opaque(kLeftColor)));
}

// The ghost reads as an outline: more opaque toward its silhouette than where it faces
// the eye.
TEST_F(OverlayRenderTest, TheGhostsRimIsMoreOpaqueThanItsMiddle) {
    const Vec3 p{0.0f, 0.0f, -0.5f};
    const float radius = 0.04f;  // as drawn
    left().ghost_active = true;
    put_joint(left().ghost, 0, p, radius / kGhostThickness);
    const Pixels pixels = draw();
    const auto [x, y] = project(p);
    const auto rim = static_cast<uint32_t>(0.9f * projected_radius(p, radius));
    EXPECT_NEAR(pixels.at(x, y).a, std::lround(kGhostCentreAlpha * 255.0f), kTolerance);
    EXPECT_GT(pixels.at(x + rim, y).a, 2 * pixels.at(x, y).a);
    EXPECT_LE(pixels.at(x + rim, y).a, std::lround(kGhostAlpha * 255.0f));
}

TEST_F(OverlayRenderTest, RealHandsDrawBothColoursAndTheTint) {
    frame_ = testing::demo_frame(views_);
    frame_.settings.hand_colors = {kLeftColor, kRightColor};
    const Pixels pixels = draw();
    int red = 0, green = 0, tint = 0;
    for (uint32_t y = 0; y < kExtent.height; ++y) {
        for (uint32_t x = 0; x < kExtent.width; ++x) {
            const Rgba p = pixels.at(x, y);
            red += p.a == 255 && p.r > 2 * p.g && p.r > 2 * p.b;
            green += p.a == 255 && p.g > 2 * p.r && p.g > p.b;
            tint += p.a == 255 && p.b > p.g && p.g > p.r && p.r > 60;
        }
    }
    EXPECT_GT(red, 1000);
    EXPECT_GT(green, 1000);
    EXPECT_GT(tint, 20);
}

}  // namespace
}  // namespace physhand::overlay
