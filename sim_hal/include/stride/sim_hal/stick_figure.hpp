// Stick figure of the robot: the points and strokes that the pose pictures (pose_svg) and the
// HTML replay (optimiser/report) draw, so both show the same figure.
//
// Points of one pose, in this order: every link origin (RobotModel::links() order; link 0 is
// the torso), then for each foot (a link with a collision box and studs) its sole's heel, toe,
// inner and outer edge points, then the centre of every collision sphere of at least 3 cm
// radius (the head). Strokes join each joint's parent and child link origins and the sole's
// heel-toe and inner-outer points; they are coloured by side: a name with "left" is the
// robot's left, "right" its right, anything else the centre.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim {

enum class StickSide : char { kCentre = 'c', kLeft = 'l', kRight = 'r' };

struct StickStroke {
  int a = 0, b = 0;  ///< point indices
  StickSide side = StickSide::kCentre;
  bool sole = false;  ///< a foot's sole (drawn thinner than the limbs)
};

struct StickCircle {
  int centre = 0;         ///< point index
  double radius_m = 0.0;  ///< [m]
};

struct StickFigure {
  int point_count = 0;
  std::vector<StickStroke> strokes;
  std::vector<StickCircle> circles;
};

/// The figure's layout for a model (independent of the pose).
StickFigure stick_figure(const RobotModel& model);

/// The figure's points (world frame) for link poses in model order (SimWorld::link_poses()).
/// Empty if `links` does not match the model.
std::vector<Eigen::Vector3d> stick_points(const RobotModel& model,
                                          const std::vector<Eigen::Isometry3d>& links);

/// The stroke colour of a side (#rrggbb): left blue, right red, centre dark grey.
const char* stick_colour(StickSide side);

}  // namespace stride::sim
