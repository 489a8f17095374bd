// The collision points of a RobotModel, independent of any physics engine: what SimWorld rests
// on the grass at a reset, and what Stride's contact law (the Simbody engine) presses into it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim {

/// A point that touches the field: a collision sphere (centre and radius) or a box corner
/// (radius 0), in its link's frame.
struct CollisionPoint {
  int link = -1;
  Eigen::Vector3d station = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// Every sphere and every box corner of the model, link by link in model order.
std::vector<CollisionPoint> collision_points(const RobotModel& model);

}  // namespace stride::sim
