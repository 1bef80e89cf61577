// The layer inside an app that exports a Bullet of its own, as an engine linked with a copy
// of Bullet (and built to export its symbols) does: this test executable defines
// btDiscreteDynamicsWorld::stepSimulation, which a layer bound to it would call instead of
// its own Bullet's, and exports it (ENABLE_EXPORTS). The layer's hands must still simulate,
// and the app's function must never be called.

#include <atomic>
#include <cmath>

#include "layer_fixture.h"

// The app's Bullet: a world that never steps, counting the calls it gets.
class btDiscreteDynamicsWorld {
  public:
    int stepSimulation(float time_step, int max_sub_steps, float fixed_time_step);
};

namespace {
std::atomic<int> app_bullet_steps = 0;
}  // namespace

int btDiscreteDynamicsWorld::stepSimulation(float, int, float) {
    ++app_bullet_steps;
    return 0;
}

namespace physhand::layer_test {
namespace {

TEST_F(LayerTest, HandsSimulateInAnAppThatExportsAnotherBullet) {
    ASSERT_NO_FATAL_FAILURE(start_with_desk(scene_with_hands({{"right", pressing_hand(0.1)}})));
    const XrHandTrackerEXT right = hand_tracker(XR_HAND_RIGHT_EXT);
    HandJoints hand;
    int resting = 0;
    for (int f = 0; f < 180; ++f) {
        ASSERT_EQ(locate(right, stage_, frame(), hand), XR_SUCCESS);
        if (!hand.physical.isSimulated) continue;
        // The ghost presses into the desk; a simulated hand stays on it.
        const XrVector3f& wrist = hand.joints[XR_HAND_JOINT_WRIST_EXT].pose.position;
        const XrVector3f& ghost = hand.ghost[XR_HAND_JOINT_WRIST_EXT].position;
        if (hand.any_contact() && wrist.y > ghost.y + 0.01f) ++resting;
    }
    EXPECT_GT(resting, 0);
    EXPECT_EQ(app_bullet_steps, 0);
}

}  // namespace
}  // namespace physhand::layer_test
