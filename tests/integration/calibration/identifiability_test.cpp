// Identifiability of the calibration's values (issue 45, identifiability.hpp): the analysis
// finds two values that move the replayed log identically (the same value named twice) fully
// confounded and a bias of the accelerometer apart from a servo's torque; of the supply voltage
// and the MX-106's torque scale (both scale the motor torque, calibration.hpp) it finds them the
// most correlated pair; `stride calibrate --fit` refuses a pair correlated beyond
// --max-correlation with one line naming it, and fits a pair below it. The log: the nominal
// robot standing 4 s (noise off), replayed in one window of 3 s.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "expect_bad_input.hpp"
#include "stride/calibration/identifiability.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/sim_hal/servo_model.hpp"
#include "temp_dir.hpp"

namespace stride::calibration {
namespace {

const std::string kBin = STRIDE_BIN_DIR;

test::ChildRun stride(const test::TempDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), kBin + "/stride");
  return test::run_child(args, dir.path());
}

class Identifiability : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::TempDir>();
    log_path_ = dir_->path() / "stand.flog";
    const test::ChildRun run = stride(*dir_, {"identify", "--out", log_path_.string(), "--noise",
                                              "off", "--parts", "stand", "--stand-s", "4"});
    ASSERT_EQ(run.code, 0) << run.err;
    log_ = std::make_unique<fw::FlightLog>();
    ASSERT_TRUE(fw::read_flight_log(log_path_, *log_));
  }
  static void TearDownTestSuite() {
    log_.reset();
    dir_.reset();
  }

  static IdentifiabilityResult analyse(const std::vector<std::string>& names) {
    sim::WorldOptions world;
    world.imu.set_noise(false);  // as stride calibrate replays
    IdentifiabilityOptions options;
    options.names = names;
    options.replay.window_s = 3.0;
    IdentifiabilityResult result;
    EXPECT_TRUE(analyse_identifiability({log_.get()}, world, sim::WorldFile{}, options, result));
    return result;
  }

  static std::unique_ptr<test::TempDir> dir_;
  static std::filesystem::path log_path_;
  static std::unique_ptr<fw::FlightLog> log_;
};
std::unique_ptr<test::TempDir> Identifiability::dir_;
std::filesystem::path Identifiability::log_path_;
std::unique_ptr<fw::FlightLog> Identifiability::log_;

TEST_F(Identifiability, TheSensorNoiseIsTheModelsQuantisationAndChipNoise) {
  sim::WorldOptions world;
  const SensorNoise n = sensor_noise(world);
  EXPECT_DOUBLE_EQ(n.position_rad, sim::kEncoderRadPerTick / std::sqrt(12.0));
  // The CM730 register's LSB (1800 deg/s / 512, 4 g / 512) dominates the chips' white noise.
  const double gyro_lsb = 1800.0 * M_PI / 180.0 / 512.0, accel_lsb = 4.0 * 9.80665 / 512.0;
  EXPECT_GT(n.gyro_rad_s, gyro_lsb / std::sqrt(12.0));
  EXPECT_LT(n.gyro_rad_s, 1.1 * gyro_lsb / std::sqrt(12.0));
  EXPECT_GT(n.accel_mps2, accel_lsb / std::sqrt(12.0));
  EXPECT_LT(n.accel_mps2, 1.5 * accel_lsb / std::sqrt(12.0));
}

TEST_F(Identifiability, AValueNamedTwiceIsConfoundedAndABiasIsNot) {
  const IdentifiabilityResult r = analyse({"torque_mx106", "torque_mx106", "accel_bias_x"});
  ASSERT_EQ(r.values.size(), 3U);
  EXPECT_EQ(r.parts, std::vector<std::string>{"stand"});
  EXPECT_EQ(r.replays, 1 + 2 + 2 + 2);
  for (const ValueIdentifiability& v : r.values) EXPECT_GT(v.total, 0.0) << v.name;
  // The same column twice: the two estimates trade one for the other exactly.
  EXPECT_LT(r.correlation(0, 1), -0.999);
  EXPECT_LT(r.correlation_floor(0, 1), -0.999);
  EXPECT_LT(std::abs(r.correlation(0, 2)), 0.2);
  EXPECT_LT(std::abs(r.correlation_floor(0, 2)), 0.2);
  EXPECT_EQ(r.values[2].sensor.partner, "torque_mx106");
  EXPECT_LT(std::abs(r.values[2].sensor.correlation), 0.2);
  // Alone it is as well determined as the bias is; together not at all.
  EXPECT_GT(r.values[0].sensor.standard_error, 100.0 * r.values[0].sensor.alone_error);
  EXPECT_LT(r.values[2].sensor.standard_error, 1.1 * r.values[2].sensor.alone_error);
  const std::vector<ConfoundedPair> pairs = confounded_pairs(r, 0.95);
  ASSERT_EQ(pairs.size(), 1U);
  EXPECT_EQ(pairs[0].first, "torque_mx106");
  EXPECT_EQ(pairs[0].second, "torque_mx106");
}

TEST_F(Identifiability, TheVoltageAndTheTorqueScaleAreTheMostCorrelatedPair) {
  const IdentifiabilityResult r = analyse({"torque_mx106", "voltage", "accel_bias_x"});
  // Both scale the motor torque (more of either holds the robot the same way): the estimates
  // trade, r < 0; the accelerometer's bias moves only the accelerometer.
  EXPECT_LT(r.correlation(0, 1), -0.2);
  EXPECT_GT(std::abs(r.correlation(0, 1)), 2.0 * std::abs(r.correlation(0, 2)));
  EXPECT_GT(std::abs(r.correlation(0, 1)), 2.0 * std::abs(r.correlation(1, 2)));
  EXPECT_EQ(r.values[0].sensor.partner, "voltage");
  EXPECT_TRUE(confounded_pairs(r, 0.95).empty());
  const std::vector<ConfoundedPair> loose = confounded_pairs(r, 0.15);
  ASSERT_FALSE(loose.empty());
  EXPECT_EQ(loose[0].first + "," + loose[0].second, "torque_mx106,voltage");
}

TEST_F(Identifiability, CalibrateRefusesAConfoundedPairAndFitsASeparableOne) {
  test::TempDir dir;
  const auto out = dir.path() / "w.json";
  const std::vector<std::string> common = {
      "calibrate", log_path_.string(), "--out", out.string(),  "--window",
      "3",         "--subsets",        "0",     "--max-evals", "3"};
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--fit", "torque_mx106,voltage", "--max-correlation", "0.15"});
  test::expect_bad_input(stride(dir, args),
                         "--fit: torque_mx106 and voltage cannot be told apart on these logs");
  EXPECT_FALSE(std::filesystem::exists(out));
  args.push_back("--allow-confounded");
  test::ChildRun run = stride(dir, args);
  EXPECT_EQ(run.code, 0) << run.err;
  EXPECT_TRUE(std::filesystem::exists(out));
  std::filesystem::remove(out);
  args = common;  // the default threshold, 0.95
  args.insert(args.end(), {"--fit", "torque_mx106,accel_bias_x"});
  run = stride(dir, args);
  EXPECT_EQ(run.code, 0) << run.err;
  // --identifiability prints the table and writes nothing.
  std::filesystem::remove(out);
  run = stride(dir, {"calibrate", log_path_.string(), "--window", "3", "--fit",
                     "torque_mx106,voltage", "--identifiability"});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.out.find("torque_mx106"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("stand"), std::string::npos) << run.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace stride::calibration
