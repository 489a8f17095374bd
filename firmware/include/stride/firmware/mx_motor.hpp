// MX motor table: the published figures of the Dynamixel MX-64 and MX-106, in one place.
//
// Read by the firmware's compliance compensation (walk/compliance_compensation.hpp: the goal
// offset that makes the servo deliver an expected torque) and by the simulator's servo models
// (sim_hal mx_servo.hpp: the identified servo law; servo_model.hpp: the seed's torque-speed
// line). No other file holds a copy of these numbers.
//
// The MX position controller sets a PWM duty, i.e. a voltage, not a torque (Rhoban's
// oscilloscope measurement, BAM's MX actuator):
//     duty = clip(kErrorGain * P * (goal - position), +-kMaxDuty)        [P: register 0-254]
// and the motor is a DC motor with back-EMF seen at the output shaft:
//     tau = kt (duty V - kt w) / R                                        [N m]
// with kt the torque constant [N m/A = V s/rad], R the winding resistance [ohm], V the supply
// [V] and w the joint speed [rad/s]. The armature is the rotor's and the gearbox's inertia
// reflected to the joint axis [kg m^2].
//
// Sources (../shared/robot/servos.md):
//  - kt, R, armature: Rhoban BAM (Duclusaud & Passault, "Extended Friction Models for the
//    Physics Simulation of Servo Actuators", ICRA 2025, arXiv 2410.08650), identified on a
//    pendulum bench. M6 (the richest friction model; params mx64/m6.json, mx106/m6.json) is
//    the one Stride uses; M1 (Coulomb-viscous; m1.json) is kept for the simulator's simpler
//    friction option. Full precision as published; servos.md's table rounds them.
//  - gear ratio, stall torque and no-load speed at 11.1 / 12 / 14.8 V, backlash: the ROBOTIS
//    e-manual (MX-64, MX-106 pages).
//  - kErrorGain, kMaxDuty: BAM's oscilloscope measurements of the MX firmware (servos.md).
#pragma once

#include <array>

#include "stride/firmware/servo_table.hpp"

namespace stride::fw {

/// One identification of the DC motor at the output shaft.
struct MxMotorFit {
  double torque_constant;  ///< kt [N m/A = V s/rad]
  double resistance_ohm;   ///< R [ohm]
  double armature_kg_m2;   ///< reflected rotor and gearbox inertia about the joint axis
};

/// The published figures of one MX model.
struct MxMotor {
  MxMotorFit m6;      ///< BAM M6: what the firmware and the identified servo law use
  MxMotorFit m1;      ///< BAM M1 (Coulomb-viscous friction)
  double gear_ratio;  ///< motor turns per output turn
  /// Datasheet stall torque [N m] and no-load speed [rpm] at kMxDatasheetVolts.
  std::array<double, 3> stall_torque_nm;
  std::array<double, 3> no_load_speed_rpm;
};

/// Supply voltages of the datasheet's torque and speed figures [V].
inline constexpr std::array<double, 3> kMxDatasheetVolts = {11.1, 12.0, 14.8};
/// PWM duty per (P register x rad of position error) of the MX firmware's P law.
inline constexpr double kMxErrorGain = 0.158;
/// Largest PWM duty the MX firmware sets.
inline constexpr double kMxMaxDuty = 0.9625;
/// The supply the robot's servos run at nominally: its 4S LiPo [V].
inline constexpr double kMxNominalSupplyV = 14.8;
/// Gearbox backlash, total play: 20 arcmin [rad].
inline constexpr double kMxBacklashRad = 0.33 * 3.14159265358979323846 / 180.0;

// Rows: M6 {kt, R, armature}, M1 {kt, R, armature}, gear ratio, stall torque [N m] and
// no-load speed [rpm] at 11.1 / 12 / 14.8 V.
inline constexpr MxMotor kMx64{{1.6016833, 2.3164043, 0.0122659},
                               {1.6224668, 3.9494337, 0.0119512},
                               200.0,
                               {5.5, 6.0, 7.3},
                               {58.0, 63.0, 78.0}};

inline constexpr MxMotor kMx106{{2.2098282, 2.0336617, 0.0260162},
                                {2.1913757, 2.9649904, 0.0266092},
                                225.0,
                                {8.0, 8.4, 10.0},
                                {41.0, 45.0, 55.0}};

/// The table of a servo model.
constexpr const MxMotor& mx_motor(ServoModel model) noexcept {
  return model == ServoModel::kMx64 ? kMx64 : kMx106;
}

}  // namespace stride::fw
