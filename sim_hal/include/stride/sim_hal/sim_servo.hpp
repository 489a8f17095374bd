// SimServo: one simulated Dynamixel behind the HAL's registers, whatever its law. SimWorld holds
// twenty of them and steps each with its joint's angle and speed every physics step; the law is
// chosen by name in one place (make_sim_servo, WorldOptions::servo.law):
//   ServoLaw::kSeed        the seed's Gazebo figures, ServoModel (servo_model.hpp);
//   ServoLaw::kIdentified  the MX-64/MX-106 identified from the e-manual and the BAM tables,
//                          MxServo (mx_servo.hpp).
// Units: rad, rad/s, N m, s, V. Real-time: set_command and step run every control period and
// physics step; they allocate nothing.
#pragma once

#include <cstdint>
#include <memory>

#include "stride/firmware/servo_table.hpp"
#include "stride/hal/command_frame.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

/// What a servo is built from at each reset.
struct ServoSetup {
  fw::ServoModel model = fw::ServoModel::kMx106;
  double supply_voltage_v = 14.8;
  /// Stall torque scale: the reset's randomised strength times the calibration's torque scale.
  double strength = 1.0;
  double friction_scale = 1.0;  ///< RobotCalibration::friction_scale
  const ServoOptions* options = nullptr;
  const JointSpec* joint = nullptr;  ///< its end stops
};

class SimServo {
 public:
  virtual ~SimServo() = default;
  /// The reflected rotor inertia the engine adds to the joint [kg m^2] (fixed per world).
  virtual double armature(fw::ServoModel model, double supply_voltage_v,
                          const ServoOptions& options) const = 0;
  /// Rebuilds the law's parameters and rests at `q` holding `hold` (a reset).
  virtual void reset(const ServoSetup& setup, double q, const hal::ServoCommand& hold) = 0;
  /// The registers that act from now on; `enabled` is torque enable after the emergency stop.
  virtual void set_command(const hal::ServoCommand& command, bool enabled) = 0;
  /// Joint torque over the next physics step of length h, at joint angle q and speed w.
  virtual double step(double q, double w, double h) = 0;
  /// Present load register, signed fraction [-1, 1].
  virtual double load() const = 0;
  /// The motor's torque at the output over the last step [N m], unclipped: what the gear train
  /// carries from the motor (a back-driven motor brakes with more than its stall torque).
  virtual double motor_torque_nm() const = 0;
  virtual double temperature_c() const = 0;
  /// Folds the servo's own state (set-point, backlash) into a state hash (fnv1a).
  virtual std::uint64_t hash(std::uint64_t seed) const = 0;
};

/// The servo of a law.
std::unique_ptr<SimServo> make_sim_servo(ServoLaw law);

}  // namespace stride::sim
