// MxServo: the Dynamixel MX-64 / MX-106 as identified on a bench, a joint torque source that
// does not depend on the physics engine (pure arithmetic, no allocation, no I/O).
//
// The law (../shared/robot/servos.md; Rhoban BAM, Duclusaud & Passault, ICRA 2025,
// arXiv 2410.08650; the motor's figures from the MX motor table, firmware mx_motor.hpp), per
// physics step of length h:
//  1. Moving speed: an internal set-point moves towards the goal at the Moving Speed register's
//     rate (0 = no speed control: it jumps to the goal), as the MX firmware does.
//  2. Firmware P law on the output encoder (4096 ticks/rev, quantised):
//        duty = clip(0.158 * P * (set-point - encoder), +-0.9625 * torque_limit)
//     0.158 and 0.9625 were measured with an oscilloscope by Rhoban (BAM's MX actuator); the
//     Torque Limit register scales the largest duty, which is how the MX firmware limits it.
//  3. DC motor with back-EMF, seen at the output shaft, at the supply voltage V:
//        tau_m = kt (duty V - drop - kt w) / R
//     `drop` is a driver voltage loss of 0.27 V (same sign as duty V, never reversing it),
//     fitted here to BAM's no-load speed table (velocity_mx106: 2-15 V); it is not part of
//     BAM's identification. Back-EMF damping kt^2/R acts at every speed, not only in
//     saturation. Torque off: the bridge coasts, tau_m = 0.
//  4. Friction as a budget (BAM's M6 model; M1-M5 are M6 with terms zeroed):
//        F = f_base + |lfe tau_e - lfm tau_m| + s (f_s + |lfes tau_e - lfms tau_m|)
//            + s [quadratic load terms when tau_e and tau_m oppose] + k_v |w|,
//        s = exp(-|w / w_s|^alpha)   (Stribeck: 1 at rest, 0 when moving fast)
//     tau_e is the external torque on the joint (gravity, the rest of the body). The friction
//     torque is the torque that would stop the joint within this step, clipped to +-F: it can
//     stop the joint but never drive it.
//  5. Gearbox backlash (0.33 deg, the e-manual): the motor side takes up the gap before the
//     motor torque reaches the output. While crossing, the armature moves alone under tau_m
//     (a kinematic gap state); the output gets no motor torque, only friction.
//  6. Mechanical end stops beyond the joint limits (spring-damper), and a first-order thermal
//     model for Present Temperature.
// The armature (reflected rotor and gearbox inertia about the joint axis, identified by BAM)
// belongs to the multibody model: the engine adds it to the joint; `armature` here is the
// figure it should use, and the inertia the stopping torque of step 4 is computed with.
#pragma once

#include "stride/firmware/mx_motor.hpp"
#include "stride/firmware/servo_table.hpp"

namespace stride::sim {

/// Identified friction terms (BAM M6; set terms to 0 for simpler models).
struct MxFriction {
  double base_nm = 0.0;                  ///< friction_base [N m]
  double stribeck_nm = 0.0;              ///< friction_stribeck [N m]
  double stribeck_speed_rad_s = 1.0;     ///< dtheta_stribeck [rad/s]
  double stribeck_alpha = 1.0;           ///< alpha (curvature)
  double viscous_nm_s = 0.0;             ///< friction_viscous [N m s/rad]
  double load_motor = 0.0;               ///< load_friction_motor
  double load_external = 0.0;            ///< load_friction_external
  double load_motor_stribeck = 0.0;      ///< load_friction_motor_stribeck
  double load_external_stribeck = 0.0;   ///< load_friction_external_stribeck
  double load_motor_quadratic = 0.0;     ///< load_friction_motor_quad [1/(N m)]
  double load_external_quadratic = 0.0;  ///< load_friction_external_quad [1/(N m)]

  /// Every friction torque times `s` (RobotCalibration::friction_scale): the constant terms and
  /// the load-dependent fractions; the Stribeck speed and curvature are kept.
  void scale(double s) {
    base_nm *= s;
    stribeck_nm *= s;
    viscous_nm_s *= s;
    load_motor *= s;
    load_external *= s;
    load_motor_stribeck *= s;
    load_external_stribeck *= s;
    load_motor_quadratic *= s;
    load_external_quadratic *= s;
  }
};

struct MxServoParams {
  // Motor and driver.
  // Defaults: the MX-106 (BAM M6) of the MX motor table (fw::mx_motor).
  double torque_constant = fw::kMx106.m6.torque_constant;  ///< kt [N m/A = V s/rad] at the output
  double resistance_ohm = fw::kMx106.m6.resistance_ohm;    ///< R [ohm]
  double armature_kg_m2 = fw::kMx106.m6.armature_kg_m2;    ///< reflected inertia about the joint
  double supply_voltage_v = fw::kMxNominalSupplyV;         ///< the robot's 4S LiPo, nominal
  double error_gain = fw::kMxErrorGain;                    ///< duty per (P register x rad)
  double max_duty = fw::kMxMaxDuty;                        ///< largest PWM duty the firmware sets
  double driver_drop_v = 0.27;  ///< bridge voltage loss (fitted to the speed table)
  double strength = 1.0;        ///< scales the motor torque (world randomisation)
  MxFriction friction{};
  double backlash_rad = fw::kMxBacklashRad;  ///< total play (20 arcmin)
  // Joint end stops.
  bool limited = false;
  double lower = 0.0, upper = 0.0;  ///< [rad]
  double stop_stiffness = 500.0;    ///< [N m/rad] beyond the end stop
  double stop_damping = 2.0;        ///< [N m s/rad] beyond the end stop
  // Present Temperature.
  double ambient_temperature_c = 30.0;
  double thermal_rise_c = 45.0;  ///< steady rise at stall torque [deg C]
  double thermal_time_constant_s = 120.0;

  /// Stall torque at full duty at the supply voltage [N m] (what Present Load is relative to).
  double stall_torque_nm() const;
  /// No-load speed at full duty without friction [rad/s].
  double no_load_speed_rad_s() const;
};

/// Which published identification to use.
enum class MxFrictionModel { kM1, kM6 };

/// The published parameters of `model` at `supply_voltage_v`: BAM's identified M6 (servos.md)
/// or M1 (Coulomb-viscous; BAM params mx106/m1.json, mx64/m1.json).
MxServoParams mx_servo_params(fw::ServoModel model, double supply_voltage_v,
                              MxFrictionModel friction = MxFrictionModel::kM6);

/// Registers that drive the servo (a subset of hal::ServoCommand).
struct MxServoInput {
  double goal_rad = 0.0;
  double moving_speed_rad_s = 0.0;  ///< 0 = no speed control
  double p_gain = 32.0;             ///< P register, 0-254
  double torque_limit = 1.0;        ///< fraction of the largest duty, 0-1
  bool torque_enable = false;
};

/// What one step produced (for load, logging and the bench).
struct MxServoOutput {
  double duty = 0.0;             ///< PWM duty the firmware set, signed
  double motor_torque = 0.0;     ///< tau_m at the output [N m]
  double friction_torque = 0.0;  ///< applied friction [N m]
  double joint_torque = 0.0;     ///< what reaches the joint: transmitted motor + friction + stop
};

class MxServo {
 public:
  void configure(const MxServoParams& params) { params_ = params; }
  const MxServoParams& params() const { return params_; }
  /// At rest at joint angle q, set-point on q, backlash gap centred.
  void reset(double q);
  void set_input(const MxServoInput& input) { input_ = input; }
  const MxServoInput& input() const { return input_; }

  /// Advances the set-point, backlash and temperature by h [s] and returns the torque on the
  /// joint for angle q [rad], speed w [rad/s] and the external torque tau_e [N m] that the rest
  /// of the system applies to the joint (gravity on a bench; an estimate in a multibody world).
  /// `joint_inertia` is the inertia the stopping torque is computed with [kg m^2] (at least
  /// the armature; pass 0 to use the armature alone).
  double step(double q, double w, double external_torque, double h, double joint_inertia = 0.0);

  const MxServoOutput& output() const { return output_; }
  double setpoint() const { return setpoint_; }
  void set_setpoint(double s) { setpoint_ = s; }
  /// Present Load: motor torque as a signed fraction of the stall torque, in [-1, 1].
  double load() const;
  double temperature_c() const { return temperature_c_; }
  /// Motor side minus output inside the backlash [rad], in [-backlash/2, +backlash/2].
  double backlash_gap() const { return gap_; }

 private:
  double friction_budget(double motor_torque, double external_torque, double w) const;

  MxServoParams params_{};
  MxServoInput input_{};
  MxServoOutput output_{};
  double setpoint_ = 0.0;
  double gap_ = 0.0;        ///< motor side relative to the output [rad]
  double gap_speed_ = 0.0;  ///< relative speed while crossing the gap [rad/s]
  double temperature_c_ = 30.0;
};

}  // namespace stride::sim
