// The episode sections of the report pages: the animated replay of several individuals side by
// side (data for replay.js), the accelerometer over time (the seed's Fig D.2) and strips of
// poses at regular times (the seed's Fig 7.3), all from EpisodeCaptures of re-run episodes.
//
// Replay data: frames every EpisodeCapture::frame_every_ticks ticks (25 per second at 100 Hz)
// plus the last tick; each frame is the stick figure's points (sim/stick_figure.hpp) and the
// ball, as int16 millimetres, base64 (248 bytes per frame: 6.2 kB per second of episode and
// individual). The 3D replay's data is added by html_replay3d.hpp.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/sim_hal/episode_capture.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::opt::report {

struct ReplayIndividual {
  std::string name;  ///< "Ind_O", "fastest, knee", ...
  std::string note;  ///< how the episode ended, e.g. "reached 2.5 m at 10.84 s"
  std::string colour;
  sim::EpisodeCapture capture;
};

struct ReplayScene {
  std::string ground = "seed";   ///< the ground's name (sim::contact_kind_name): its colour
  double grass_m = 0.02;         ///< the top of the ground's soft layer [m]
  double ball_radius_m = 0.0;    ///< 0: no ball in the world
  std::optional<double> goal_m;  ///< the walk's goal line [m] from the start
};
/// The scene of an episode in `world`: its ground (name and layer thickness) and its ball (if
/// the world has one).
ReplayScene replay_scene(const sim::WorldOptions& world);

/// The JSON block replay.js reads.
nlohmann::json replay_data(const sim::RobotModel& model,
                           const std::vector<ReplayIndividual>& individuals,
                           const ReplayScene& scene);
/// The replay section's body: controls (play/pause, speed, time slider, clock) and the cards'
/// container that replay.js fills.
std::string replay_section_html();
/// |a|, a_x, a_y, a_z against time over the whole episode, one panel each, every individual
/// on the same axes; first, when `window` is given, |a| over that stretch (the seed's Fig D.2
/// shows a walk cycle).
std::string accel_charts_html(const std::vector<ReplayIndividual>& individuals,
                              std::optional<std::pair<double, double>> window = std::nullopt);
/// Pose strips at `times_s`: for each individual after the first, the first individual's strip
/// above its own (pick_rows = true, the report); or each individual's strip alone.
std::string pose_strips_html(const sim::RobotModel& model,
                             const std::vector<ReplayIndividual>& individuals,
                             const std::vector<double>& times_s, const ReplayScene& scene,
                             bool pick_rows);
/// The first time a ball moved more than 1 cm in the field plane in any capture (the kick's
/// contact), or `fallback_s` if it never did.
double first_ball_motion_s(const std::vector<ReplayIndividual>& individuals, double fallback_s);
/// The strip's times: `count` moments spaced `step_s` from `start_s` (clipped to [0, end_s]).
std::vector<double> strip_times(double start_s, double step_s, int count, double end_s);

/// Base64 (RFC 4648, with padding).
std::string base64(const std::string& bytes);

}  // namespace stride::opt::report
