// The walk engines' servos (see walk_servos.hpp).
#include "stride/firmware/walk/walk_servos.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace stride::fw::walk {
namespace {

std::size_t find(const ServoTable& servos, std::string_view who, const char* name) {
  const auto index = servos.index_of(name);
  if (!index) throw std::runtime_error(std::string(who) + ": servo table has no " + name);
  return *index;
}

}  // namespace

WalkServos::WalkServos(const ServoTable& servos, std::string_view who) {
  auto f = [&](const char* name) { return find(servos, who, name); };
  left_leg = {f("l_hip_yaw"), f("l_hip_roll"),    f("l_hip_pitch"),
              f("l_knee"),    f("l_ankle_pitch"), f("l_ankle_roll")};
  right_leg = {f("r_hip_yaw"), f("r_hip_roll"),    f("r_hip_pitch"),
               f("r_knee"),    f("r_ankle_pitch"), f("r_ankle_roll")};
  left_arm = {f("l_shoulder_pitch"), f("l_shoulder_roll"), f("l_elbow")};
  right_arm = {f("r_shoulder_pitch"), f("r_shoulder_roll"), f("r_elbow")};
  std::size_t k = 0;
  for (auto i : left_arm) driven[k++] = i;
  for (auto i : right_arm) driven[k++] = i;
  for (auto i : left_leg) driven[k++] = i;
  for (auto i : right_leg) driven[k++] = i;
}

void WalkServos::start_pose(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
                            std::array<double, kDriven>& from,
                            std::array<double, hal::kServoCount>& pose) const noexcept {
  pose.fill(0.0);
  for (std::size_t k = 0; k < kDriven; ++k) {
    const std::size_t i = driven[k];
    const double position = last_sent.servos[i].torque_enable ? last_sent.servos[i].position_rad
                                                              : sensors.servos[i].position_rad;
    from[k] = std::isfinite(position) ? position : 0.0;
    pose[i] = from[k];
  }
}

Pose2 WalkServos::foot_in_plane(const LegKinematics& leg,
                                const std::array<double, hal::kServoCount>& pose,
                                const std::array<std::size_t, 6>& index,
                                const Eigen::Matrix3d& trunk,
                                const Eigen::Vector3d& reference) noexcept {
  const LegJoints q{pose[index[0]], pose[index[1]], pose[index[2]],
                    pose[index[3]], pose[index[4]], pose[index[5]]};
  const Pose3 foot = leg.forward(q);
  const Eigen::Vector3d p = trunk * (foot.position - reference);
  const Eigen::Matrix3d r = trunk * foot.rotation;
  return Pose2{p.x(), p.y(), std::atan2(r(1, 0), r(0, 0))};
}

bool WalkServos::plausible_stance(const Pose2& left, const Pose2& right) noexcept {
  const Pose2 rel = relative(right, left);
  return std::isfinite(rel.x) && std::isfinite(rel.y) && std::isfinite(rel.theta) &&
         std::abs(rel.x) < 0.15 && rel.y > 0.08 && rel.y < 0.4 && std::abs(rel.theta) < 0.5;
}

std::array<double, hal::kServoCount> WalkServos::p_gains(double arm_p,
                                                         double leg_p) const noexcept {
  std::array<double, hal::kServoCount> p{};
  for (std::size_t k = 0; k < kDriven; ++k) p[driven[k]] = k < kArms ? arm_p : leg_p;
  return p;
}

void WalkServos::write(const std::array<double, hal::kServoCount>& targets,
                       const std::array<double, kDriven>& from, double blend, double arm_p,
                       double leg_p, hal::CommandFrame& out) const noexcept {
  for (std::size_t k = 0; k < kDriven; ++k) {
    const std::size_t i = driven[k];
    hal::ServoCommand& command = out.servos[i];
    command.position_rad = from[k] + blend * (targets[i] - from[k]);
    command.moving_speed_rad_s = 0.0;
    command.p_gain = k < kArms ? arm_p : leg_p;
    command.i_gain = 0.0;
    command.d_gain = 0.0;
    command.torque_limit = 1.0;
    command.torque_enable = true;
  }
}

}  // namespace stride::fw::walk
