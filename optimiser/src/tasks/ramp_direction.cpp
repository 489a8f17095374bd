// The speed ramp of one direction apart from the simulation (ramp_direction.hpp).
#include "stride/optimiser/tasks/ramp_direction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "stride/optimiser/tasks/ramp_command.hpp"

namespace stride::opt {

RampLevel measure_ramp_level(const PlanarPose& direction_start, const PlanarPose& window_start,
                             const PlanarPose& end, const std::array<double, 3>& axis,
                             const RampSettings& ramp) {
  const StraightnessLimits& limits = ramp.straightness;
  const double window = ramp.timing.measure_s;
  const bool turn = axis[2] != 0.0;
  const Translation t =
      measure_translation(window_start, end, turn ? 1.0 : axis[0], turn ? 0.0 : axis[1]);
  RampLevel level;
  if (turn) {
    level.speed = (end.yaw - window_start.yaw) * (axis[2] > 0.0 ? 1.0 : -1.0) / window;
    level.translation_m = t.distance_m;
    level.straight =
        limits.max_turn_translation_m < 0.0 || level.translation_m <= limits.max_turn_translation_m;
  } else {
    level.speed = t.along_m / window;
    // Straightness over the direction so far (from its first level's start): a window of a
    // few steps sees the feet's step-to-step sway, the whole walk its drift.
    const Translation so_far = measure_translation(direction_start, end, axis[0], axis[1]);
    level.drift_ratio = so_far.off_axis_m / std::max(std::abs(so_far.along_m), kRampDriftFloorM);
    level.heading_change_rad = so_far.heading_change_rad;
    const double heading_limit = limits.max_heading_change_deg * std::numbers::pi / 180.0;
    level.straight =
        (limits.max_drift_ratio < 0.0 || level.drift_ratio <= limits.max_drift_ratio) &&
        (heading_limit < 0.0 || level.heading_change_rad <= heading_limit);
  }
  return level;
}

int RampDirection::level_at(double t) const {
  const RampTiming& r = ramp_;
  return t < r.start_s ? 0 : 1 + static_cast<int>((t - r.start_s) / r.hold_s);
}

double RampDirection::level_speed(int level) const {
  const RampTiming& r = ramp_;
  if (r.normalised()) return std::min(1.0, level * r.increment);
  return level * (axis_[2] != 0.0 ? r.increment_radps : r.increment_mps);
}

bool RampDirection::window_begun(int level, double t) const {
  const RampTiming& r = ramp_;
  const double level_end = r.start_s + level * r.hold_s;
  return t >= level_end - r.measure_s - 1e-9;
}

double RampDirection::begin_level(int level, const fw::walk::WalkParameters& walk) {
  if (level > ramp_.max_levels) ended_ = true;
  if (ended_) return 0.0;
  if (ramp_.normalised()) return level_speed(level);
  const std::optional<double> command = command_for_speed(walk, axis_, level_speed(level));
  if (!command) {
    ended_ = beyond_walk_limits_ = true;
    return 0.0;
  }
  return *command;
}

void RampDirection::end_level(int level, const RampLevel& figures) {
  if (!figures.straight) {
    if (level == 1) crooked_first_ = true;
    ended_ = true;
    return;
  }
  if (figures.speed <= best_.speed) {  // no faster: the direction ends after `patience` such
    if (++levels_without_gain_ >= ramp_.patience) ended_ = true;
    return;
  }
  levels_without_gain_ = 0;
  best_ = figures;
  counted_ = true;
}

}  // namespace stride::opt
