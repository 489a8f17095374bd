// The check `stride calibrate` prints after a fit (issue 45 point 3): what the nominal and the
// calibrated world predict, so a team can hold both against its robot.
//
//   from the logs   the peak |acceleration| the logs measured against the replays' peak in
//                   each world (windows that ran to their end), the one figure a flight log
//                   of the routine measures;
//   simulated       the firmware's default walk in each world (noise on, seed 1): the time to
//                   walk 2.5 m forward and that walk's peak |a|, the speed in each of the six
//                   directions (the torso's displacement from 5 s to 20 s over 15 s, as
//                   tests/bench/walk_speed_per_direction.py measures it) and the largest push
//                   on the trunk the forward walk survives at 8 s, per direction (bisected to
//                   0.1 N s up to 4 N s; survived: not fallen 4 s later). On the robot: a
//                   stopwatch over 2.5 m, a walk along a tape, a pendulum push.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/sim_hal/log_replay.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::tools {

/// What one world predicts (see above).
struct WorldPrediction {
  double replay_peak_accel_mps2 = 0.0;   ///< the replays' peak |a| [m/s^2]
  std::optional<double> time_to_goal_s;  ///< forward walk to 2.5 m (none: fell or not reached)
  double walk_peak_accel_mps2 = 0.0;     ///< that walk's peak |a| [m/s^2]
  /// forward, backward, left, right [m/s], turning left, right [rad/s], each along its own
  /// direction (none: the walk fell).
  std::array<std::optional<double>, 6> speed{};
  std::array<double, 4> largest_push_n_s{};  ///< forward, backward, left, right [N s]
};

/// The logs' own peak |a| over the windows replayed [m/s^2], and what `world` predicts.
/// `replay` as the fit used it. Errors: a world that cannot be built.
Status predict(const std::vector<const fw::FlightLog*>& logs, const sim::WorldOptions& world,
               const sim::ReplayOptions& replay, double& logged_peak_mps2, WorldPrediction& out);

/// The table printed by stride calibrate: one row per figure, the logs' column where they
/// measure it, the nominal and the calibrated world's.
std::string prediction_table(double logged_peak_mps2, const WorldPrediction& nominal,
                             const WorldPrediction& calibrated);

}  // namespace stride::tools
