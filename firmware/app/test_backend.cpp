// The `test` HAL backend of stride-fw: the scripted test HAL with an ideal servo echo, paced
// by the real clock. Runs the firmware loop without a robot (the quick-start demo).
#include "stride/firmware/hal_registry.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace {

void declare(stride::core::CliArgs&) {}

stride::Status make(const stride::core::CliArgs&, std::int64_t period_ns,
                    stride::fw::HalInstance& out) {
  stride::hal::ScriptedRobot::Options options;
  options.period_ns = period_ns;
  options.echo_commands = true;
  options.record_capacity = 0;
  out.robot = std::make_unique<stride::hal::ScriptedRobot>(
      options, std::vector<stride::hal::SensorFrame>{stride::hal::ScriptedRobot::standing_frame()});
  out.paced_by_clock = true;
  return {};
}

}  // namespace

STRIDE_HAL_BACKEND(test, "scripted test HAL (ideal servos, robot standing still)", declare, nullptr,
                   make);
