// Compliance compensation (equations and sources in compliance_compensation.hpp).
#include "stride/firmware/walk/compliance_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stride/firmware/mx_motor.hpp"

namespace stride::fw::walk {
namespace {

constexpr std::array<const char*, 12> kLegServos = {
    "l_hip_yaw", "l_hip_roll", "l_hip_pitch", "l_knee", "l_ankle_pitch", "l_ankle_roll",
    "r_hip_yaw", "r_hip_roll", "r_hip_pitch", "r_knee", "r_ankle_pitch", "r_ankle_roll"};

std::size_t servo_index(const ServoTable& servos, const char* name) {
  const auto index = servos.index_of(name);
  if (!index) throw std::runtime_error(std::string("compliance compensation: no servo ") + name);
  return *index;
}

Eigen::Vector3d perpendicular(const Eigen::Vector3d& v, const Eigen::Vector3d& unit) {
  return v - v.dot(unit) * unit;
}

}  // namespace

ComplianceCompensation::ComplianceCompensation(ParameterStore& store, const RobotDescription& robot,
                                               const ServoTable& servos, double period_s,
                                               std::string_view prefix)
    : store_(store), robot_(robot), period_s_(period_s) {
  const std::string p(prefix);
  gain_ = store.add_real(p + ".compliance.gain", 1.0, 0.0, 1.5, "1",
                         "share of the servos' predicted deflection under the expected joint "
                         "torque added to the leg goals (0: off)");
  back_emf_gain_ = store.add_real(p + ".compliance.back_emf_gain", 0.0, 0.0, 1.5, "1",
                                  "share of the back-EMF at the planned joint speed added to the "
                                  "leg goals (0: off)");
  max_offset_ = store.add_real(p + ".compliance.max_offset", 0.15, 0.0, 0.3, "rad",
                               "largest compensation added to one joint");
  for (std::size_t k = 0; k < kLegServos.size(); ++k)
    leg_servos_[k] = servo_index(servos, kLegServos[k]);
  left_foot_joint_ = robot.joint_of_servo(servo_index(servos, "l_ankle_roll"));
  right_foot_joint_ = robot.joint_of_servo(servo_index(servos, "r_ankle_roll"));
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const MxMotorFit& motor = mx_motor(servos[i].model).m6;
    torque_constant_[i] = motor.torque_constant;
    resistance_[i] = motor.resistance_ohm;
  }
}

void ComplianceCompensation::reset() noexcept {
  have_previous_ = false;
  torque_.fill(0.0);
  offset_.fill(0.0);
}

bool ComplianceCompensation::enabled() const noexcept {
  return store_.value(gain_) > 0.0 || store_.value(back_emf_gain_) > 0.0;
}

void ComplianceCompensation::apply(std::array<double, hal::kServoCount>& targets,
                                   const Eigen::Vector3d& field, FootContact contact,
                                   const std::array<double, hal::kServoCount>& p_gain,
                                   const hal::SensorFrame& sensors) noexcept {
  const std::array<double, hal::kServoCount> reference = targets;
  const double gain = store_.value(gain_);
  const double emf_gain = store_.value(back_emf_gain_);
  const double limit = store_.value(max_offset_);
  torque_.fill(0.0);
  offset_.fill(0.0);
  const double g = field.norm();
  if (!(g > 1.0) || !field.allFinite() || (!(gain > 0.0) && !(emf_gain > 0.0))) {
    previous_reference_ = reference;
    have_previous_ = true;
    return;
  }
  robot_.compute_frames(reference, frames_);
  const Eigen::Vector3d down = field / g;
  const double mass = robot_.total_mass();
  const Eigen::Vector3d cop = perpendicular(robot_.center_of_mass(frames_), down);
  auto sole = [&](std::size_t joint) {
    return perpendicular(frames_.position[joint], down);  // ankle projected along the field
  };
  auto clamp_offset = [&](const Eigen::Vector3d& offset, std::size_t joint) {
    // Limit the pressure point to the sole, in the foot's own x and y.
    const Eigen::Matrix3d& r = frames_.rotation[joint];
    Eigen::Vector3d local = r.transpose() * offset;
    local.x() = std::clamp(local.x(), -kMaxCopOffsetX, kMaxCopOffsetX);
    local.y() = std::clamp(local.y(), -kMaxCopOffsetY, kMaxCopOffsetY);
    return perpendicular(r * local, down);
  };
  const Eigen::Vector3d left_sole = sole(left_foot_joint_);
  const Eigen::Vector3d right_sole = sole(right_foot_joint_);
  double left_share = contact.left ? 1.0 : 0.0;
  Eigen::Vector3d left_point = left_sole, right_point = right_sole;
  if (contact.left && contact.right) {
    const Eigen::Vector3d span = left_sole - right_sole;
    const double length2 = span.squaredNorm();
    left_share =
        length2 > 1e-6 ? std::clamp((cop - right_sole).dot(span) / length2, 0.0, 1.0) : 0.5;
    const Eigen::Vector3d offset = cop - (right_sole + left_share * span);
    left_point = left_sole + clamp_offset(offset, left_foot_joint_);
    right_point = right_sole + clamp_offset(offset, right_foot_joint_);
  } else if (contact.left) {
    left_point = left_sole + clamp_offset(cop - left_sole, left_foot_joint_);
  } else if (contact.right) {
    right_point = right_sole + clamp_offset(cop - right_sole, right_foot_joint_);
  }
  const Eigen::Vector3d left_force = -left_share * mass * field;
  const Eigen::Vector3d right_force =
      (contact.right ? 1.0 - (contact.left ? left_share : 0.0) : 0.0) * -mass * field;
  const auto& joints = robot_.joints();
  for (const std::size_t servo : leg_servos_) {
    const std::size_t j = robot_.joint_of_servo(servo);
    const Eigen::Vector3d& at = frames_.position[j];
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (std::size_t k = j; k < joints.size(); ++k) {
      if (robot_.is_ancestor(j, k)) moment += (frames_.com[k] - at).cross(joints[k].mass * field);
    }
    if (robot_.is_ancestor(j, left_foot_joint_)) moment += (left_point - at).cross(left_force);
    if (robot_.is_ancestor(j, right_foot_joint_)) moment += (right_point - at).cross(right_force);
    const double tau = -frames_.axis[j].dot(moment);
    torque_[servo] = tau;
    const double volts = sensors.servos[servo].voltage_v;
    const double v = std::isfinite(volts) && volts > 5.0 ? volts : kMxNominalSupplyV;
    const double stiffness = kMxErrorGain * p_gain[servo] * v;  // duty volts per rad
    if (!(stiffness > 0.0)) continue;
    const double kt = torque_constant_[servo];
    const double speed =
        have_previous_ ? (reference[servo] - previous_reference_[servo]) / period_s_ : 0.0;
    const double offset =
        gain * tau * resistance_[servo] / (kt * stiffness) + emf_gain * kt * speed / stiffness;
    offset_[servo] = std::clamp(offset, -limit, limit);
    targets[servo] += offset_[servo];
  }
  previous_reference_ = reference;
  have_previous_ = true;
}

}  // namespace stride::fw::walk
