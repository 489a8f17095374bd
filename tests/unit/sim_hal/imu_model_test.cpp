// Tests of the IMU chain (imu_model.hpp): chip rates and filters, CM730 averaging, register
// quantisation and range (L3G4200D, LIS331DLH datasheets; the igus CM730 firmware).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "stride/sim_hal/imu_model.hpp"

namespace stride::sim {
namespace {

const Eigen::Vector3d kUpright(0.0, 0.0, 9.81);

TEST(ImuModel, RegistersHoldMultiplesOfTheCm730Units) {
  ImuModel imu;
  imu.configure(ImuChain{});
  imu.reset(kUpright, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  WorldRng rng(3);
  const Eigen::Vector3d accel(0.3, -1.234, 9.81), gyro(0.1, -0.2, 0.05);
  for (int k = 0; k < 200; ++k) imu.step(accel, gyro, 0.001, rng);
  const ImuChain c;
  for (int i = 0; i < 3; ++i) {
    const double a = imu.accel()[i] / c.accel_register_lsb, g = imu.gyro()[i] / c.gyro_register_lsb;
    EXPECT_NEAR(a, std::round(a), 1e-9);
    EXPECT_NEAR(g, std::round(g), 1e-9);
    EXPECT_NEAR(imu.accel()[i], accel[i], 0.5 * c.accel_register_lsb + 1e-9);
    EXPECT_NEAR(imu.gyro()[i], gyro[i], 0.5 * c.gyro_register_lsb + 1e-9);
  }
}

TEST(ImuModel, AccelerometerUpdatesAtItsOutputDataRate) {
  ImuChain chain;
  chain.accel_register_lsb = 0.0;  // see the chip's own steps
  chain.cm730_average = 1;
  ImuModel imu;
  imu.configure(chain);
  imu.reset(kUpright, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  WorldRng rng(1);
  std::set<double> values;
  int changes = 0;
  double last = imu.accel().x();
  for (int k = 1; k <= 1000; ++k) {  // 0.5 s of a ramp at 0.5 ms steps
    imu.step(Eigen::Vector3d(0.01 * k, 0.0, 9.81), Eigen::Vector3d::Zero(), 0.0005, rng);
    if (imu.accel().x() != last) ++changes;
    last = imu.accel().x();
  }
  // 100 Hz for 0.5 s: about 50 new samples (not one per physics step).
  EXPECT_GE(changes, 45);
  EXPECT_LE(changes, 52);
}

TEST(ImuModel, Cm730AveragesItsLastFiveReadings) {
  ImuChain chain;
  chain.gyro_register_lsb = 0.0;
  chain.gyro.resolution = 0.0;
  chain.gyro.cutoff_hz = 1e6;  // no chip lag: the CM730 average alone
  ImuModel imu;
  imu.configure(chain);
  imu.reset(kUpright, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  WorldRng rng(1);
  for (int k = 0; k < 100; ++k) imu.step(kUpright, Eigen::Vector3d::Zero(), 0.0005, rng);
  // A rate step of 1 rad/s: after one CM730 read the register shows 1/5 of it, after five all.
  double after_first_read = -1.0, at_20ms = -1.0;
  for (int k = 1; k <= 60; ++k) {
    imu.step(kUpright, Eigen::Vector3d(1.0, 0.0, 0.0), 0.0005, rng);
    if (after_first_read < 0.0 && imu.gyro().x() > 0.0) after_first_read = imu.gyro().x();
    if (k == 40) at_20ms = imu.gyro().x();
  }
  EXPECT_NEAR(after_first_read, 0.2, 1e-9);
  EXPECT_NEAR(at_20ms, 1.0, 1e-9);
}

TEST(ImuModel, RangesClipAtFourGAndTheRegisterRange) {
  ImuModel imu;
  imu.configure(ImuChain{});
  imu.reset(kUpright, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  WorldRng rng(1);
  for (int k = 0; k < 200; ++k)
    imu.step(Eigen::Vector3d(60.0, 0.0, 9.81), Eigen::Vector3d(0.0, 0.0, 10.0), 0.001, rng);
  EXPECT_NEAR(imu.accel().x(), 4.0 * 9.80665, 0.04);        // LIS331DLH at +-4 g
  EXPECT_NEAR(imu.gyro().z(), 250.0 * M_PI / 180.0, 0.07);  // L3G4200D at +-250 dps
}

TEST(ImuModel, NoiseIsSeededAndOffWhenAskedOff) {
  auto run = [](bool noise, std::uint64_t seed) {
    ImuChain chain;
    chain.noise = noise;
    chain.accel_register_lsb = 0.0;
    ImuModel imu;
    imu.configure(chain);
    imu.reset(kUpright, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    WorldRng rng(seed);
    for (int k = 0; k < 100; ++k) imu.step(kUpright, Eigen::Vector3d::Zero(), 0.001, rng);
    return imu.accel().x();
  };
  EXPECT_EQ(run(false, 1), 0.0);
  EXPECT_EQ(run(true, 7), run(true, 7));
  EXPECT_NE(run(true, 7), run(true, 8));
  // White noise of 218 ug/sqrt(Hz) over the 74 Hz filter, averaged: well under 0.05 m/s^2.
  EXPECT_LT(std::abs(run(true, 7)), 0.05);
}

}  // namespace
}  // namespace stride::sim
