// Standing still, the IMU reads what a still robot's IMU reads (issue 20 point 3): with the
// identified MX servo and the CM730 IMU chain, noise off, the field-plane reading
// sqrt(ax^2 + ay^2) varies by at most 0.3 m/s^2 peak to peak over 10 s after 1 s of settling,
// and so does the torso's true acceleration, at the 2 ms and the 0.5 ms step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {
namespace {

struct Spread {
  double reading_min = 1e9, reading_max = -1e9;
  double true_accel_max = 0.0;  ///< largest |a| of the torso at a tick's last physics step
};

Spread stand_still(std::int64_t physics_step_ns) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  WorldOptions options;
  options.physics_step_ns = physics_step_ns;
  options.control_period_ns = firmware->period_ns();
  options.servo.law = ServoLaw::kIdentified;
  options.imu.chain = ImuChain{};  // the chips and the CM730, noise off
  std::unique_ptr<SimWorld> world;
  const Status created = SimWorld::create(options, world);
  EXPECT_TRUE(created) << created.message();
  SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  Spread spread;
  hal::SensorFrame sensors;
  for (hal::Tick tick = 0; tick < 1100; ++tick) {
    robot.read(sensors);
    robot.write(controller.step(sensors, tick));
    robot.sleep_until(tick + 1);
    const SimWorld& w = robot.world();
    EXPECT_EQ(w.status(), WorldStatus::kRunning) << w.failure_reason();
    if (tick >= 100) {
      // A step-to-step chatter shows in any one step's acceleration.
      spread.true_accel_max =
          std::max(spread.true_accel_max, w.ground_truth().torso_linear_acceleration.norm());
      const Eigen::Vector3d a = w.imu().accel;
      const double reading = std::hypot(a.x(), a.y());
      spread.reading_min = std::min(spread.reading_min, reading);
      spread.reading_max = std::max(spread.reading_max, reading);
    }
  }
  return spread;
}

TEST(ImuQuiet, StandingStillTheFieldPlaneReadingAndTheTorsoStayQuiet) {
  for (const std::int64_t step_ns : {2'000'000, 500'000}) {
    const Spread s = stand_still(step_ns);
    std::printf("  step %lld us: field-plane reading %.3f..%.3f m/s^2, true |a| max %.3f\n",
                static_cast<long long>(step_ns / 1000), s.reading_min, s.reading_max,
                s.true_accel_max);
    EXPECT_LE(s.reading_max - s.reading_min, 0.3) << "step " << step_ns << " ns";
    EXPECT_LE(s.true_accel_max, 0.3) << "step " << step_ns << " ns";
  }
}

}  // namespace
}  // namespace stride::sim
