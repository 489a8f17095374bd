// First-order servo motion for the virtual bus (see virtual_bus_physics.hpp).
#include <algorithm>
#include <cmath>

#include "stride/hal/dynamixel/virtual_bus_physics.hpp"

namespace stride::hal::dxl {

FirstOrderPhysics::FirstOrderPhysics(const Options& options) : options_(options) {
  for (std::size_t i = 0; i < kServoCount; ++i) {
    states_[i].position_rad = options_.initial_rad[i];
    states_[i].temperature_c = options_.ambient_c;
    states_[i].voltage_v = options_.supply_v;
    commands_[i].goal_rad = options_.initial_rad[i];
  }
}

void FirstOrderPhysics::set_command(std::size_t index, const PhysicsServoCommand& command) {
  if (index < kServoCount) commands_[index] = command;
}

void FirstOrderPhysics::advance(double dt_s) {
  if (!(dt_s > 0.0)) return;
  for (std::size_t i = 0; i < kServoCount; ++i) {
    const PhysicsServoCommand& c = commands_[i];
    PhysicsServoState& s = states_[i];
    double speed = 0.0;
    double load = 0.0;
    if (c.torque_enabled && c.p_gain > 0.0 && std::isfinite(c.goal_rad)) {
      const double v_max =
          c.speed_limit_rad_s > 0.0
              ? std::min(c.speed_limit_rad_s, no_load_speed_rad_s(options_.models[i]))
              : no_load_speed_rad_s(options_.models[i]);
      const double tau = options_.tau_at_p32_s * 32.0 / c.p_gain;
      // Exact first-order step, then the speed clamp.
      const double error = c.goal_rad - s.position_rad;
      double step = error * (1.0 - std::exp(-dt_s / tau));
      step = std::clamp(step, -v_max * dt_s, v_max * dt_s);
      s.position_rad += step;
      speed = step / dt_s;
      const double limit = std::clamp(c.torque_limit, 0.0, 1.0);
      load = std::clamp((c.p_gain / 32.0) * (c.goal_rad - s.position_rad) / 0.5, -limit, limit);
    }
    s.speed_rad_s = speed;
    s.load = load;
    const double heating = 1.0 * load * load;  // K/s at full load
    s.temperature_c += dt_s * (heating - (s.temperature_c - options_.ambient_c) / 300.0);
    s.voltage_v = options_.supply_v;
  }
}

PhysicsServoState FirstOrderPhysics::servo_state(std::size_t index) const {
  return index < kServoCount ? states_[index] : PhysicsServoState{};
}

}  // namespace stride::hal::dxl
