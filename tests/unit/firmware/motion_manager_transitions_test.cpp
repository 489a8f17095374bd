// MotionManager transitions (issue 6 point 7): stand <-> walk, stand -> kick -> stand, a walk
// stops before a kick, falls from every state, the get-up script chosen by the side that is
// down, get-up -> stand or back to fallen, and the refusals. The script engine is the real
// ScriptEngine with the stock scripts; the walk is a small stand-in (the walk engine is issue 5)
// that takes a few ticks to finish its step after request_stop(), as a walk does.
#include <gtest/gtest.h>

#include "motion_manager_rig.hpp"
#include "stride/firmware/controller.hpp"

namespace stride::fw {
namespace {

using test::idx;
using test::kPeriodNs;
using test::kPeriodS;
using test::kStandRampTicks;
using test::Rig;
using test::StepWalk;

TEST(MotionManager, StartsInStandAndSettles) {
  Rig r;
  r.run(1);
  EXPECT_EQ(r.manager->state(), MotionState::kStand);
  EXPECT_FALSE(r.manager->stand().done());
  r.run(kStandRampTicks + 1);
  EXPECT_TRUE(r.manager->stand().done());
  EXPECT_NEAR(r.out.servos[idx("l_knee")].position_rad, kStandPoseRad[idx("l_knee")], 1e-12);
}

TEST(MotionManager, StandToWalkOnlyOnceTheStandPoseIsReached) {
  Rig r;
  r.run(1);
  r.manager->request(MotionRequest::walk(0.5, 2.0, -0.1));
  r.run(10);
  EXPECT_EQ(r.manager->state(), MotionState::kStand) << "stand not settled yet";
  EXPECT_EQ(r.walk.starts, 0);
  r.run(kStandRampTicks);
  EXPECT_EQ(r.manager->state(), MotionState::kWalk);
  EXPECT_EQ(r.walk.starts, 1);
  EXPECT_DOUBLE_EQ(r.walk.vx, 0.5);
  EXPECT_DOUBLE_EQ(r.walk.vy, 1.0) << "clamped to [-1, 1]";
  EXPECT_DOUBLE_EQ(r.out.servos[idx("r_hip_yaw")].position_rad, StepWalk::kWalkMark);
  // A new velocity while walking goes straight to the walk.
  r.manager->request(MotionRequest::walk(-0.2, 0, 0));
  r.run(1);
  EXPECT_DOUBLE_EQ(r.walk.vx, -0.2);
}

TEST(MotionManager, WalkToStandFinishesTheStepFirst) {
  Rig r;
  r.settle_stand();
  r.manager->request(MotionRequest::walk(1, 0, 0));
  r.run(30);
  ASSERT_EQ(r.manager->state(), MotionState::kWalk);
  r.manager->request(MotionRequest::stand());
  r.run(1);
  EXPECT_EQ(r.walk.stop_requests, 1);
  EXPECT_EQ(r.manager->state(), MotionState::kWalk) << "the step is finished first";
  const hal::Tick taken = r.run_until(MotionState::kStand, 100);
  EXPECT_GE(taken, StepWalk::kStopTicks - 2);
  EXPECT_LE(taken, StepWalk::kStopTicks + 1);
  EXPECT_EQ(r.manager->state(), MotionState::kStand);
}

TEST(MotionManager, AWalkAskedForWhileTheWalkStopsStartsAgainOnceItHasStopped) {
  Rig r;
  r.settle_stand();
  r.manager->request(MotionRequest::walk(1, 0, 0));
  r.run(30);
  ASSERT_EQ(r.walk.starts, 1);
  r.manager->request(MotionRequest::stand());
  r.run(5);
  r.manager->request(MotionRequest::walk(0, 0.5, 0));  // before the stop has finished
  r.run(StepWalk::kStopTicks + 5);
  EXPECT_EQ(r.manager->state(), MotionState::kWalk);
  EXPECT_EQ(r.walk.starts, 2) << "the stopped walk starts again";
  EXPECT_FALSE(r.walk.done());
  EXPECT_EQ(r.walk.vy, 0.5);
}

TEST(MotionManager, KickFromStandPlaysTheScriptThenStands) {
  Rig r;
  r.settle_stand();
  r.manager->request(MotionRequest::play("kick_right"));
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kScript);
  EXPECT_EQ(r.manager->active_script(), "kick_right");
  // Frame 4 (ends 2100 ms after the start) drives r_hip_pitch to -0.8608.
  r.run(195);
  EXPECT_DOUBLE_EQ(r.out.servos[idx("r_hip_pitch")].position_rad, -0.8608);
  EXPECT_DOUBLE_EQ(r.out.servos[idx("r_hip_pitch")].p_gain, 51);
  const hal::Tick rest = r.run_until(MotionState::kStand, 400);
  EXPECT_LE(rest, 400);
  // The whole 3.1 s kick ran: 311 ticks from start to done.
  EXPECT_NEAR(static_cast<double>(196 + rest), 312.0, 1.0);
  EXPECT_EQ(r.manager->active_script(), "");
  r.run(kStandRampTicks + 1);
  EXPECT_TRUE(r.manager->stand().done());
}

TEST(MotionManager, AStandRequestStopsAScriptAndStandsFromWhereItIs) {
  // The console's `stop` during a long script (the 33 s identify_stand): stand at once, ramping
  // from the pose the script reached, and a later script plays whole.
  Rig r;
  r.settle_stand();
  r.manager->request(MotionRequest::play("identify_stand"));
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kScript);
  r.run(300);  // into the sway
  const double ankle = r.out.servos[idx("l_ankle_pitch")].position_rad;
  r.manager->request(MotionRequest::stand());
  r.run(1);
  EXPECT_EQ(r.manager->state(), MotionState::kStand);
  EXPECT_EQ(r.manager->active_script(), "");
  EXPECT_FALSE(r.manager->stand().done());
  EXPECT_NEAR(r.out.servos[idx("l_ankle_pitch")].position_rad, ankle, 0.01) << "no jump";
  r.run(kStandRampTicks + 1);
  EXPECT_TRUE(r.manager->stand().done());
  r.manager->request(MotionRequest::play("kick_right"));
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kScript);
  const hal::Tick kick = r.run_until(MotionState::kStand, 400);
  EXPECT_GT(kick, 300) << "the 3.1 s kick plays whole after an aborted script";
  EXPECT_LE(kick, 400);
}

TEST(MotionManager, KickWaitsForASettledStand) {
  Rig r;
  r.run(1);
  r.manager->request(MotionRequest::play("kick_left"));
  r.run(20);
  EXPECT_EQ(r.manager->state(), MotionState::kStand);
  const hal::Tick waited = r.run_until(MotionState::kScript, 300);
  EXPECT_LE(21 + waited, kStandRampTicks + 3);
  EXPECT_GE(21 + waited, kStandRampTicks);
  EXPECT_EQ(r.manager->active_script(), "kick_left");
}

TEST(MotionManager, AWalkStopsBeforeAKick) {
  Rig r;
  r.settle_stand();
  r.manager->request(MotionRequest::walk(1, 0, 0));
  r.run(40);
  ASSERT_EQ(r.manager->state(), MotionState::kWalk);
  r.manager->request(MotionRequest::play("kick_right"));
  r.run(1);
  EXPECT_EQ(r.walk.stop_requests, 1);
  EXPECT_EQ(r.manager->state(), MotionState::kWalk);
  EXPECT_LE(r.run_until(MotionState::kStand, 100), StepWalk::kStopTicks + 1);
  // Stand must settle before the kick starts (a kick only from stand).
  const hal::Tick stand_ticks = r.run_until(MotionState::kScript, 400);
  EXPECT_GE(stand_ticks, kStandRampTicks);
  EXPECT_LE(stand_ticks, kStandRampTicks + 2);
  EXPECT_EQ(r.manager->active_script(), "kick_right");
  EXPECT_EQ(r.walk.starts, 1);
}

TEST(MotionManager, UnknownScriptsAndMissingWalkAreRefused) {
  Rig r(/*with_walk=*/false);
  r.settle_stand();
  r.manager->request(MotionRequest::play("moonwalk"));
  r.run(1);
  r.manager->request(MotionRequest::walk(1, 0, 0));
  r.run(5);
  EXPECT_EQ(r.manager->refused_requests(), 2u);
  EXPECT_EQ(r.manager->state(), MotionState::kStand);
}

TEST(MotionManager, FallFromEveryStateGoesToFallenAndHoldsSoft) {
  for (const char* from : {"stand", "walk", "script"}) {
    Rig r;
    r.settle_stand();
    if (std::string_view(from) == "walk") r.manager->request(MotionRequest::walk(1, 0, 0));
    if (std::string_view(from) == "script") r.manager->request(MotionRequest::play("kick_right"));
    r.run(50);
    r.lie(-9.81, 0.0, 0.0);
    r.sensors.servos[idx("r_knee")].position_rad = 1.2345;
    r.run(1);
    EXPECT_EQ(r.manager->state(), MotionState::kFallen) << from;
    EXPECT_EQ(r.manager->active_script(), "") << from;
    // Soft hold at the measured pose: gain motion.fallen_gain (5 -> P 13).
    EXPECT_DOUBLE_EQ(r.out.servos[idx("r_knee")].position_rad, 1.2345) << from;
    EXPECT_DOUBLE_EQ(r.out.servos[idx("r_knee")].p_gain, 13) << from;
    // Requests are refused while fallen.
    r.manager->request(MotionRequest::play("kick_right"));
    r.run(1);
    EXPECT_EQ(r.manager->refused_requests(), 1u) << from;
  }
}

TEST(MotionManager, LyingStillOnTheFrontPlaysGetUpFrontAfterTheStillTime) {
  Rig r;
  r.settle_stand();
  r.lie(-9.81, 0.5, 0.3);                            // torso x axis points down: face down
  r.sensors.cm730.gyro_rad_s = {0.03, -0.04, 0.02};  // a bias and noise, not a motion
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kFallen);
  // motion.fallen_still_time 0.2 s = 20 ticks of lying still (gyro below 0.5 rad/s) first.
  const hal::Tick waited = r.run_until(MotionState::kGetUp, 300);
  EXPECT_GE(waited, 18);
  EXPECT_LE(waited, 20);
  EXPECT_EQ(r.manager->active_script(), "get_up_front");
}

TEST(MotionManager, ARobotStillRockingWaitsUntilItIsStillOrTheSettleTimeHasPassed) {
  Rig r;
  r.settle_stand();
  r.lie(-9.81, 0.5, 0.3);
  r.sensors.cm730.gyro_rad_s = {0.0, 0.8, 0.0};  // still rolling after the impact
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kFallen);
  r.run(50);
  EXPECT_EQ(r.manager->state(), MotionState::kFallen);
  // It comes to rest at tick 51: the get-up starts 0.2 s later, not at the 1 s settle time.
  r.sensors.cm730.gyro_rad_s = {0.0, 0.1, 0.0};
  const hal::Tick still = r.run_until(MotionState::kGetUp, 300);
  EXPECT_GE(still, 19);
  EXPECT_LE(still, 21);
  // Rocking for ever: motion.fallen_settle_time 1.0 s = 100 ticks is the longest wait.
  Rig rocking;
  rocking.settle_stand();
  rocking.lie(9.81, -0.5, 0.3);
  rocking.sensors.cm730.gyro_rad_s = {0.6, 0.0, -0.7};
  rocking.run(1);
  const hal::Tick waited = rocking.run_until(MotionState::kGetUp, 300);
  EXPECT_GE(waited, 98);
  EXPECT_LE(waited, 100);
  EXPECT_EQ(rocking.manager->active_script(), "get_up_back");
}

TEST(MotionManager, LyingOnTheBackPlaysGetUpBack) {
  Rig r;
  r.settle_stand();
  r.lie(9.81, -0.5, 0.3);
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kFallen);
  EXPECT_LE(r.run_until(MotionState::kGetUp, 300), 101);
  EXPECT_EQ(r.manager->active_script(), "get_up_back");
}

TEST(MotionManager, LyingStillOnASidePlaysTheScriptOfTheSideItLeansTo) {
  Rig r;
  r.settle_stand();
  r.lie(1.0, 9.7, 0.3);  // on its right side, leaning slightly onto the back (accel x > 0)
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kFallen);
  // Still (gyro 0): after motion.fallen_still_time, 20 ticks, as on the front or back.
  const hal::Tick waited = r.run_until(MotionState::kGetUp, 300);
  EXPECT_GE(waited, 18);
  EXPECT_LE(waited, 20);
  EXPECT_EQ(r.manager->active_script(), "get_up_back");
}

TEST(MotionManager, RockingOnASideWaitsTwiceTheSettleTime) {
  Rig r;
  r.settle_stand();
  r.lie(1.0, 9.7, 0.3);
  r.sensors.cm730.gyro_rad_s = {0.7, 0.0, 0.0};  // it may still roll over
  r.run(1);
  ASSERT_EQ(r.manager->state(), MotionState::kFallen);
  // One settle time (1 s) is not enough on a side while it still moves.
  r.run(150);
  EXPECT_EQ(r.manager->state(), MotionState::kFallen);
  // After twice the settle time the get-up of the side it leans to starts.
  const hal::Tick waited = r.run_until(MotionState::kGetUp, 300);
  EXPECT_GE(151 + waited, 199);
  EXPECT_LE(151 + waited, 202);
  EXPECT_EQ(r.manager->active_script(), "get_up_back");
}

TEST(MotionManager, RollingFromASideOntoTheFrontStartsAtOnce) {
  Rig r;
  r.settle_stand();
  r.lie(-1.0, 9.7, 0.3);
  r.sensors.cm730.gyro_rad_s = {0.7, 0.0, 0.0};  // rolling
  r.run(120);
  EXPECT_EQ(r.manager->state(), MotionState::kFallen);
  r.sensors.cm730.accel_mps2 = {-9.7, 1.0, 0.3};  // rolled onto the front, past the settle time
  r.run(2);
  EXPECT_EQ(r.manager->state(), MotionState::kGetUp);
  EXPECT_EQ(r.manager->active_script(), "get_up_front");
}

TEST(MotionManager, GetUpThenStandWhenUpright) {
  Rig r;
  r.settle_stand();
  r.lie(-9.81, 0, 0);
  ASSERT_LE(r.run_until(MotionState::kGetUp, 300), 101);
  // A fall report during the get-up does not restart it.
  r.run(100);
  EXPECT_EQ(r.manager->state(), MotionState::kGetUp);
  r.get_up_upright();  // the script has raised the robot
  const Script& script = r.scripts.script(static_cast<std::size_t>(r.scripts.find("get_up_front")));
  const hal::Tick rest = r.run_until(MotionState::kStand, 2000);
  EXPECT_NEAR(static_cast<double>(100 + rest), script.total_duration_ms() / 10.0, 2.0);
  r.run(kStandRampTicks + 1);
  EXPECT_TRUE(r.manager->stand().done());
}

TEST(MotionManager, GetUpThatLeavesTheRobotDownTriesAgain) {
  Rig r;
  r.settle_stand();
  r.lie(-9.81, 0, 0);
  ASSERT_LE(r.run_until(MotionState::kGetUp, 300), 101);
  EXPECT_LE(r.run_until(MotionState::kFallen, 2000), 2000);
  EXPECT_EQ(r.manager->active_script(), "");
  EXPECT_LE(r.run_until(MotionState::kGetUp, 300), 101);
  EXPECT_EQ(r.manager->active_script(), "get_up_front_retry");
  // The retry's variants (the roll from the back, the slower get-up):
  // motion_manager_retry_test.cpp.
}

TEST(MotionManager, RightedWhileFallenGoesToStand) {
  Rig r;
  r.settle_stand();
  r.lie(-9.81, 0, 0);
  r.run(10);
  ASSERT_EQ(r.manager->state(), MotionState::kFallen);
  r.get_up_upright();
  r.run(1);
  EXPECT_EQ(r.manager->state(), MotionState::kStand);
}

TEST(MotionManager, GetUpCanBeSwitchedOff) {
  Rig r;
  ASSERT_TRUE(r.params.set_now({{"motion.get_up", 0}}));
  r.settle_stand();
  r.lie(-9.81, 0, 0);
  r.run(500);
  EXPECT_EQ(r.manager->state(), MotionState::kFallen);
}

TEST(MotionManager, ControllerDetectsTheFallAndPicksTheSideFromTheImu) {
  // Through the Controller: the safety layer's tilt detector feeds the manager.
  for (const double ax : {-9.81, 9.81}) {
    ParameterStore params;
    ScriptEngine scripts(kPeriodNs, params);
    ASSERT_TRUE(scripts.load_folder(default_script_folder()));
    AttitudeEstimator attitude(params, kPeriodNs * 1e-9);
    Controller controller(params, ServoTable::defaults(), kPeriodNs, attitude, {nullptr, &scripts});
    hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame(kStandPoseRad);
    hal::Tick tick = 0;
    for (; tick < 200; ++tick) (void)controller.step(sensors, tick);
    EXPECT_EQ(controller.motion().state(), MotionState::kStand);
    sensors.cm730.accel_mps2 = {ax, 0.0, 0.2};
    for (; tick < 230; ++tick) (void)controller.step(sensors, tick);
    EXPECT_EQ(controller.motion().state(), MotionState::kFallen);
    for (; tick < 400; ++tick) (void)controller.step(sensors, tick);
    EXPECT_EQ(controller.motion().state(), MotionState::kGetUp);
    EXPECT_EQ(controller.motion().active_script(), ax < 0 ? "get_up_front" : "get_up_back");
  }
}

}  // namespace
}  // namespace stride::fw
