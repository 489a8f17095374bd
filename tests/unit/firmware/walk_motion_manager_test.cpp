// The walk engine as the firmware composes it: the motion manager starts it from stand on a
// walk request (normalised velocity), stops it on a stand request and returns to stand, with
// no jumps in the commanded joint angles on the way.
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "stride/firmware/firmware.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

TEST(WalkMotionManager, StartsFromStandWalksAndStopsBackIntoStand) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  // The 46 genome parameters and the body height; the feedback gains live in their own groups,
  // the spline walk under walk.spline.*, and walk.engine chooses between the two walks.
  const auto& params = firmware->params();
  EXPECT_EQ(params.list("walk.").size() - params.list("walk.balance.").size() -
                params.list("walk.compliance.").size() - params.list("walk.capture.").size() -
                params.list("walk.spline.").size() - params.list("walk.engine").size(),
            47u);
  Controller& controller = firmware->controller();
  const auto sensors = hal::ScriptedRobot::standing_frame();
  hal::Tick tick = 0;
  hal::CommandFrame previous = controller.step(sensors, tick++);
  double max_jump = 0.0;  // largest change of an arm/leg target in one tick, per window
  auto run = [&](int ticks) {
    for (int i = 0; i < ticks; ++i) {
      const hal::CommandFrame c = controller.step(sensors, tick++);
      for (std::size_t k = 0; k < 18; ++k) {  // arms and legs
        ASSERT_TRUE(std::isfinite(c.servos[k].position_rad));
        max_jump = std::max(max_jump,
                            std::abs(c.servos[k].position_rad - previous.servos[k].position_rad));
      }
      previous = c;
    }
  };
  run(200);  // settle into stand
  EXPECT_EQ(controller.motion().state(), MotionState::kStand);
  max_jump = 0.0;
  controller.request(MotionRequest::walk(1.0, 0.0, 0.0));
  run(5);
  EXPECT_EQ(controller.motion().state(), MotionState::kWalk);
  run(100);  // the walk's start blend into its stance (1 s)
  const double start_jump = max_jump;
  const double knee_before = previous.servos[12].position_rad;
  max_jump = 0.0;
  run(1000);  // 10 s of walking
  const double walking_jump = max_jump;
  EXPECT_EQ(controller.motion().state(), MotionState::kWalk);
  EXPECT_NE(previous.servos[12].position_rad, knee_before);
  max_jump = 0.0;
  controller.request(MotionRequest::stand());
  int ticks_to_stand = 0;
  while (controller.motion().state() == MotionState::kWalk && ticks_to_stand < 400) {
    run(1);
    ++ticks_to_stand;
  }
  EXPECT_EQ(controller.motion().state(), MotionState::kStand);
  EXPECT_LE(ticks_to_stand, 2 * 85 + 2);  // finishes the step, then the last step
  run(300);                               // ramps back into the stand pose
  EXPECT_TRUE(controller.motion().state() == MotionState::kStand);
  // No jumps at the transitions: the blends move slower than the gait itself (whose swing
  // knee peaks near 0.08 rad per 10 ms tick as the nearly straight leg lifts the foot).
  EXPECT_LT(start_jump, 0.03) << "rad per tick";
  EXPECT_LT(max_jump, walking_jump) << "rad per tick";
  EXPECT_LT(walking_jump, 0.1) << "rad per tick";
  const auto report = controller.safety().report();
  for (auto c : report.limit_clamps) EXPECT_EQ(c, 0u);
}

}  // namespace
}  // namespace stride::fw
