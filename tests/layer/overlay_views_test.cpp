// What the overlay draws for the app's projection views (layer/overlay_views.cpp, compiled
// in): the app's own sizes, however large, and nothing for a view that cannot be drawn.

#include "overlay_views.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <utility>

#include "overlay_renderer.h"

namespace physhand::layer {
namespace {

constexpr float kAngle = 0.7f;

XrSystemGraphicsProperties limits() {
    return {.maxSwapchainImageHeight = 4096, .maxSwapchainImageWidth = 4096, .maxLayerCount = 16};
}

class OverlayViews : public ::testing::Test {
  protected:
    void SetUp() override {
        for (XrCompositionLayerProjectionView& view : views_) {
            view.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW;
            view.pose.orientation.w = 1.0f;
            view.fov = {-kAngle, kAngle, kAngle, -kAngle};
            view.subImage.imageRect.extent = {2208, 2064};
        }
        layer_.type = XR_TYPE_COMPOSITION_LAYER_PROJECTION;
        layer_.viewCount = static_cast<uint32_t>(views_.size());
        layer_.views = views_.data();
    }

    std::array<XrCompositionLayerProjectionView, 2> views_{};
    XrCompositionLayerProjection layer_{};
};

// Views up to overlay::kMaxDrawnPixels come through at their own size, one per view; a
// headset's larger ones are drawn smaller, both sides scaled alike, and the runtime scales
// the layer up to them.
TEST_F(OverlayViews, AreTheAppsOwnSizeUpToTheMostPixelsTheOverlayDraws) {
    views_[1].subImage.imageRect.extent = {1000, 1100};
    const auto extents = overlay_extents(layer_, limits());
    ASSERT_TRUE(extents.has_value());
    ASSERT_EQ(extents->size(), 2u);
    const VkExtent2D headset = (*extents)[0];
    EXPECT_LE(uint64_t{headset.width} * headset.height, overlay::kMaxDrawnPixels);
    EXPECT_GT(uint64_t{headset.width + 1} * (headset.height + 1), overlay::kMaxDrawnPixels);
    EXPECT_NEAR(double(headset.width) / headset.height, 2208.0 / 2064.0, 0.005);
    EXPECT_EQ((*extents)[1].width, 1000u);
    EXPECT_EQ((*extents)[1].height, 1100u);
    views_[0].subImage.imageRect.extent = {4096, 4096};
    EXPECT_TRUE(overlay_extents(layer_, limits()).has_value()) << "the largest swapchain";
}

struct BadView {
    const char* name;
    std::function<void(XrCompositionLayerProjectionView&)> spoil;
};

// Test names and failures show the case's name, not its bytes.
void PrintTo(const BadView& bad, std::ostream* out) {
    *out << bad.name;
}

class OverlayViewsReject : public OverlayViews, public ::testing::WithParamInterface<BadView> {};

TEST_P(OverlayViewsReject, SoTheFrameIsSkipped) {
    GetParam().spoil(views_[1]);
    EXPECT_FALSE(overlay_extents(layer_, limits()).has_value());
}

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
using View = XrCompositionLayerProjectionView;

const BadView kBadViews[] = {
    {"NegativeWidth", [](View& v) { v.subImage.imageRect.extent.width = -256; }},
    {"NegativeHeight", [](View& v) { v.subImage.imageRect.extent.height = -1; }},
    {"ZeroWidth", [](View& v) { v.subImage.imageRect.extent.width = 0; }},
    {"ZeroHeight", [](View& v) { v.subImage.imageRect.extent.height = 0; }},
    {"WiderThanAnySwapchain", [](View& v) { v.subImage.imageRect.extent.width = 4097; }},
    {"TallerThanAnySwapchain", [](View& v) { v.subImage.imageRect.extent.height = 1 << 30; }},
    {"NanPosition", [](View& v) { v.pose.position.y = kNan; }},
    {"InfinitePosition", [](View& v) { v.pose.position.z = -kInf; }},
    {"NanOrientation", [](View& v) { v.pose.orientation.x = kNan; }},
    {"NanFov", [](View& v) { v.fov.angleLeft = kNan; }},
    {"InfiniteFov", [](View& v) { v.fov.angleUp = kInf; }},
    {"EmptyFov", [](View& v) { v.fov.angleRight = v.fov.angleLeft; }},
    {"UpsideDownFov", [](View& v) { std::swap(v.fov.angleUp, v.fov.angleDown); }},
    {"RightAngleFov", [](View& v) { v.fov.angleRight = 1.5708f; }},
};

INSTANTIATE_TEST_SUITE_P(OverlayViews, OverlayViewsReject, ::testing::ValuesIn(kBadViews),
                         [](const ::testing::TestParamInfo<BadView>& info) {
                             return std::string(info.param.name);
                         });

}  // namespace
}  // namespace physhand::layer
