// ServoModel: the Dynamixel MX-64 / MX-106 as a joint torque source (pure, no Simbody).
//
// Per physics step of length h:
//  1. Moving-speed limit: an internal set-point moves towards the goal at the moving speed
//     (0 = no speed control: the set-point jumps to the goal), like the MX firmware.
//  2. P control on the encoder reading: tau_p = Kp * (set-point - quantised q), with
//     Kp = kp_per_register * P  [N m/rad]. The MX computes P/8 in internal units; the scale
//     from the register to N m/rad is a model choice (see sim_hal/models/README.md).
//  3. Saturation on the torque-speed line of the DC motor at the battery voltage:
//     -tau_s (1 + w/w0) <= tau <= tau_s (1 - w/w0), and |tau| <= torque_limit * tau_s,
//     with tau_s the stall torque and w0 the no-load speed at that voltage (igus.md 6.1).
//  4. Friction: viscous -b w and Coulomb -c sgn(w), the Coulomb part limited to what stops the
//     reflected rotor inertia within one step (a stable form of stiction for explicit steps).
//  5. A joint stop: a stiff spring-damper beyond the position limits (mechanical end stop).
// Rotor inertia (J_rotor N^2) is added to the model's mass matrix by SimWorld, not here.
#pragma once

#include <cstdint>

#include "stride/firmware/servo_table.hpp"

namespace stride::sim {

/// Encoder resolution: 4096 ticks per revolution.
inline constexpr double kEncoderRadPerTick = 2.0 * 3.14159265358979323846 / 4096.0;
/// Moving-speed register: 1023 * 0.114 rpm at most [rad/s].
inline constexpr double kMaxMovingSpeedRadS = 1023.0 * 0.114 * 2.0 * 3.14159265358979323846 / 60.0;

double quantise_encoder(double angle_rad);

/// Stall torque and no-load speed of a servo model at a supply voltage, interpolated linearly
/// through the e-manual figures of the MX motor table (fw::mx_motor: stall torque and no-load
/// speed at 11.1/12/14.8 V) and extrapolated beyond them; the gear ratio from the same table.
struct MotorCurve {
  double stall_torque_nm = 0.0;
  double no_load_speed_rad_s = 0.0;
  double gear_ratio = 0.0;
};
MotorCurve motor_curve(fw::ServoModel model, double voltage_v);

struct ServoParams {
  double stall_torque_nm = 10.0;        ///< at the battery voltage (after strength scaling)
  double no_load_speed_rad_s = 5.76;    ///< at the battery voltage
  double kp_per_register = 4.0 / 2.54;  ///< N m/rad per P register unit (seed: 4 g, P = 2.54 g)
  double viscous_friction = 1.0;        ///< b [N m s/rad] (seed: damping 1)
  double coulomb_friction = 0.5;        ///< c [N m] (seed: friction 0.5)
  double reflected_inertia = 0.003;     ///< J_rotor N^2 [kg m^2]: bounds the stiction torque
  bool limited = false;
  double lower = 0.0, upper = 0.0;  ///< end stops [rad]
  double stop_stiffness = 500.0;    ///< [N m/rad] beyond the end stop
  double stop_damping = 2.0;        ///< [N m s/rad] beyond the end stop
  double ambient_temperature_c = 30.0;
  double thermal_rise_c = 45.0;  ///< steady rise at stall torque [deg C]
  double thermal_time_constant_s = 120.0;
};

/// The commanded registers (a subset of hal::ServoCommand).
struct ServoInput {
  double goal_rad = 0.0;
  double moving_speed_rad_s = 0.0;  ///< 0 = no speed control
  double p_gain = 32.0;             ///< register units
  double torque_limit = 1.0;        ///< fraction of stall torque
  bool torque_enable = false;
};

class ServoModel {
 public:
  void configure(const ServoParams& params) { params_ = params; }
  const ServoParams& params() const { return params_; }
  /// Starts at rest at angle q with the set-point on q.
  void reset(double q);
  void set_input(const ServoInput& input) { input_ = input; }
  const ServoInput& input() const { return input_; }

  /// Advances the set-point and temperature by h and returns the joint torque [N m] for
  /// joint angle q and speed w. Stores the motor torque for load().
  double step(double q, double w, double h);

  double setpoint() const { return setpoint_; }
  double motor_torque() const { return motor_torque_; }
  /// Present load: motor torque as a signed fraction of the stall torque.
  double load() const;
  double temperature_c() const { return temperature_c_; }
  void set_setpoint(double s) { setpoint_ = s; }

 private:
  ServoParams params_{};
  ServoInput input_{};
  double setpoint_ = 0.0;
  double motor_torque_ = 0.0;
  double temperature_c_ = 30.0;
};

}  // namespace stride::sim
