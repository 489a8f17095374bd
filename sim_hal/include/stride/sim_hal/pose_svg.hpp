// Pose pictures: stick figures of the robot (side and front views) at chosen moments, as an
// SVG document, so a person can see what happened in an episode without reading numbers.
// Each column is one snapshot; the top row is the side view (x right, z up), the bottom row
// the front view as seen from in front of the robot (its left on the picture's right). The
// ground, the grass top and the ball are drawn; the feet are drawn as their soles.
#pragma once

#include <string>
#include <vector>

#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim {

std::string render_pose_svg(const RobotModel& model, const std::vector<PoseSnapshot>& snapshots,
                            double grass_thickness_m, double ball_radius_m);

}  // namespace stride::sim
