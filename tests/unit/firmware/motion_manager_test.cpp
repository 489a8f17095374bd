// MotionManager without walk or script engines: stand, refusals, fall handling.
// (Transitions into walk and scripts are tested with the real engines in their own tests.)
#include "stride/firmware/motion_manager.hpp"

#include <gtest/gtest.h>

#include "firmware_fixture.hpp"
#include "stride/firmware/stand_pose.hpp"

namespace stride::fw {
namespace {

TEST(MotionManager, StartsInStandAndReachesThePose) {
  ParameterStore params;
  MotionManager manager(params, 0.01, nullptr, nullptr);
  const auto sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame out;
  for (hal::Tick t = 0; t <= 200; ++t) manager.step(sensors, t, false, out);
  EXPECT_EQ(manager.state(), MotionState::kStand);
  EXPECT_TRUE(manager.stand().done());
  EXPECT_DOUBLE_EQ(out.servos[13].position_rad, kStandPoseRad[13]);
}

TEST(MotionManager, RefusesWalkAndScriptWithoutEngines) {
  ParameterStore params;
  MotionManager manager(params, 0.01, nullptr, nullptr);
  const auto sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame out;
  manager.request(MotionRequest::walk(1.0, 0, 0));
  manager.step(sensors, 0, false, out);
  manager.request(MotionRequest::play("kick_right"));
  manager.step(sensors, 1, false, out);
  EXPECT_EQ(manager.refused_requests(), 2u);
  EXPECT_EQ(manager.state(), MotionState::kStand);
}

TEST(MotionManager, FallMakesItSoftAndRightingReturnsToStand) {
  ParameterStore params;
  MotionManager manager(params, 0.01, nullptr, nullptr);
  ASSERT_TRUE(params.set_now({{"motion.fallen_gain", 5}}));
  std::array<double, hal::kServoCount> lying_pose{};
  lying_pose[10] = -1.2;
  const auto lying = test::tilted_frame(1.5, lying_pose);
  hal::CommandFrame out;
  manager.step(lying, 0, false, out);
  manager.step(lying, 1, true, out);
  EXPECT_EQ(manager.state(), MotionState::kFallen);
  EXPECT_DOUBLE_EQ(out.servos[10].position_rad, -1.2) << "holds the measured pose";
  EXPECT_DOUBLE_EQ(out.servos[10].p_gain, 13.0);  // round(2.54 * 5)
  // No script engine: it stays down however long it lies there.
  for (hal::Tick t = 2; t < 400; ++t) manager.step(lying, t, true, out);
  EXPECT_EQ(manager.state(), MotionState::kFallen);
  // Walk requests are refused while fallen, and a righted robot stands again.
  manager.step(hal::ScriptedRobot::standing_frame(), 400, false, out);
  EXPECT_EQ(manager.state(), MotionState::kStand);
}

}  // namespace
}  // namespace stride::fw
