// MagneticHeading and the heading hold with a magnetometer (the CM730 with NimbRo's firmware):
// the tilt-compensated heading, and a gyro bias the stand did not see, which turns the walk with
// the gyro alone but not with the magnetometer fused in; without a magnetometer the hold is the
// gyro-only one to the bit.
#include "stride/firmware/walk/magnetic_heading.hpp"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "stride/firmware/walk/heading_hold.hpp"

#include "fed_heading_hold.hpp"

namespace stride::fw {
namespace {

constexpr double kPeriod = 0.01;
constexpr double kPi = 3.14159265358979323846;

/// The Earth's field near Bonn (0.49 gauss, 66 deg down), magnetic north at `north` [rad].
Eigen::Vector3d earth_field(double north) {
  const double inclination = 66.0 * kPi / 180.0;
  return 0.49 * Eigen::Vector3d(std::cos(inclination) * std::cos(north),
                                std::cos(inclination) * std::sin(north), -std::sin(inclination));
}

Eigen::Matrix3d attitude(double yaw, double pitch, double roll) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// What the CM730 reads for a torso at `r` (torso to world) turning at `yaw_rate` about the
/// world's z, with a gyro bias about the torso's z.
hal::Cm730State reading(const Eigen::Matrix3d& r, double yaw_rate, double gyro_bias,
                        bool magnetometer, double north = 0.4) {
  hal::Cm730State s;
  const Eigen::Vector3d f = r.transpose() * Eigen::Vector3d(0, 0, 9.81);
  const Eigen::Vector3d w = r.transpose() * Eigen::Vector3d(0, 0, yaw_rate);
  const Eigen::Vector3d m = r.transpose() * earth_field(north);
  for (int k = 0; k < 3; ++k) {
    s.accel_mps2[static_cast<std::size_t>(k)] = f[k];
    s.gyro_rad_s[static_cast<std::size_t>(k)] = w[k] + (k == 2 ? gyro_bias : 0.0);
    s.mag_gauss[static_cast<std::size_t>(k)] = magnetometer ? m[k] : 0.0;
  }
  s.has_magnetometer = magnetometer;
  return s;
}

TEST(MagneticHeading, TiltCompensatedHeadingIsTheYawWhateverTheTilt) {
  const Eigen::Vector3d field = earth_field(0.0);
  for (const double yaw : {-2.5, -0.3, 0.0, 1.1, 3.0})
    for (const double pitch : {-0.3, 0.0, 0.2})
      for (const double roll : {-0.25, 0.0, 0.15}) {
        const Eigen::Vector3d m = attitude(yaw, pitch, roll).transpose() * field;
        const double psi =
            walk::MagneticHeading::tilt_compensated_heading({m.x(), m.y(), m.z()}, roll, pitch);
        EXPECT_NEAR(std::remainder(psi - yaw, 2.0 * kPi), 0.0, 1e-9)
            << yaw << " " << pitch << " " << roll;
      }
  // Levelled with the wrong tilt, the heading is off: the compensation matters at 66 deg.
  const Eigen::Vector3d m = attitude(0.0, 0.0, 0.1).transpose() * field;
  EXPECT_GT(
      std::abs(walk::MagneticHeading::tilt_compensated_heading({m.x(), m.y(), m.z()}, 0.0, 0.0)),
      0.15);
}

/// A heading hold fed as the walk feeds it (fed_heading_hold.hpp).
struct Hold : test::FedHeadingHold {
  explicit Hold(ParameterStore& store) : FedHeadingHold(store, kPeriod) {}
};

/// A walk of `seconds` after a 1 s stand, with the hold's correction turning the robot over
/// each 0.5 s step. The gyro reads a bias of `bias` rad/s once the walk starts (the stand saw
/// none: a drift the start-up calibration missed). Returns the robot's true heading change.
double walk_with_bias(double bias, bool magnetometer, double seconds, double bias_time = 0.0,
                      double* estimate = nullptr) {
  ParameterStore store;
  Hold fed(store);
  walk::HeadingHold& hold = fed.hold;
  EXPECT_TRUE(store.set_now({{"walk.balance.heading_mag_bias_time", bias_time}}).is_ok());
  hold.reset();
  const double pitch = 0.12;  // the walk's forward lean
  double yaw = 0.0;
  for (int i = 0; i < 100; ++i)
    fed.update(reading(attitude(yaw, pitch, 0.0), 0.0, 0.0, magnetometer), true, true);
  double turn_rate = 0.0;
  const int ticks_per_step = 50;
  const int ticks = static_cast<int>(seconds / kPeriod);
  for (int i = 0; i < ticks; ++i) {
    if (i % ticks_per_step == 0) turn_rate = hold.begin_step() / (ticks_per_step * kPeriod);
    // The torso also rolls to and fro with the steps (+-0.05 rad), as walking does.
    const double roll = 0.05 * std::sin(2.0 * kPi * i / (2.0 * ticks_per_step));
    yaw += turn_rate * kPeriod;
    fed.update(reading(attitude(yaw, pitch, roll), turn_rate, bias, magnetometer), false, true);
  }
  EXPECT_EQ(hold.using_magnetometer(), magnetometer);
  if (estimate != nullptr) *estimate = hold.heading_error();
  return yaw;
}

TEST(MagneticHeading, GyroBiasTurnsTheGyroOnlyWalkButNotTheFusedOne) {
  const double bias = 0.02;  // a third of the stock register's step
  const double gyro_only_30 = walk_with_bias(bias, false, 30.0);
  const double gyro_only_60 = walk_with_bias(bias, false, 60.0);
  // Gyro only: the hold steers the measured heading to 0, so the robot turns by -bias t,
  // without bound.
  EXPECT_LT(gyro_only_30, -0.4);
  EXPECT_LT(gyro_only_60, -1.0);
  // Fused (the defaults: heading_mag_time 10 s, no bias learning): the error stays near
  // -bias * 10 s = -0.2 rad however long the walk.
  const double fused_30 = walk_with_bias(bias, true, 30.0);
  const double fused_60 = walk_with_bias(bias, true, 60.0);
  EXPECT_NEAR(fused_30, -0.2, 0.04);
  EXPECT_NEAR(fused_60, -0.2, 0.03);
  // Learning the bias from the magnetometer (over 10 s) takes that error away too.
  double estimate = 0.0;
  const double learnt = walk_with_bias(bias, true, 60.0, 10.0, &estimate);
  EXPECT_LT(std::abs(learnt), 0.03);
  EXPECT_LT(std::abs(learnt - estimate), 0.03);
}

TEST(MagneticHeading, LearnsTheGyroBiasFromTheMagnetometer) {
  ParameterStore store;
  AttitudeEstimator attitude_estimate(store, kPeriod);
  walk::MagneticHeading heading(store, kPeriod);
  auto tick = [&](const hal::Cm730State& imu, bool calibrating) {
    attitude_estimate.update(imu);
    heading.update(attitude_estimate, imu, calibrating);
  };
  ASSERT_TRUE(store
                  .set_now({{"walk.balance.heading_mag_time", 2.0},
                            {"walk.balance.heading_mag_bias_time", 10.0}})
                  .is_ok());
  const Eigen::Matrix3d r = attitude(0.8, 0.1, -0.05);
  // The heading is measured from magnetic north (0.4 rad from the world's x here).
  for (int i = 0; i < 100; ++i) tick(reading(r, 0.0, 0.0, true, 0.4), true);
  EXPECT_NEAR(heading.heading(), 0.8 - 0.4, 1e-6);
  EXPECT_NEAR(heading.bias(), 0.0, 1e-12);
  for (int i = 0; i < 6000; ++i) tick(reading(r, 0.0, 0.03, true, 0.4), false);
  EXPECT_NEAR(heading.bias(), 0.03, 0.002);
  EXPECT_NEAR(heading.heading(), 0.8 - 0.4, 0.01);
  // The z bias turns the estimate's up direction about the torso's z until the accelerometer
  // pulls it back: 0.03 sin(0.1) rad/s over the 0.84 s time constant, about 3 mrad.
  EXPECT_NEAR(attitude_estimate.roll(), -0.05, 5e-3);
  EXPECT_NEAR(attitude_estimate.pitch(), 0.1, 5e-3);
}

TEST(MagneticHeading, WithoutAMagnetometerTheHoldIsTheGyroOnlyOneToTheBit) {
  ParameterStore plain_store, store;
  Hold fed_plain(plain_store), fed(store);
  walk::HeadingHold &plain = fed_plain.hold, &hold = fed.hold;
  // Off by its parameter: a reading with a field but heading_mag_time 0.
  ParameterStore off_store;
  Hold fed_off(off_store);
  walk::HeadingHold& off = fed_off.hold;
  ASSERT_TRUE(off_store.set_now({{"walk.balance.heading_mag_time", 0.0}}).is_ok());
  for (int i = 0; i < 1500; ++i) {
    const double gz = 0.013 * std::sin(0.01 * i) + 0.004;
    hal::Cm730State s;
    s.gyro_rad_s = {0.001 * i, 0.0, gz};
    hal::Cm730State with_field = s;
    with_field.mag_gauss = {0.3, -0.1 * std::cos(0.02 * i), -0.4};  // ignored: no magnetometer
    with_field.has_magnetometer = false;
    hal::Cm730State switched_off = s;
    switched_off.mag_gauss = with_field.mag_gauss;
    switched_off.has_magnetometer = true;
    const bool calibrating = i < 100, holding = i < 700 || i > 800;
    fed_plain.update(s, calibrating, holding);
    fed.update(with_field, calibrating, holding);
    fed_off.update(switched_off, calibrating, holding);
    ASSERT_EQ(plain.heading_error(), hold.heading_error()) << i;
    ASSERT_EQ(plain.heading_error(), off.heading_error()) << i;
    if (i % 50 == 0) {
      const double c = plain.begin_step();
      ASSERT_EQ(c, hold.begin_step()) << i;
      ASSERT_EQ(c, off.begin_step()) << i;
    }
  }
  EXPECT_FALSE(off.using_magnetometer());
}

}  // namespace
}  // namespace stride::fw
