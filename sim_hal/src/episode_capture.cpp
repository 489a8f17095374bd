// EpisodeCapture: link poses, ball and accelerometer of an episode for replays and pictures.
#include "stride/sim_hal/episode_capture.hpp"

#include <cmath>

#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

std::function<void(hal::Tick, const SimWorld&, const hal::SensorFrame&)>
EpisodeCapturer::observer() {
  return [this](hal::Tick tick, const SimWorld& world, const hal::SensorFrame& sensors) {
    observe(tick, world, sensors);
  };
}

void EpisodeCapturer::observe(hal::Tick tick, const SimWorld& world,
                              const hal::SensorFrame& sensors) {
  capture_.period_s = static_cast<double>(world.options().control_period_ns) * 1e-9;
  capture_.frame_every_ticks = every_;
  const double t = static_cast<double>(tick) * capture_.period_s;
  const auto& a = sensors.cm730.accel_mps2;
  capture_.accel.push_back({t, Eigen::Vector3d(a[0], a[1], a[2])});
  const GroundTruth truth = world.ground_truth();
  last_ = {t,
           world.link_poses(),
           truth.ball_position,
           world.joint_angles(),
           truth.left_contact.force,
           truth.right_contact.force};
  have_last_ = true;
  if (tick % every_ == 0) capture_.frames.push_back(last_);
}

EpisodeCapture EpisodeCapturer::finish() const {
  EpisodeCapture out = capture_;
  if (have_last_ && (out.frames.empty() || out.frames.back().time_s < last_.time_s))
    out.frames.push_back(last_);
  return out;
}

std::vector<PoseSnapshot> snapshots_at(const EpisodeCapture& capture,
                                       const std::vector<double>& times_s) {
  std::vector<PoseSnapshot> out;
  if (capture.frames.empty()) return out;
  for (double t : times_s) {
    const PoseSnapshot* best = &capture.frames.front();
    for (const PoseSnapshot& f : capture.frames)
      if (std::abs(f.time_s - t) < std::abs(best->time_s - t)) best = &f;
    out.push_back(*best);
  }
  return out;
}

}  // namespace stride::sim
