// Compliance compensation in the faithful world (identified MX servos, CM730 IMU, noise on):
// walking sideways with balance-identified.json, the soft servos let the swing foot drag through
// the grass in nearly every step; with walk.compliance.gain 1 it clears the grass. Deterministic
// (seed 1, 2 ms), so the figures are asserted as measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "read_file.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/swing_clearance.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

const std::filesystem::path kBalance =
    std::filesystem::path(STRIDE_SOURCE_DIR) / "firmware/config/balance-identified.json";

struct Sideways {
  bool fell = true;
  double median_clearance = 0.0;
  int steps = 0, grazing = 0;
};

Sideways walk_left(double compliance_gain) {
  test::TempDir dir;
  nlohmann::json params = nlohmann::json::parse(test::read_file(kBalance));
  params["walk.compliance.gain"] = compliance_gain;
  fw::FirmwareOptions options;
  options.params_file = dir.write("params.json", params.dump());
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create(options, firmware));
  WorldOptions world_options;
  world_options.seed = 1;
  world_options.imu = ImuOptions::noisy();
  world_options.imu.chain = ImuChain{};
  world_options.imu.chain.noise = true;
  world_options.servo.law = ServoLaw::kIdentified;
  world_options.control_period_ns = firmware->period_ns();
  std::unique_ptr<SimWorld> world;
  EXPECT_TRUE(SimWorld::create(world_options, world));
  SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(0.0, 1.0, 0.0));
  SwingClearance clearance;
  const double period = static_cast<double>(firmware->period_ns()) * 1e-9;
  const StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    clearance.observe(static_cast<double>(tick) * period, robot.world().ground_truth());
    return controller.step(sensors, tick);
  };
  EpisodeOptions episode;
  episode.duration_s = 12.0;
  Sideways out;
  out.fell = run_episode(robot, step, episode).fell;
  std::vector<double> c = clearance.clearance();
  std::sort(c.begin(), c.end());
  out.median_clearance = c.empty() ? 0.0 : c[c.size() / 2];
  out.steps = clearance.steps();
  out.grazing = clearance.grazing_steps();
  return out;
}

TEST(WalkCompliance, TheSwingFootClearsTheGrassWalkingSideways) {
  const Sideways sagging = walk_left(0.0);
  const Sideways compensated = walk_left(1.0);
  ASSERT_FALSE(sagging.fell);
  ASSERT_FALSE(compensated.fell);
  SCOPED_TRACE("sagging: " + std::to_string(sagging.grazing) + " of " +
               std::to_string(sagging.steps) + " steps graze, median clearance " +
               std::to_string(sagging.median_clearance) + " m; compensated: " +
               std::to_string(compensated.grazing) + " of " + std::to_string(compensated.steps) +
               ", " + std::to_string(compensated.median_clearance) + " m");
  ASSERT_GE(sagging.steps, 8);
  ASSERT_GE(compensated.steps, 8);
  // Planned lift at this speed: 35 mm (step.height 0.07 m x the slow fraction 0.5).
  EXPECT_LT(sagging.median_clearance, 0.015);
  EXPECT_GT(sagging.grazing, 0.8 * sagging.steps);
  EXPECT_GT(compensated.median_clearance, 0.028);
  EXPECT_LT(compensated.grazing, 0.2 * compensated.steps);
}

}  // namespace
}  // namespace stride::sim
