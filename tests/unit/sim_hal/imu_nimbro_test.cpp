// The simulated CM730 with NimbRo's firmware (`--imu cm730-nimbro`): 16-bit registers at its
// scales (igus.md 6.5) and the magnetometer model (magnetometer_model.hpp: Earth field,
// floor disturbance, hard iron, HMC5883L noise and 1/820 gauss steps).
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "stride/sim_hal/imu_model.hpp"
#include "stride/sim_hal/imu_sampler.hpp"
#include "stride/sim_hal/magnetometer_model.hpp"
#include "stride/sim_hal/world_options.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
const Eigen::Vector3d kUpright(0.0, 0.0, 9.81);

bool on_grid(double value, double lsb) {
  const double n = value / lsb;
  return std::abs(n - std::round(n)) < 1e-6;
}

TEST(ImuNimbro, GyroReadsABiasThatTheStockRegisterRoundsAway) {
  const Eigen::Vector3d bias(0.004, -0.007, 0.011);  // all under half a stock step (0.031)
  for (const bool nimbro : {false, true}) {
    ImuModel imu;
    imu.configure(nimbro ? ImuChain::cm730_nimbro() : ImuChain{});
    imu.reset(kUpright, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), bias);
    WorldRng rng(5);
    for (int k = 0; k < 100; ++k) imu.step(kUpright, Eigen::Vector3d::Zero(), 0.002, rng);
    const ImuChain& c = imu.chain();
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(on_grid(imu.gyro()[i], c.gyro_register_lsb)) << i;
      EXPECT_TRUE(on_grid(imu.accel()[i], c.accel_register_lsb)) << i;
      if (nimbro) {
        // The chip's own step (8.75 mdps) and the register's (7.6 mdps) bound the error.
        EXPECT_NEAR(imu.gyro()[i], bias[i], 0.00015 + 0.5 * c.gyro_register_lsb) << i;
      } else {
        EXPECT_EQ(imu.gyro()[i], 0.0) << i;
      }
    }
  }
  EXPECT_NEAR(ImuChain::cm730_nimbro().gyro_register_lsb, 1.3315805e-4, 1e-10);
  EXPECT_NEAR(ImuChain::cm730_nimbro().accel_register_lsb * 8192.0, 9.81, 1e-12);
  EXPECT_TRUE(ImuChain::cm730_nimbro().magnetometer.present);
  EXPECT_FALSE(ImuChain{}.magnetometer.present);
}

MagnetometerSpec quiet_spec() {
  MagnetometerSpec s;
  s.present = true;
  s.hard_iron_std_gauss = 0.0;
  s.disturbance_gauss = 0.0;
  return s;
}

TEST(Magnetometer, ReadsTheEarthFieldRotatedIntoTheTorsoInRegisterSteps) {
  MagnetometerModel m;
  const Eigen::Matrix3d yaw = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  m.reset(quiet_spec(), 42, yaw, Eigen::Vector3d::Zero(), false);
  const Eigen::Vector3d earth = m.earth_field();
  // 0.49 gauss at 66 deg inclination, pointing down.
  EXPECT_NEAR(earth.norm(), 0.49, 1e-12);
  EXPECT_NEAR(std::atan2(-earth.z(), earth.head<2>().norm()), 66.0 * kPi / 180.0, 1e-12);
  const Eigen::Vector3d expected = yaw.transpose() * earth;
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(on_grid(m.reading()[k], 1.0 / 820.0)) << k;
    EXPECT_NEAR(m.reading()[k], expected[k], 0.5 / 820.0 + 1e-12) << k;
  }
  // The heading of the reading turns with the torso: yaw 0.7 rad less in the torso frame.
  const double north_world = std::atan2(earth.y(), earth.x());
  const double north_torso = std::atan2(m.reading().y(), m.reading().x());
  EXPECT_NEAR(std::remainder(north_world - north_torso - 0.7, 2.0 * kPi), 0.0, 0.01);
}

TEST(Magnetometer, SamplesAndHoldsAtItsRateWithItsNoiseFloor) {
  MagnetometerSpec spec = quiet_spec();
  spec.resolution_gauss = spec.register_lsb_gauss = 0.0;  // see the noise itself
  MagnetometerModel m;
  m.reset(spec, 7, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), true);
  int changes = 0;
  double sum = 0.0, sum2 = 0.0;
  Eigen::Vector3d last = m.reading();
  const int periods = 3000;  // 30 s at 100 Hz
  for (int k = 0; k < periods; ++k) {
    m.sample(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), 0.01);
    if (m.reading() != last) ++changes;
    last = m.reading();
    const double n = m.reading().x() - m.earth_field().x();
    sum += n;
    sum2 += n * n;
  }
  EXPECT_NEAR(changes, 75 * 30, 5);  // 75 Hz, not 100
  const double std_dev = std::sqrt(sum2 / periods - (sum / periods) * (sum / periods));
  EXPECT_NEAR(std_dev, 0.002, 0.0003);
}

TEST(Magnetometer, FloorDisturbanceAndHardIronHaveTheirStatedSize) {
  MagnetometerSpec spec;
  spec.present = true;
  double largest = 0.0;
  Eigen::Vector3d sum_hard = Eigen::Vector3d::Zero();
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    MagnetometerModel m;
    m.reset(spec, seed, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), false);
    sum_hard += m.hard_iron().cwiseAbs2();
    for (double x = 0.0; x < 6.0; x += 0.05) {
      const Eigen::Vector3d d = m.world_field({x, 0.3 * x, 0.5}) - m.earth_field();
      largest = std::max({largest, std::abs(d.x()), std::abs(d.y())});
      EXPECT_LE(std::abs(d.z()), 0.5 * spec.disturbance_gauss + 1e-12);
    }
  }
  EXPECT_LE(largest, spec.disturbance_gauss + 1e-12);
  EXPECT_GT(largest, 0.95 * spec.disturbance_gauss);
  const Eigen::Vector3d rms = (sum_hard / 200.0).cwiseSqrt();
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(rms[k], spec.hard_iron_std_gauss, 0.003) << k;
}

TEST(Magnetometer, SamplerGivesAFieldOnlyToTheNimbroChainAndKeepsTheWorldStream) {
  for (const ImuKind kind : {ImuKind::kCm730, ImuKind::kCm730Nimbro}) {
    WorldOptions o;
    o.use_imu(kind);
    EXPECT_EQ(o.imu_kind(), kind);
    ImuSampler sampler;
    MagnetometerStart start;
    start.seed = 99;
    sampler.reset(o.imu, 9.81, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                  Eigen::Matrix3d::Identity(), start);
    WorldRng rng(3);
    TorsoMotion still;
    for (int k = 0; k < 10; ++k) {
      sampler.feed(still, 0.002, rng);
      sampler.sample(still, rng);
    }
    EXPECT_EQ(sampler.reading().has_mag, kind == ImuKind::kCm730Nimbro);
    EXPECT_EQ(sampler.reading().mag.norm() > 0.4, kind == ImuKind::kCm730Nimbro);
    // The magnetometer draws nothing from the world's generator.
    WorldRng expected(3);
    ImuModel chain;
    chain.configure(o.imu.chain);
    chain.reset(kUpright, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                Eigen::Vector3d::Zero());
    for (int k = 0; k < 10; ++k) chain.step(kUpright, Eigen::Vector3d::Zero(), 0.002, expected);
    EXPECT_EQ(rng.next_u64(), expected.next_u64());
  }
}

TEST(ImuNimbro, WorldOptionsNameTheProfileAndTheFloorField) {
  WorldSpec spec;
  ASSERT_TRUE(spec.set("imu", "cm730-nimbro", "--imu").is_ok());
  ASSERT_TRUE(spec.set("mag_disturbance", "0.01", "--mag-disturbance").is_ok());
  const WorldOptions o = spec.to_options();
  EXPECT_EQ(o.imu_kind(), ImuKind::kCm730Nimbro);
  EXPECT_TRUE(o.imu.chain.noise);  // --noise on by default, kept by the chain's swap
  EXPECT_EQ(o.imu.chain.magnetometer.disturbance_gauss, 0.01);
  const nlohmann::json j = to_json(spec);
  EXPECT_EQ(j.at("imu"), "cm730-nimbro");
  EXPECT_EQ(j.at("mag_disturbance"), 0.01);
  const Status bad = spec.set("imu", "nimbro", "--imu");
  EXPECT_EQ(bad.message(), "--imu: expected ideal, cm730 or cm730-nimbro, got 'nimbro'");
  EXPECT_FALSE(spec.set("mag_disturbance", "-0.1", "--mag-disturbance").is_ok());
  EXPECT_EQ(spec.to_options().imu_kind(), ImuKind::kCm730Nimbro);   // unchanged by the errors
  EXPECT_EQ(WorldSpec{}.to_options().imu_kind(), ImuKind::kCm730);  // the default world's
}

}  // namespace
}  // namespace stride::sim
