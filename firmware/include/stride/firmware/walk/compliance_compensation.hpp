// ComplianceCompensation: feeds the expected joint torques forward into the soft MX servos'
// position commands, so a leg sags by about nothing instead of by degrees under the body's
// weight (NimbRo-OP's actuator scheme on the igus platform, Schwarz & Behnke; research notes in
// ../shared/research/walk-anchors.md 1). Real-time: no allocation, no I/O.
//
// Torque model (quasi-static rigid body, from fw::RobotDescription): the walk's own planned
// trunk acceleration a (the LIPM's) is folded into gravity, f = R_trunk^T (g - a) per kg. The
// ground carries -M f at the centre of pressure P, the whole robot's centre of mass projected
// along f. In single support the stance foot takes it all at P (within kMaxCopOffset of the
// ankle); in double support the feet share it by where P lies between them (each foot's share
// acts at its ankle shifted by P's offset from the line between the ankles). For each leg
// joint j with axis e_j at p_j, the torque the servo must apply to the distal part is
//   tau_j = -e_j . [ sum_{links k below j} (c_k - p_j) x m_k f  +  (P_foot - p_j) x F_foot ].
// Servo (the MX firmware's P law into a DC motor with back-EMF; kt, R and the P law's 0.158
// from the MX motor table, mx_motor.hpp, BAM M6):
//   tau = kt (0.158 P (q_goal - q) V - kt w) / R,
// so the goal that delivers tau at the planned joint speed w is
//   q_goal = q_ref + gain * tau R / (0.158 P V kt) + back_emf_gain * kt w / (0.158 P V),
// clamped to +-max_offset. V is the servo's reported supply voltage (14.8 V if none).
// Friction is not fed forward: the MX's Stribeck and load friction are a dead band around the
// goal that feed-forward would only chatter across.
//
// Parameters (walk.compliance.*, not in the genome; gain 0 = the seed's uncompensated walk):
//   gain           [0, 1.5]  share of the predicted gravity/inertia deflection fed forward
//   back_emf_gain  [0, 1.5]  share of the back-EMF voltage fed forward
//   max_offset     [0, 0.3]  rad, largest offset added to a joint
#pragma once

#include <string_view>

#include <array>

#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/robot_description.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::walk {

/// Which feet carry the robot this tick.
struct FootContact {
  bool left = true;
  bool right = true;
};

class ComplianceCompensation {
 public:
  /// Largest distance of the centre of pressure from the stance ankle [m] (the igus sole,
  /// 0.215 m long, about 0.12 m wide: a little inside its edges).
  static constexpr double kMaxCopOffsetX = 0.09;
  static constexpr double kMaxCopOffsetY = 0.05;
  /// Stud tips below the ankle crossing [m] (LegGeometry::kAnkleHeight).
  static constexpr double kSoleBelowAnkle = 0.0565;

  /// Registers PREFIX.compliance.* (PREFIX: "walk", or "walk.spline" for the spline walk; start-up
  /// only; throws on a name clash or a servo table without the leg servos).
  ComplianceCompensation(ParameterStore& store, const RobotDescription& robot,
                         const ServoTable& servos, double period_s,
                         std::string_view prefix = "walk");

  void reset() noexcept;
  bool enabled() const noexcept;

  /// Adds the compensation to the 12 leg joints of `targets` (URDF angles [rad], servo order).
  /// `field` is g - a in the trunk frame [m/s^2]; `p_gain` the P registers sent per servo.
  void apply(std::array<double, hal::kServoCount>& targets, const Eigen::Vector3d& field,
             FootContact contact, const std::array<double, hal::kServoCount>& p_gain,
             const hal::SensorFrame& sensors) noexcept;

  /// The torques [N m] and offsets [rad] of the last apply(), per servo (0 off the legs).
  const std::array<double, hal::kServoCount>& torques() const noexcept { return torque_; }
  const std::array<double, hal::kServoCount>& offsets() const noexcept { return offset_; }

 private:
  const ParameterStore& store_;
  const RobotDescription& robot_;
  double period_s_;
  ParamHandle gain_, back_emf_gain_, max_offset_;
  std::array<std::size_t, 12> leg_servos_{};
  std::size_t left_foot_joint_ = 0, right_foot_joint_ = 0;
  std::array<double, hal::kServoCount> torque_constant_{}, resistance_{};
  std::array<double, hal::kServoCount> previous_reference_{};
  bool have_previous_ = false;
  RobotDescription::Frames frames_;
  std::array<double, hal::kServoCount> torque_{}, offset_{};
};

}  // namespace stride::fw::walk
