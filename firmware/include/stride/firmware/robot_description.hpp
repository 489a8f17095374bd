// RobotDescription: the robot's rigid-body model as the firmware needs it (masses, centres of
// mass and joint frames of the 21 links), loaded once at start-up from
// firmware/config/robot_description.json. That file is generated from the simulator's URDF by
// `stride robot-description` (sim_hal/models/igus_op.urdf), so the firmware links no URDF parser
// and no physics engine. The walk uses it to predict joint torques (compliance compensation).
//
// Tree: the root link (trunk) and one revolute joint per servo, each with its parent joint
// (-1: the root), its frame in the parent link frame (URDF <origin>: xyz [m], roll-pitch-yaw
// [rad], R = Rz(yaw) Ry(pitch) Rx(roll)), its unit axis, and its child link's mass [kg] and
// centre of mass [m, child link frame]. Parents come before children.
//
// Kinematics (real-time, no allocation): for joint angles q (servo order)
//   R_child = R_parent R_origin R(axis, q),  p_child = p_parent + R_parent xyz,
// all in the root (trunk) frame; the joint axis in that frame is R_parent R_origin axis.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "stride/core/status.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/hal/types.hpp"

namespace stride::fw {

class RobotDescription {
 public:
  static constexpr std::size_t kJoints = hal::kServoCount;

  struct Joint {
    std::string name;       ///< URDF joint name
    std::size_t servo = 0;  ///< servo index 0..19 (servo table order)
    int parent = -1;        ///< parent joint index, -1 for the root link
    Eigen::Matrix3d origin_rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d origin_position = Eigen::Vector3d::Zero();  ///< [m], parent link frame
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();            ///< unit, joint frame
    std::string link;                                           ///< child link name
    double mass = 0.0;                                          ///< child link [kg]
    Eigen::Vector3d com = Eigen::Vector3d::Zero();              ///< child link centre of mass [m]
  };

  /// Link frames and joint axes in the root frame for one set of joint angles.
  struct Frames {
    std::array<Eigen::Matrix3d, kJoints> rotation;  ///< child link of joint j
    std::array<Eigen::Vector3d, kJoints> position;  ///< joint j's origin [m]
    std::array<Eigen::Vector3d, kJoints> axis;      ///< joint j's axis (unit)
    std::array<Eigen::Vector3d, kJoints> com;       ///< child link's centre of mass [m]
  };

  /// Loads and validates a description against `servos`: every servo of the table exactly
  /// once, parents before children, finite numbers, positive masses, unit axes. The error
  /// names the file and the field, e.g. "robot_description.json: joints[4].servo: ...".
  static Status load(const std::filesystem::path& path, const ServoTable& servos,
                     RobotDescription& out);
  /// Parses a description already read (`where` names it in errors).
  static Status parse(const std::string& text, const std::string& where, const ServoTable& servos,
                      RobotDescription& out);
  /// The description shipped in firmware/config/robot_description.json for the shipped servo
  /// table (throws std::runtime_error with the loader's message if it is missing or broken).
  static const RobotDescription& defaults();
  static std::filesystem::path default_path();

  const std::array<Joint, kJoints>& joints() const noexcept { return joints_; }
  /// Joint index driven by servo `servo` (0..19).
  std::size_t joint_of_servo(std::size_t servo) const noexcept { return joint_of_servo_[servo]; }
  double root_mass() const noexcept { return root_mass_; }
  const Eigen::Vector3d& root_com() const noexcept { return root_com_; }
  double total_mass() const noexcept { return total_mass_; }
  /// True if joint `ancestor` lies on the path from the root to joint `joint` (or is it).
  bool is_ancestor(std::size_t ancestor, std::size_t joint) const noexcept {
    return (ancestor_mask_[joint] >> ancestor) & 1U;
  }
  /// FNV-1a hash of the file's text, to name the description in logs.
  std::uint64_t hash() const noexcept { return hash_; }

  /// Frames for joint angles `q` (servo order, URDF angles [rad]). Real-time.
  void compute_frames(const std::array<double, hal::kServoCount>& q, Frames& out) const noexcept;
  /// Centre of mass of the whole robot in the root frame [m], from computed frames.
  Eigen::Vector3d center_of_mass(const Frames& frames) const noexcept;

 private:
  std::array<Joint, kJoints> joints_{};
  std::array<std::size_t, hal::kServoCount> joint_of_servo_{};
  std::array<std::uint32_t, kJoints> ancestor_mask_{};
  double root_mass_ = 0.0;
  Eigen::Vector3d root_com_ = Eigen::Vector3d::Zero();
  double total_mass_ = 0.0;
  std::uint64_t hash_ = 0;
};

}  // namespace stride::fw
