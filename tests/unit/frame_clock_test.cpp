#include "frame_clock.h"

#include <gtest/gtest.h>

namespace physhand {
namespace {

TEST(SceneFrameCount, PlaysUpToTheFrameAtOrJustPastTheEnd) {
    EXPECT_EQ(scene_frame_count(1.0), 90);
    EXPECT_EQ(scene_frame_count(1.005), 91);
    EXPECT_EQ(scene_frame_count(0.001), 1);
    EXPECT_EQ(scene_frame_count(0.0), 0);
}

TEST(SceneFrameCount, AWholeNumberOfFramesGainsNoneThroughRounding) {
    // 1.1 * 90 is 99.00000000000001 in doubles, 8.3 * 90 747.0000000000001.
    EXPECT_EQ(scene_frame_count(1.1), 99);
    EXPECT_EQ(scene_frame_count(8.3), 747);
}

}  // namespace
}  // namespace physhand
