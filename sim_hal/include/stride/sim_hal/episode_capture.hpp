// EpisodeCapture: what a replay of an episode needs, taken while it runs (EpisodeOptions::
// on_tick): the link poses, the joint angles, each foot's contact force and the ball every
// `frame_every_ticks` control ticks (4 at 100 Hz: 25 frames per second) plus the last tick, and
// the accelerometer (the IMU reading the controller saw, torso frame, m/s^2) at every tick. Used by
// `stride sim --html` and by `stride report` when it re-runs the chosen individuals.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "stride/sim_hal/episode.hpp"

namespace stride::sim {

struct AccelSample {
  double t = 0.0;                               ///< [s] from the episode's start
  Eigen::Vector3d a = Eigen::Vector3d::Zero();  ///< [m/s^2]
};

struct EpisodeCapture {
  double period_s = 0.01;  ///< control period
  int frame_every_ticks = 4;
  std::vector<PoseSnapshot> frames;  ///< at ticks 0, k, 2k, ... and the last tick
  std::vector<AccelSample> accel;    ///< every tick
};

class EpisodeCapturer {
 public:
  explicit EpisodeCapturer(int frame_every_ticks = 4)
      : every_(frame_every_ticks < 1 ? 1 : frame_every_ticks) {}
  /// The observer to put into EpisodeOptions::on_tick (it refers to this capturer).
  std::function<void(hal::Tick, const SimWorld&, const hal::SensorFrame&)> observer();
  void observe(hal::Tick tick, const SimWorld& world, const hal::SensorFrame& sensors);
  /// The capture so far, the last observed tick included as a frame.
  EpisodeCapture finish() const;

 private:
  int every_;
  EpisodeCapture capture_;
  PoseSnapshot last_;
  bool have_last_ = false;
};

/// The snapshots of a capture nearest to each of `times_s` (the last frame for times after the
/// end), for pose pictures.
std::vector<PoseSnapshot> snapshots_at(const EpisodeCapture& capture,
                                       const std::vector<double>& times_s);

}  // namespace stride::sim
