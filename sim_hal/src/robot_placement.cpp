// Placing the robot at a reset (SimWorld::reset): attitude, height on the grass, start speeds.
#include "robot_placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stride::sim {

/// How deep a robot of weight `weight_n` whose collision spheres' bottoms are at `bottom`
/// (lowest: the lowest of them) sinks into the grass until the contact springs (grass over the
/// solid ground, contact_law.cpp) carry it standing still [m].
double sinking(const ContactOptions& c, const std::vector<double>& bottom, double lowest,
               double weight_n) {
  const auto force = [&](double sink) {
    double f = 0.0;
    for (double b : bottom) {
      const double depth = sink - (b - lowest);
      if (depth <= 0.0) continue;
      f += c.grass_stiffness_n_m * std::min(depth, c.grass_thickness_m) +
           c.ground_stiffness_n_m * std::max(0.0, depth - c.grass_thickness_m);
    }
    return f;
  };
  double lo = 0.0, hi = 0.1;
  if (!(weight_n > 0.0) || bottom.empty() || force(hi) < weight_n) return 0.0;
  for (int k = 0; k < 60; ++k) (force(0.5 * (lo + hi)) < weight_n ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

/// Places the robot for a reset on `engine`: the given orientation, tilted so that the mean
/// sole normal points up if asked, lowered until the lowest collision point rests on the grass
/// top unless a height is given. The feet and points are read from the engine itself, so the
/// placement is exact in the engine's own kinematics.
Status place_robot(PhysicsEngine& engine, const std::vector<CollisionPoint>& points,
                   const ResetSpec& spec, int left_foot, int right_foot,
                   const ContactOptions& contact, double weight_n, EngineStart& start) {
  const double grass_top = contact.grass_thickness_m;
  start.torso_orientation = spec.torso_orientation.normalized();
  start.torso_position = Eigen::Vector3d(spec.torso_position.x(), spec.torso_position.y(), 0.0);
  start.tilt_angle = 0.0;
  if (spec.level_feet && left_foot >= 0 && right_foot >= 0) {
    if (Status s = engine.start(start); !s) return s;
    const Eigen::Vector3d up =
        engine.link_pose(static_cast<std::size_t>(left_foot)).linear().col(2) +
        engine.link_pose(static_cast<std::size_t>(right_foot)).linear().col(2);
    const Eigen::Vector3d n = up / up.norm();
    const Eigen::Vector3d axis = n.cross(Eigen::Vector3d::UnitZ());
    if (axis.norm() > 1e-12) {
      start.tilt_axis = axis;
      start.tilt_angle = std::atan2(axis.norm(), n.z());
    }
  }
  if (std::isfinite(spec.torso_position.z())) {
    start.torso_position.z() = spec.torso_position.z();
    return engine.start(start);
  }
  if (Status s = engine.start(start); !s) return s;
  std::vector<double> bottom;  // of every collision sphere [m]
  for (const CollisionPoint& p : points) {
    const Eigen::Isometry3d x = engine.link_pose(static_cast<std::size_t>(p.link));
    bottom.push_back((x * p.station).z() - p.radius);
  }
  // A model without collision points has nothing to rest on the grass: the trunk stays at z 0.
  if (bottom.empty()) return Status::ok();
  const double lowest = *std::min_element(bottom.begin(), bottom.end());
  start.torso_position.z() = grass_top - lowest;
  if (spec.sink_into_grass) start.torso_position.z() -= sinking(contact, bottom, lowest, weight_n);
  return engine.start(start);
}

/// Gives the trunk of a robot placed by `start` (with joint speeds) the velocity that keeps its
/// lower foot still: the foot's pose after a short time with the trunk held, moved back onto
/// where it is now, moves the trunk by the opposite of the foot's motion.
Status still_lower_foot(PhysicsEngine& engine, int left_foot, int right_foot, EngineStart& start) {
  if (left_foot < 0 || right_foot < 0) return Status::ok();
  const Eigen::Isometry3d torso = engine.link_pose(0);
  const Eigen::Isometry3d left = engine.link_pose(static_cast<std::size_t>(left_foot));
  const Eigen::Isometry3d right = engine.link_pose(static_cast<std::size_t>(right_foot));
  const bool use_left = left.translation().z() <= right.translation().z();
  const Eigen::Isometry3d foot = use_left ? left : right;
  constexpr double kDt = 1e-5;  // [s]
  EngineStart probe = start;
  for (std::size_t j = 0; j < probe.joint_angles.size(); ++j)
    probe.joint_angles[j] += kDt * start.joint_speeds[j];
  if (Status s = engine.start(probe); !s) return s;
  const Eigen::Isometry3d moved =
      engine.link_pose(static_cast<std::size_t>(use_left ? left_foot : right_foot));
  const Eigen::Isometry3d back = foot * moved.inverse();  // takes the moved foot back
  const Eigen::AngleAxisd turn(back.linear());
  start.torso_angular_velocity = turn.axis() * (turn.angle() / kDt);
  start.torso_velocity = ((back * torso).translation() - torso.translation()) / kDt;
  return engine.start(start);
}

}  // namespace stride::sim
