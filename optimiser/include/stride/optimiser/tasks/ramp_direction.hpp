// The speed ramp of one direction (task "walk-ramp", speed_ramp.hpp has the rules), apart from
// the simulation: which level a moment belongs to, its speed, its command for the walk's
// parameters and its measurement window, each level's speed and straightness from three walking
// frames, and whether the direction goes on (levels, the walk's limits, patience, straightness).
// walk_ramp_task.cpp feeds it the simulated robot's parameters and frames.
#pragma once

#include <array>

#include "stride/firmware/walk/walk_parameters.hpp"
#include "stride/optimiser/tasks/speed_ramp.hpp"
#include "stride/optimiser/tasks/walk_measures.hpp"

namespace stride::opt {

/// The drift ratio's floor of a ramp [m]: a direction that has walked less is held to 0.5 m's
/// allowance (5 cm at 10 %), not the walk task's 0.25 m: the first levels are slow, and the
/// feet's step-to-step sway alone is 1-3 cm (Ind_O drifts 3 cm in its first 0.05 m forward).
inline constexpr double kRampDriftFloorM = 0.5;

/// One completed level's figures.
struct RampLevel {
  double speed = 0.0;               ///< over the window, along the command [m/s or rad/s]
  double drift_ratio = 0.0;         ///< translations: since the direction's start
  double heading_change_rad = 0.0;  ///< translations: since the direction's start
  double translation_m = 0.0;       ///< turns: over the window
  bool straight = true;             ///< within the ramp's straightness limits
};

/// A level's figures from the walking frame at the direction's first level start, at its
/// measurement window's start and at its end; `axis` the direction's normalised command, the
/// window the ramp's measure_s, the limits its straightness limits.
RampLevel measure_ramp_level(const PlanarPose& direction_start, const PlanarPose& window_start,
                             const PlanarPose& end, const std::array<double, 3>& axis,
                             const RampSettings& ramp);

class RampDirection {
 public:
  /// `axis`: the direction's normalised command (omni_command).
  /// `ramp`: the walk-ramp task's own settings (outlive the direction).
  RampDirection(const RampSettings& ramp, const std::array<double, 3>& axis)
      : ramp_(ramp.timing), axis_(axis) {}
  /// The level at `t` [s] from the episode's start: 0 before ramp.start_s, then 1, 2, ...
  int level_at(double t) const;
  /// The speed `level` asks for: level * increment_mps [m/s] for a translation, level *
  /// increment_radps [rad/s] for a turn (a normalised ramp: its command's share, as below).
  double level_speed(int level) const;
  /// Whether `level`'s measurement window (its last measure_s) has begun at `t`.
  bool window_begun(int level, double t) const;
  /// `level` begins: its command's share of the axis (the walk command is the share times the
  /// axis), the one with which the walk's parameters `walk` plan level_speed(level)
  /// (ramp_command.hpp); in a normalised ramp min(1, level * increment). The direction ends past
  /// max_levels, or when the walk's limits cannot command the level's speed
  /// (beyond_walk_limits()); the share is then 0.
  double begin_level(int level, const fw::walk::WalkParameters& walk);
  /// A level's figures: the direction ends if it was not straight, or after `patience` levels
  /// in a row no faster than the best; otherwise a faster level becomes the best.
  void end_level(int level, const RampLevel& figures);

  bool ended() const { return ended_; }
  /// A level was held (its speed counted).
  bool counted() const { return counted_; }
  /// The first level was already beyond the straightness limits.
  bool crooked_first() const { return crooked_first_; }
  /// The direction ended at a level whose speed the walk's limits cannot command.
  bool beyond_walk_limits() const { return beyond_walk_limits_; }
  /// The fastest straight level (zeros until one is counted).
  const RampLevel& best() const { return best_; }

 private:
  const RampTiming& ramp_;
  std::array<double, 3> axis_;
  int levels_without_gain_ = 0;
  bool ended_ = false, counted_ = false, crooked_first_ = false, beyond_walk_limits_ = false;
  RampLevel best_;
};

}  // namespace stride::opt
