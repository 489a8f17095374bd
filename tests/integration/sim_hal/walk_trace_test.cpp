// Diagnostic trace of a simulated walk (run with --gtest_also_run_disabled_tests).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <gtest/gtest.h>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride {
namespace {

TEST(WalkInSimTrace, DISABLED_Trace) {
  const char* vx_env = std::getenv("TRACE_VX");
  const double vx = vx_env ? std::atof(vx_env) : 1.0;
  const char* dur_env = std::getenv("TRACE_T");
  const double duration = dur_env ? std::atof(dur_env) : 8.0;
  std::unique_ptr<fw::Firmware> firmware;
  ASSERT_TRUE(fw::Firmware::create({}, firmware));
  if (const char* p = std::getenv("TRACE_PARAMS")) {
    ASSERT_TRUE(firmware->params().load_file_now(p));
  }
  sim::WorldOptions options;
  options.seed = 1;
  options.imu = sim::ImuOptions::noisy();
  std::unique_ptr<sim::SimWorld> world;
  ASSERT_TRUE(sim::SimWorld::create(options, world));
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(vx, 0, 0));
  hal::SensorFrame sensors;
  for (hal::Tick t = 0; t < static_cast<hal::Tick>(duration * 100); ++t) {
    robot.read(sensors);
    const hal::CommandFrame c = controller.step(sensors, t);
    robot.write(c);
    robot.sleep_until(t + 1);
    if (t % 5 == 0) {
      const auto gt = robot.world().ground_truth();
      const Eigen::Matrix3d r = gt.torso.rotation();
      const double pitch = std::atan2(-r(2, 0), r(2, 2));
      const double roll = std::atan2(r(2, 1), r(2, 2));
      std::printf(
          "t %.2f st %d torso (%.3f %.3f %.3f) pitch %.3f roll %.3f com (%.3f %.3f) "
          "feet L(%.3f %.3f %.3f %d) R(%.3f %.3f %.3f %d) knee cmd %.3f act %.3f rhr %.3f/%.3f rar "
          "%.3f/%.3f lhr %.3f/%.3f\n",
          t * 0.01, static_cast<int>(controller.motion().state()), gt.torso.translation().x(),
          gt.torso.translation().y(), gt.torso.translation().z(), pitch, roll,
          gt.center_of_mass.x(), gt.center_of_mass.y(), gt.left_foot.translation().x(),
          gt.left_foot.translation().y(), gt.left_foot.translation().z(),
          gt.left_contact.points_in_contact, gt.right_foot.translation().x(),
          gt.right_foot.translation().y(), gt.right_foot.translation().z(),
          gt.right_contact.points_in_contact, c.servos[12].position_rad,
          sensors.servos[12].position_rad, c.servos[8].position_rad, sensors.servos[8].position_rad,
          c.servos[16].position_rad, sensors.servos[16].position_rad, c.servos[9].position_rad,
          sensors.servos[9].position_rad);
    }
  }
}

}  // namespace
}  // namespace stride
