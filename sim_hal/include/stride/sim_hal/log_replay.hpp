// Replay of a flight log (stride-fw --record) against the simulated robot (`stride replay`).
//
// The log is cut into windows of whole control periods. Each window puts the simulated robot
// in the logged state at the window's start (joint angles from the encoders, trunk roll and
// pitch from the firmware's attitude estimator over the logged IMU, yaw 0, the lowest contact point
// on the grass; no ball: the log does not say where one was), then feeds the logged CommandFrames
// one control period each and compares the simulated SensorFrames with the logged ones: RMS error
// per joint of position, speed and load, and of the IMU's attitude, rate and specific force. Format
// of the log: FLIGHT_LOG.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stride/core/status.hpp"
#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/firmware/robot_description.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

/// The trunk's attitude over a log is the firmware's own estimator (fw::AttitudeEstimator,
/// attitude_estimator.hpp) run over the logged IMU readings, with the time constant the log's
/// firmware used (the header's walk.balance.tilt_filter_time; its default for a log without
/// it) and the gyro's bias about the horizontal axes learnt (the replay sees the whole log).
/// The time constant of `log` [s].
double log_attitude_time_constant(const fw::FlightLog& log);

/// Checks that `log` can be replayed with the firmware files in use: a sim-able header
/// (period), whole (unless `allow_truncated`), and recorded with the same servo table and robot
/// description. The error is one line naming what does not match.
Status check_replayable(const fw::FlightLog& log, const fw::ServoTable& servos,
                        const fw::RobotDescription& robot, bool allow_truncated = false);

struct ReplayOptions {
  double window_s = 2.0;     ///< window length [s] (rounded to whole control periods)
  bool keep_traces = false;  ///< keep the logged and simulated traces (ReplayWindow::traces)
  /// Start each window with the logged joint speeds (the trunk at rest) instead of at rest.
  bool start_with_logged_speeds = false;
  /// Sink the robot into the grass until the contacts carry its weight (ResetSpec).
  bool sink_into_grass = true;
  /// Threads replaying windows side by side (each its own world); the result does not depend
  /// on it.
  int threads = 1;
  /// Replay only the windows whose index (in the order of the log) is listed; empty: all.
  std::vector<std::size_t> only_windows;
};

/// RMS errors, simulated minus logged (NaN where nothing was compared).
struct ReplayErrors {
  std::array<double, hal::kServoCount> position_rad{};  ///< per servo
  std::array<double, hal::kServoCount> speed_rad_s{};
  std::array<double, hal::kServoCount> load{};  ///< fraction of the stall torque
  double position_all_rad = 0.0;                ///< over every servo sample
  double speed_all_rad_s = 0.0;
  double load_all = 0.0;
  double roll_rad = 0.0, pitch_rad = 0.0;  ///< attitude estimate (fw::AttitudeEstimator)
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
  /// The mean of logged minus simulated IMU reading (signed) over the compared samples from 1 s
  /// into each window (the placed robot settles first): what a constant sensor bias the world
  /// lacks leaves behind [rad/s, m/s^2].
  Eigen::Vector3d gyro_mean_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mean_mps2 = Eigen::Vector3d::Zero();
  /// The largest |accelerometer reading| over the same samples, logged and simulated [m/s^2]
  /// (the seed walk's Obj2, measured on the robot and predicted by the world).
  double peak_accel_logged_mps2 = 0.0, peak_accel_sim_mps2 = 0.0;
  std::size_t mean_samples = 0;  ///< the IMU samples in the means and peaks
  std::size_t samples = 0;       ///< ticks compared
};

/// The traces of one window (one entry per compared tick), logged and simulated.
struct ReplayTraces {
  std::vector<double> time_s;          ///< log time of the compared sensors
  std::vector<std::size_t> log_index;  ///< index in FlightLog::ticks of the compared sensors
  std::array<std::vector<float>, hal::kServoCount> logged_position, sim_position;
  std::array<std::vector<float>, hal::kServoCount> logged_speed, sim_speed, logged_load, sim_load;
  std::vector<float> logged_roll, sim_roll, logged_pitch, sim_pitch;
  std::array<std::vector<float>, 3> logged_gyro, sim_gyro, logged_accel, sim_accel;
};

struct ReplayWindow {
  std::size_t index = 0;        ///< the window's number in the log (ReplayOptions::only_windows)
  std::size_t first_index = 0;  ///< index in FlightLog::ticks of the starting state
  hal::Tick start_tick = 0;
  double start_s = 0.0;  ///< log time of the start
  std::size_t ticks = 0;
  Eigen::Vector2d start_roll_pitch = Eigen::Vector2d::Zero();  ///< the placed trunk [rad]
  std::string failure;  ///< why the simulation stopped early ("" if it did not)
  ReplayErrors errors;
  ReplayTraces traces;  ///< empty unless ReplayOptions::keep_traces
};

struct ReplayResult {
  double period_s = 0.01;
  std::size_t window_ticks = 0;
  std::vector<ReplayWindow> windows;
  ReplayErrors overall;
  std::size_t ticks_in_log = 0;
  std::size_t ticks_not_replayed = 0;  ///< the tail shorter than a window, and around gaps
  std::array<std::string, hal::kServoCount> servo_names;
};

/// The control period of `log` [ns] (its header's period_ns), or an error naming the field.
Status log_period_ns(const fw::FlightLog& log, std::int64_t& out);

/// Checks that a window of `window_s` fits in `log` (which check_replayable accepted): the
/// error names --window, the window and the log's longest run of consecutive ticks.
Status check_window(const fw::FlightLog& log, double window_s);

/// The number of windows of `window_s` in `log` (which check_window accepted).
std::size_t count_windows(const fw::FlightLog& log, double window_s);

/// The index in FlightLog::ticks of each window's starting state, in the windows' order (the
/// numbers of ReplayOptions::only_windows); `ticks`, if given, is set to the window's length in
/// control periods. Empty for a log without a period.
std::vector<std::size_t> window_first_indices(const fw::FlightLog& log, double window_s,
                                              std::size_t* ticks = nullptr);

/// Replays `log` (which check_replayable and check_window accepted) in `world` (its control
/// period is taken from the log). Fails only if the world cannot be built.
Status replay_flight_log(const fw::FlightLog& log, const WorldOptions& world,
                         const ReplayOptions& options, ReplayResult& out);

}  // namespace stride::sim
