// AttitudeEstimator: the firmware's one attitude estimate (attitude_estimator.hpp), with
// synthetic IMU readings: a known tilt, a known rate, the accelerometer ignored outside its
// g window, the time constant, gyro bias learning, and no allocation per tick.
#include "stride/firmware/attitude_estimator.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "counting_allocator.hpp"

namespace stride::fw {
namespace {

constexpr double kPeriod = 0.01;
constexpr double kG = 9.81;

/// The specific force of a still torso rotated by roll (about x) then pitch (about y).
Eigen::Vector3d still_accel(double roll, double pitch) {
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  return r.transpose() * Eigen::Vector3d(0.0, 0.0, kG);
}

TEST(AttitudeEstimator, RegistersOneTimeConstantAndStartsInvalid) {
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  double tau = 0.0;
  ASSERT_TRUE(store.get("walk.balance.tilt_filter_time", tau));
  EXPECT_EQ(tau, AttitudeEstimator::kDefaultTimeConstantS);
  EXPECT_EQ(attitude.time_constant(), tau);
  EXPECT_FALSE(attitude.valid());
  EXPECT_EQ(attitude.roll(), 0.0);
  EXPECT_EQ(attitude.pitch(), 0.0);
  ASSERT_TRUE(store.set_now({{"walk.balance.tilt_filter_time", 0.3}}));
  EXPECT_EQ(attitude.time_constant(), 0.3);
}

TEST(AttitudeEstimator, AStillTiltIsReadFromTheAccelerometer) {
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  for (int i = 0; i < 10; ++i) attitude.update(still_accel(0.2, -0.3), Eigen::Vector3d::Zero());
  ASSERT_TRUE(attitude.valid());
  EXPECT_NEAR(attitude.roll(), 0.2, 1e-12);
  EXPECT_NEAR(attitude.pitch(), -0.3, 1e-12);
  EXPECT_NEAR(attitude.up().norm(), 1.0, 1e-12);
  EXPECT_NEAR(attitude.measured_roll(), 0.2, 1e-12);  // the sample's own tilt
  EXPECT_NEAR(attitude.measured_pitch(), -0.3, 1e-12);
}

TEST(AttitudeEstimator, FollowsAKnownRateWhileTheAccelerometerIsIgnored) {
  // Upright, then pitching forward at 0.5 rad/s for 1 s with a specific force of 2 g (outside
  // the window, e.g. a push): the gyro alone carries the estimate, exactly.
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  attitude.update(still_accel(0.0, 0.0), Eigen::Vector3d::Zero());
  for (int i = 0; i < 100; ++i)
    attitude.update(Eigen::Vector3d(0.0, 0.0, 2.0 * kG), Eigen::Vector3d(0.0, 0.5, 0.0));
  EXPECT_NEAR(attitude.pitch(), 0.5, 2e-3);  // the Euler step's error, first order in dt
  EXPECT_NEAR(attitude.roll(), 0.0, 1e-12);
  // A NaN or a free fall (0 g) are ignored the same way.
  const double before = attitude.pitch();
  for (int i = 0; i < 10; ++i) {
    attitude.update(Eigen::Vector3d(NAN, 0.0, kG), Eigen::Vector3d::Zero());
    attitude.update(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  }
  EXPECT_NEAR(attitude.pitch(), before, 1e-12);
}

TEST(AttitudeEstimator, TheRateAndTheAccelerometerAgreeOnATurningTorso) {
  // Rolling right at 0.3 rad/s with the matching specific force: the estimate tracks the truth
  // within one tick's rotation (3 mrad; the accelerometer's sample is the tick's end).
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  attitude.update(still_accel(0.0, 0.0), Eigen::Vector3d::Zero());
  for (int i = 1; i <= 100; ++i)
    attitude.update(still_accel(0.3 * i * kPeriod, 0.0), Eigen::Vector3d(0.3, 0.0, 0.0));
  EXPECT_NEAR(attitude.roll(), 0.3, 3e-3);
  EXPECT_NEAR(attitude.pitch(), 0.0, 1e-9);
}

TEST(AttitudeEstimator, TheAccelerometerPullsWithTheTimeConstant) {
  // Estimate upright, torso still at 0.1 rad of pitch: after one time constant the error is
  // e^-1 of the start (first order), after five nearly gone.
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  ASSERT_TRUE(store.set_now({{"walk.balance.tilt_filter_time", 0.5}}));
  attitude.update(still_accel(0.0, 0.0), Eigen::Vector3d::Zero());
  for (int i = 0; i < 50; ++i) attitude.update(still_accel(0.0, 0.1), Eigen::Vector3d::Zero());
  EXPECT_NEAR(attitude.pitch(), 0.1 * (1.0 - std::exp(-1.0)), 2e-3);
  for (int i = 0; i < 200; ++i) attitude.update(still_accel(0.0, 0.1), Eigen::Vector3d::Zero());
  EXPECT_NEAR(attitude.pitch(), 0.1, 1e-3);
}

TEST(AttitudeEstimator, TheVerticalRateIsTheRateAboutTheWorldsUp) {
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  // Pitched forward by 0.3 rad and still: a yaw about the world's vertical reads
  // g = w (-sin 0.3, 0, cos 0.3) in the torso frame.
  const double w = 0.4;
  const Eigen::Vector3d gyro(-w * std::sin(0.3), 0.0, w * std::cos(0.3));
  attitude.update(still_accel(0.0, 0.3), gyro);
  attitude.update(still_accel(0.0, 0.3), gyro);
  EXPECT_NEAR(attitude.vertical_rate(), w, 1e-9);
  // A non-finite gyro axis reads 0.
  attitude.update(still_accel(0.0, 0.3), Eigen::Vector3d(NAN, 0.0, 0.0));
  EXPECT_EQ(attitude.gyro().x(), 0.0);
}

TEST(AttitudeEstimator, LearnsAHorizontalGyroBiasWhenAsked) {
  // A still, upright torso whose gyro reads 0.02 rad/s about x: without bias learning the
  // estimate settles off upright by bias x tau; learning it, upright, with the bias found.
  AttitudeEstimator plain(kPeriod, 1.0, false), learning(kPeriod, 1.0, true);
  const Eigen::Vector3d bias(0.02, 0.0, 0.0);
  for (AttitudeEstimator* a : {&plain, &learning}) {
    a->start(still_accel(0.0, 0.0));
    for (int i = 0; i < 6000; ++i) a->update(still_accel(0.0, 0.0), bias);
  }
  EXPECT_NEAR(plain.roll(), 0.02, 2e-3);
  EXPECT_NEAR(learning.roll(), 0.0, 1e-4);
  EXPECT_NEAR(learning.gyro_bias().x(), 0.02, 1e-4);
  EXPECT_NEAR(learning.vertical_rate(), 0.0, 1e-4);
}

TEST(AttitudeEstimator, ResetForgetsTheEstimate) {
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  attitude.update(still_accel(0.4, 0.0), Eigen::Vector3d::Zero());
  ASSERT_TRUE(attitude.valid());
  attitude.reset();
  EXPECT_FALSE(attitude.valid());
  EXPECT_EQ(attitude.roll(), 0.0);
}

TEST(AttitudeEstimator, UpdateAllocatesNothing) {
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  hal::Cm730State imu;
  imu.accel_mps2 = {0.5, -0.3, 9.7};
  imu.gyro_rad_s = {0.1, 0.2, -0.1};
  test::start_counting_allocations();
  for (int i = 0; i < 100; ++i) attitude.update(imu);
  EXPECT_EQ(test::stop_counting_allocations(), 0u);
}

}  // namespace
}  // namespace stride::fw
