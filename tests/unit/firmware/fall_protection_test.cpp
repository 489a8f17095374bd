// Falling safely (issue 43 point 2), with synthetic IMU frames: FallPredictor predicts falls
// forward, backward and to either side from attitude and rate, and never while the torso only
// leans; through the Controller a predicted fall takes FallProtection's pose, soft and
// torque-limited, then the detected fall goes on to kFallen (the get-up path); fall.protect 0
// predicts but does not act; a prediction that clears without a fall returns to standing.
#include <gtest/gtest.h>

#include <cmath>

#include "stride/firmware/controller.hpp"
#include "stride/firmware/fall_predictor.hpp"
#include "stride/firmware/script/script_engine.hpp"
#include "stride/firmware/stand_pose.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;
constexpr double kPeriodS = 0.01;
constexpr double kG = 9.81;

std::size_t idx(const char* name) {
  return *ServoTable::defaults().index_of(name);
}

/// The IMU of a torso at `pitch` (forward +) and `roll` (right +), rotating at the given rates.
hal::Cm730State imu_at(double pitch, double pitch_rate, double roll = 0.0, double roll_rate = 0.0) {
  hal::Cm730State imu;
  imu.accel_mps2 = {-kG * std::sin(pitch), kG * std::sin(roll) * std::cos(pitch),
                    kG * std::cos(roll) * std::cos(pitch)};
  imu.gyro_rad_s = {roll_rate, pitch_rate, 0.0};
  imu.health = hal::DeviceHealth::kOk;
  return imu;
}

/// The fall predictor fed as the controller feeds it: the attitude estimate first.
struct Predictor {
  ParameterStore params;
  AttitudeEstimator attitude{params, kPeriodS};
  FallPredictor predictor{params};
  void observe(const hal::Cm730State& imu) {
    attitude.update(imu);
    predictor.observe(attitude);
  }
  bool falling() const { return predictor.falling(); }
  FallDirection direction() const { return predictor.direction(); }
};

/// Feeds a fall that starts upright and accelerates like an inverted pendulum about one axis
/// (angle'' = 9 angle, from 0.02 rad), `sign` and `about_pitch` choosing the direction. Returns
/// the angle at which the prediction fired, or NaN.
double predicted_at(Predictor& predictor, double sign, bool about_pitch) {
  for (int i = 0; i < 50; ++i) predictor.observe(imu_at(0.0, 0.0));  // upright first
  double angle = 0.02, rate = 0.0;
  for (int i = 0; i < 200 && angle < 1.5; ++i) {
    rate += 9.0 * angle * kPeriodS;
    angle += rate * kPeriodS;
    predictor.observe(about_pitch ? imu_at(sign * angle, sign * rate)
                                  : imu_at(0.0, 0.0, sign * angle, sign * rate));
    if (predictor.falling()) return angle;
  }
  return std::nan("");
}

TEST(FallPredictor, PredictsEachDirectionWellBeforeTheTorsoIsDown) {
  struct Case {
    double sign;
    bool about_pitch;
    FallDirection expected;
  };
  for (const Case c :
       {Case{1, true, FallDirection::kForward}, Case{-1, true, FallDirection::kBackward},
        Case{1, false, FallDirection::kRight}, Case{-1, false, FallDirection::kLeft}}) {
    Predictor predictor;
    const double angle = predicted_at(predictor, c.sign, c.about_pitch);
    ASSERT_TRUE(std::isfinite(angle)) << to_string(c.expected);
    // Fired while the torso was still less than 45 degrees from upright (the ground is at 90).
    EXPECT_LT(angle, 0.8) << to_string(c.expected);
    EXPECT_GT(angle, 0.1) << to_string(c.expected);
    EXPECT_EQ(predictor.direction(), c.expected);
  }
}

TEST(FallPredictor, LeaningAndSwayingIsNotAFall) {
  Predictor predictor;
  // Sways of 0.25 rad at up to 1.6 rad/s in pitch and roll (a walk sways far less), for 20 s.
  for (int i = 0; i < 2000; ++i) {
    const double t = i * kPeriodS;
    const double w = 2.0 * M_PI * 1.0;
    predictor.observe(imu_at(0.25 * std::sin(w * t), 0.25 * w * std::cos(w * t),
                             0.2 * std::sin(0.5 * w * t), 0.1 * w * std::cos(0.5 * w * t)));
    ASSERT_FALSE(predictor.falling()) << "at " << t << " s";
  }
}

TEST(FallPredictor, LyingDoesNotPredictUntilUprightAgain) {
  Predictor predictor;
  // Starts lying on the back and rocks: it was never upright, so no prediction.
  for (int i = 0; i < 300; ++i)
    predictor.observe(imu_at(-1.5 + 0.05 * std::sin(i * 0.3), -0.5 * std::cos(i * 0.3)));
  EXPECT_FALSE(predictor.falling());
  EXPECT_TRUE(std::isfinite(predicted_at(predictor, 1.0, true)));  // upright, then a fall
}

struct Rig {
  ParameterStore params;
  AttitudeEstimator attitude{params, kPeriodS};
  ScriptEngine scripts{kPeriodNs, params};
  std::unique_ptr<Controller> controller;
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame(kStandPoseRad);
  hal::Tick tick = 0;
  hal::CommandFrame out{};

  Rig() {
    EXPECT_TRUE(scripts.load_folder(default_script_folder()));
    controller = std::make_unique<Controller>(params, ServoTable::defaults(), kPeriodNs, attitude,
                                              ControllerEngines{nullptr, &scripts});
    run(200);  // the stand is reached
    EXPECT_EQ(controller->motion().state(), MotionState::kStand);
  }
  void run(int ticks) {
    for (int i = 0; i < ticks; ++i) out = controller->step(sensors, tick++);
  }
  /// A forward fall until the prediction (or 2 s); returns whether it was predicted.
  bool fall_forward() {
    double angle = 0.02, rate = 0.0;
    for (int i = 0; i < 200; ++i) {
      rate += 9.0 * angle * kPeriodS;
      angle += rate * kPeriodS;
      sensors.cm730 = imu_at(angle, rate);
      out = controller->step(sensors, tick++);
      if (controller->safety().falling()) return true;
    }
    return false;
  }
};

TEST(FallProtection, APredictedFallTakesTheProtectivePoseSoftAndTorqueLimited) {
  Rig r;
  ASSERT_TRUE(r.fall_forward());
  EXPECT_EQ(r.controller->motion().state(), MotionState::kFalling);
  EXPECT_EQ(r.controller->safety().report().fall_direction, FallDirection::kForward);
  EXPECT_EQ(r.controller->safety().report().predictions, 1u);
  // The defaults (FALLING.md): arms ahead, a deep crouch, gain 15 (P 38), torque limit 0.4.
  for (const char* arm : {"r_shoulder_pitch", "l_shoulder_pitch"})
    EXPECT_DOUBLE_EQ(r.out.servos[idx(arm)].position_rad, -1.3) << arm;
  for (const char* knee : {"r_knee", "l_knee"})
    EXPECT_DOUBLE_EQ(r.out.servos[idx(knee)].position_rad, 1.4) << knee;
  EXPECT_DOUBLE_EQ(r.out.servos[idx("r_hip_pitch")].position_rad, -0.7);
  for (const auto& c : r.out.servos) {
    EXPECT_DOUBLE_EQ(c.p_gain, 38.0);
    EXPECT_DOUBLE_EQ(c.torque_limit, 0.4);
    EXPECT_TRUE(c.torque_enable);
  }
  // Lying on the front: the detected fall takes over (kFallen), then the get-up.
  r.sensors.cm730 = imu_at(1.5, 0.0);
  r.run(30);
  EXPECT_EQ(r.controller->motion().state(), MotionState::kFallen);
  r.run(150);
  EXPECT_EQ(r.controller->motion().state(), MotionState::kGetUp);
  EXPECT_EQ(r.controller->motion().active_script(), "get_up_front");
}

TEST(FallProtection, BackwardAndSidewaysPoses) {
  Rig back;
  // Backward: the same pendulum, negative.
  double angle = 0.02, rate = 0.0;
  for (int i = 0; i < 200 && !back.controller->safety().falling(); ++i) {
    rate += 9.0 * angle * kPeriodS;
    angle += rate * kPeriodS;
    back.sensors.cm730 = imu_at(-angle, -rate);
    back.out = back.controller->step(back.sensors, back.tick++);
  }
  ASSERT_EQ(back.controller->motion().state(), MotionState::kFalling);
  EXPECT_DOUBLE_EQ(back.out.servos[idx("r_shoulder_pitch")].position_rad, 1.3);

  Rig right;
  angle = 0.02, rate = 0.0;
  for (int i = 0; i < 200 && !right.controller->safety().falling(); ++i) {
    rate += 9.0 * angle * kPeriodS;
    angle += rate * kPeriodS;
    right.sensors.cm730 = imu_at(0.0, 0.0, angle, rate);
    right.out = right.controller->step(right.sensors, right.tick++);
  }
  ASSERT_EQ(right.controller->motion().state(), MotionState::kFalling);
  EXPECT_EQ(right.controller->safety().report().fall_direction, FallDirection::kRight);
  // The right arm rolls out (negative), the left stays as in the stand.
  EXPECT_DOUBLE_EQ(right.out.servos[idx("r_shoulder_roll")].position_rad,
                   kStandPoseRad[idx("r_shoulder_roll")] - 1.0);
  EXPECT_DOUBLE_EQ(right.out.servos[idx("l_shoulder_roll")].position_rad,
                   kStandPoseRad[idx("l_shoulder_roll")]);
}

TEST(FallProtection, SwitchedOffItPredictsButDoesNotAct) {
  Rig r;
  ASSERT_TRUE(r.params.set_now({{"fall.protect", 0.0}}));
  ASSERT_TRUE(r.fall_forward());
  EXPECT_EQ(r.controller->motion().state(), MotionState::kStand);
  EXPECT_DOUBLE_EQ(r.out.servos[idx("r_knee")].p_gain, 76.0);  // the stand's gain 30, not 15
  EXPECT_DOUBLE_EQ(r.out.servos[idx("r_knee")].torque_limit, 1.0);
}

TEST(FallProtection, APredictionThatClearsReturnsToStandAfterTheHoldTime) {
  Rig r;
  ASSERT_TRUE(r.fall_forward());
  ASSERT_EQ(r.controller->motion().state(), MotionState::kFalling);
  // Caught: upright and still again. fall.hold_time_s 0.5 s, then the stand.
  r.sensors.cm730 = imu_at(0.0, 0.0);
  r.run(40);
  EXPECT_EQ(r.controller->motion().state(), MotionState::kFalling);
  r.run(20);
  EXPECT_EQ(r.controller->motion().state(), MotionState::kStand);
}

}  // namespace
}  // namespace stride::fw
