// WalkServos: the 18 arm and leg servos a walk engine drives, found by name in the servo table
// once at start-up, and what every walk engine does with them: the pose a walk's start blends
// from, the P gain per servo the compliance compensation needs, and the commands written each
// tick (position blended from the start pose, full speed, P only, full torque). The head is left
// to whoever drives it. Real-time: start_pose(), p_gains() and write() allocate nothing.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "stride/firmware/servo_table.hpp"
#include "stride/firmware/walk/leg_kinematics.hpp"
#include "stride/firmware/walk/pose2.hpp"
#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::walk {

struct WalkServos {
  static constexpr std::size_t kDriven = 18;  ///< arm and leg servos
  static constexpr std::size_t kArms = 6;     ///< the first kArms of `driven` are the arms'
  /// Hip yaw, hip roll, hip pitch, knee, ankle pitch, ankle roll.
  std::array<std::size_t, 6> left_leg{}, right_leg{};
  /// Shoulder pitch, shoulder roll, elbow.
  std::array<std::size_t, 3> left_arm{}, right_arm{};
  /// Left arm, right arm, left leg, right leg.
  std::array<std::size_t, kDriven> driven{};

  /// Throws std::runtime_error "`who`: servo table has no NAME" (start-up only).
  WalkServos(const ServoTable& servos, std::string_view who);

  /// The pose a walk's start blends from: per driven servo the last command if its torque was
  /// on, else the measured position (0 if not finite), in `from`; the same per servo in `pose`.
  void start_pose(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
                  std::array<double, kDriven>& from,
                  std::array<double, hal::kServoCount>& pose) const noexcept;
  /// Writes a leg's joint angles into `targets` (servo order) at the leg's servos `leg`.
  static void set_leg(std::array<double, hal::kServoCount>& targets,
                      const std::array<std::size_t, 6>& leg, const LegJoints& q) noexcept {
    targets[leg[0]] = q.hip_yaw;
    targets[leg[1]] = q.hip_roll;
    targets[leg[2]] = q.hip_pitch;
    targets[leg[3]] = q.knee;
    targets[leg[4]] = q.ankle_pitch;
    targets[leg[5]] = q.ankle_roll;
  }
  /// Where a held pose puts a leg's foot in the walk plane: its forward kinematics relative to
  /// `reference` (a point of the trunk frame), turned by `trunk` (the walk's trunk rotation at
  /// zero yaw). Both engines start a walk on the feet where they stand.
  static Pose2 foot_in_plane(const LegKinematics& leg,
                             const std::array<double, hal::kServoCount>& pose,
                             const std::array<std::size_t, 6>& index, const Eigen::Matrix3d& trunk,
                             const Eigen::Vector3d& reference) noexcept;
  /// True if the feet make a stance a walk may start from (finite, side by side within 0.15 m,
  /// 0.08-0.4 m apart, turned less than 0.5 rad against each other).
  static bool plausible_stance(const Pose2& left, const Pose2& right) noexcept;
  /// The P register of each servo (the arms' `arm_p`, the legs' `leg_p`, 0 elsewhere).
  std::array<double, hal::kServoCount> p_gains(double arm_p, double leg_p) const noexcept;
  /// Writes the driven servos' commands: from + blend (target - from), full speed, P gain, no I
  /// or D, full torque, torque on.
  void write(const std::array<double, hal::kServoCount>& targets,
             const std::array<double, kDriven>& from, double blend, double arm_p, double leg_p,
             hal::CommandFrame& out) const noexcept;
};

}  // namespace stride::fw::walk
