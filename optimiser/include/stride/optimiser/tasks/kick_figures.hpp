// The kick task's own figures of an episode (kick_task.cpp writes them; TaskFigures in
// EpisodeScore::figures): how far the ball went and how much the robot swayed.
#pragma once

namespace stride::opt {

struct KickFigures {
  double ball_distance_m = 0.0;  ///< the ball's travel on the field plane [m]
  double max_fps = 0.0;          ///< peak field-plane sway sqrt(ax^2 + ay^2) of the IMU [m/s^2]
};

}  // namespace stride::opt
