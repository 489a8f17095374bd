// RobotModel: a URDF tree of rigid links and revolute joints, as plain data (no Simbody).
//
// Loaded with urdfdom and checked: one root link (the free-floating base), every joint
// revolute or continuous (fixed joints are merged into their parent link), finite numbers,
// positive masses, physically valid inertias, non-zero axes. Collision geometry is kept as
// spheres and boxes in the link frame; other URDF geometry types are rejected.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "stride/core/status.hpp"

namespace stride::sim {

/// A collision sphere in the link frame. Named spheres on a foot are its studs.
struct CollisionSphere {
  std::string name;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< [m], link frame
  double radius = 0.0;                               ///< [m]
};

/// A collision box in the link frame (axes may be rotated).
struct CollisionBox {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< box centre frame in link frame
  Eigen::Vector3d size = Eigen::Vector3d::Zero();          ///< full edge lengths [m]
};

struct LinkSpec {
  std::string name;
  double mass = 0.0;                                  ///< [kg]
  Eigen::Vector3d com = Eigen::Vector3d::Zero();      ///< centre of mass, link frame [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the CoM, link axes [kg m^2]
  int parent_joint = -1;                              ///< index into joints, -1 for the root
  std::vector<CollisionSphere> spheres;
  std::vector<CollisionBox> boxes;
};

struct JointSpec {
  std::string name;
  int parent_link = -1;
  int child_link = -1;
  /// Joint frame in the parent link frame (URDF <origin>); the child link frame coincides
  /// with the joint frame at angle 0.
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< unit axis in the joint frame
  bool limited = false;                             ///< false for URDF "continuous"
  double lower = 0.0, upper = 0.0;                  ///< position limits [rad]
  double effort = 0.0;                              ///< URDF effort limit [N m] (0 = none)
  double velocity = 0.0;                            ///< URDF velocity limit [rad/s] (0 = none)
  double damping = 0.0;                             ///< URDF dynamics damping [N m s/rad]
  double friction = 0.0;                            ///< URDF dynamics friction [N m]
};

class RobotModel {
 public:
  /// Parses and validates a URDF file. The error names the file and what was wrong.
  static Status load_file(const std::filesystem::path& path, RobotModel& out);
  /// Same for URDF text; `source` names it in error messages.
  static Status load_string(const std::string& urdf, const std::string& source, RobotModel& out);
  /// The igus model shipped in sim_hal/models/igus_op.urdf.
  static std::filesystem::path igus_path();

  const std::string& name() const { return name_; }
  /// Links in parent-before-child order; links[0] is the root.
  const std::vector<LinkSpec>& links() const { return links_; }
  /// Joints in parent-before-child order; joints[i].child_link > joints[i].parent_link.
  const std::vector<JointSpec>& joints() const { return joints_; }
  int link_index(const std::string& name) const;   ///< -1 if absent
  int joint_index(const std::string& name) const;  ///< -1 if absent
  double total_mass() const;
  /// Scales link `link`'s mass and inertia by `mass_scale` (> 0) and moves its centre of mass
  /// by `com_shift` (link frame) [m]; a calibrated robot (RobotCalibration).
  void adjust_link(std::size_t link, double mass_scale, const Eigen::Vector3d& com_shift);

 private:
  std::string name_;
  std::vector<LinkSpec> links_;
  std::vector<JointSpec> joints_;
};

}  // namespace stride::sim
