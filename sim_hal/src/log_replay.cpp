// Replay of a flight log against the simulated robot: windows, placement, error sums.
#include "stride/sim_hal/log_replay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <thread>

#include <Eigen/Geometry>

#include "stride/firmware/recorder/flight_log_header.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {

// ---------------------------------------------------------------------------------------------
// Attitude

double log_attitude_time_constant(const fw::FlightLog& log) {
  const nlohmann::json& params =
      log.header.contains("parameters") ? log.header["parameters"] : nlohmann::json();
  if (params.is_array()) {
    for (const nlohmann::json& p : params) {
      if (p.is_object() && p.value("name", "") == "walk.balance.tilt_filter_time" &&
          p.contains("value") && p["value"].is_number() && p["value"].get<double>() > 0.0)
        return p["value"].get<double>();
    }
  }
  return fw::AttitudeEstimator::kDefaultTimeConstantS;
}

// ---------------------------------------------------------------------------------------------
// Checks

Status log_period_ns(const fw::FlightLog& log, std::int64_t& out) {
  const nlohmann::json& p = log.header.contains("period_ns") ? log.header["period_ns"] : nullptr;
  if (!p.is_number_integer() || p.get<std::int64_t>() <= 0)
    return Status::error("the header has no positive integer period_ns");
  out = p.get<std::int64_t>();
  return Status::ok();
}

Status check_replayable(const fw::FlightLog& log, const fw::ServoTable& servos,
                        const fw::RobotDescription& robot, bool allow_truncated) {
  if (!log.header.is_object() || log.header.value("format", "") != "stride-flight-log")
    return Status::error("not a Stride flight log (header format is not stride-flight-log)");
  if (!log.stopped_early.empty() && !allow_truncated)
    return Status::error("truncated or damaged: " + log.stopped_early + " (" +
                         std::to_string(log.ticks.size()) +
                         " whole ticks before it; --allow-truncated replays them)");
  std::int64_t period = 0;
  if (Status s = log_period_ns(log, period); !s) return s;
  const nlohmann::json table = fw::flight_log::servo_table_json(servos);
  const nlohmann::json& logged =
      log.header.contains("servo_table") ? log.header["servo_table"] : nlohmann::json();
  if (!logged.is_array() || logged.size() != table.size())
    return Status::error("the log's servo table does not match the firmware's (" +
                         std::to_string(logged.is_array() ? logged.size() : 0) + " servos, not " +
                         std::to_string(table.size()) + ")");
  for (std::size_t i = 0; i < table.size(); ++i)
    if (logged[i] != table[i])
      return Status::error("the log's servo table does not match the firmware's: servo " +
                           std::to_string(i + 1) + " is " + logged[i].dump() + " in the log, " +
                           table[i].dump() + " in the servo table");
  const std::string hash = fw::flight_log::robot_description_hash(servos, robot);
  std::string logged_hash;
  if (log.header.contains("robot_description") && log.header["robot_description"].is_object())
    logged_hash = log.header["robot_description"].value("hash", "");
  if (logged_hash != hash)
    return Status::error("the log's robot description (" +
                         (logged_hash.empty() ? std::string("no hash") : logged_hash) +
                         ") does not match the firmware's (" + hash +
                         "; --robot-description names another)");
  if (log.ticks.empty()) return Status::error("the log has no complete tick");
  return Status::ok();
}

namespace {

/// True if log tick `i` follows tick i-1 without a gap (no overrun, nothing dropped).
bool follows(const fw::FlightLog& log, std::size_t i) {
  return i > 0 && log.ticks[i].meta.tick == log.ticks[i - 1].meta.tick + 1 &&
         log.ticks[i].meta.dropped_before == 0;
}

/// The longest run of consecutive ticks, in periods (entries - 1).
std::size_t longest_run(const fw::FlightLog& log) {
  std::size_t best = 0, run = 0;
  for (std::size_t i = 1; i < log.ticks.size(); ++i) {
    run = follows(log, i) ? run + 1 : 0;
    best = std::max(best, run);
  }
  return best;
}

std::size_t window_ticks(double window_s, std::int64_t period_ns) {
  const double n = std::round(window_s * 1e9 / static_cast<double>(period_ns));
  return n >= 1.0 && n < 1e12 ? static_cast<std::size_t>(n) : 0;
}

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g s", s);
  return text;
}

}  // namespace

Status check_window(const fw::FlightLog& log, double window_s) {
  std::int64_t period = 0;
  if (Status s = log_period_ns(log, period); !s) return s;
  if (!(window_s > 0.0) || !std::isfinite(window_s))
    return Status::error("--window: must be a positive number of seconds");
  const std::size_t n = window_ticks(window_s, period);
  const double period_s = static_cast<double>(period) * 1e-9;
  if (n == 0)
    return Status::error("--window: " + seconds(window_s) +
                         " is shorter than one control period (" + seconds(period_s) + ")");
  const std::size_t run = longest_run(log);
  if (n > run)
    return Status::error("--window: " + seconds(window_s) + " is longer than the log (" +
                         seconds(static_cast<double>(run) * period_s) + " of consecutive ticks, " +
                         std::to_string(log.ticks.size()) + " ticks)");
  return Status::ok();
}

// ---------------------------------------------------------------------------------------------
// Replay

namespace {

/// The IMU's means and peaks skip each window's first second: the placed robot settling on its
/// feet turns and shakes the trunk in the simulation alone.
constexpr double kSettleS = 1.0;

/// Sums of squared errors, turned into ReplayErrors.
struct ErrorSums {
  std::array<double, hal::kServoCount> position{}, speed{}, load{};
  std::array<std::size_t, hal::kServoCount> servo_samples{};
  double roll = 0.0, pitch = 0.0;
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero(), accel = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_diff = Eigen::Vector3d::Zero(), accel_diff = Eigen::Vector3d::Zero();
  double peak_logged = 0.0, peak_sim = 0.0;
  std::size_t settled_samples = 0;  ///< in the means and peaks
  std::size_t imu_samples = 0;
  std::size_t ticks = 0;

  void merge(const ErrorSums& o) {
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      position[i] += o.position[i];
      speed[i] += o.speed[i];
      load[i] += o.load[i];
      servo_samples[i] += o.servo_samples[i];
    }
    roll += o.roll;
    pitch += o.pitch;
    gyro += o.gyro;
    accel += o.accel;
    gyro_diff += o.gyro_diff;
    accel_diff += o.accel_diff;
    peak_logged = std::max(peak_logged, o.peak_logged);
    peak_sim = std::max(peak_sim, o.peak_sim);
    settled_samples += o.settled_samples;
    imu_samples += o.imu_samples;
    ticks += o.ticks;
  }

  ReplayErrors rms() const {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    const auto root = [](double sum, std::size_t n) {
      return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : kNaN;
    };
    ReplayErrors e;
    double p = 0.0, v = 0.0, l = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      e.position_rad[i] = root(position[i], servo_samples[i]);
      e.speed_rad_s[i] = root(speed[i], servo_samples[i]);
      e.load[i] = root(load[i], servo_samples[i]);
      p += position[i];
      v += speed[i];
      l += load[i];
      n += servo_samples[i];
    }
    e.position_all_rad = root(p, n);
    e.speed_all_rad_s = root(v, n);
    e.load_all = root(l, n);
    e.roll_rad = root(roll, imu_samples);
    e.pitch_rad = root(pitch, imu_samples);
    for (int k = 0; k < 3; ++k) {
      e.gyro_rad_s[k] = root(gyro[k], imu_samples);
      e.accel_mps2[k] = root(accel[k], imu_samples);
    }
    const double settled = settled_samples > 0 ? static_cast<double>(settled_samples) : kNaN;
    e.gyro_mean_rad_s = gyro_diff / settled;
    e.accel_mean_mps2 = accel_diff / settled;
    e.peak_accel_logged_mps2 = peak_logged;
    e.peak_accel_sim_mps2 = peak_sim;
    e.mean_samples = settled_samples;
    e.samples = ticks;
    return e;
  }
};

Eigen::Vector3d accel_of(const hal::SensorFrame& f) {
  return {f.cm730.accel_mps2[0], f.cm730.accel_mps2[1], f.cm730.accel_mps2[2]};
}

Eigen::Vector3d gyro_of(const hal::SensorFrame& f) {
  return {f.cm730.gyro_rad_s[0], f.cm730.gyro_rad_s[1], f.cm730.gyro_rad_s[2]};
}

/// The trunk's attitude at every log tick: the firmware's estimator over the log, restarted at
/// gaps.
std::vector<fw::AttitudeEstimator> tilt_over_log(const fw::FlightLog& log, double period_s) {
  const fw::AttitudeEstimator fresh(period_s, log_attitude_time_constant(log), true);
  std::vector<fw::AttitudeEstimator> out(log.ticks.size(), fresh);
  fw::AttitudeEstimator filter = fresh;
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    const hal::SensorFrame& f = log.ticks[i].sensors;
    if (follows(log, i))
      filter.update(accel_of(f), gyro_of(f));
    else
      filter.start(accel_of(f));
    out[i] = filter;
  }
  return out;
}

/// The trunk's orientation of roll and pitch (yaw 0).
Eigen::Quaterniond trunk_orientation(double roll, double pitch) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
}

void keep(ReplayTraces& t, double time_s, std::size_t log_index, const hal::SensorFrame& logged,
          const hal::SensorFrame& sim, const fw::AttitudeEstimator& logged_tilt,
          const fw::AttitudeEstimator& sim_tilt) {
  t.time_s.push_back(time_s);
  t.log_index.push_back(log_index);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    t.logged_position[i].push_back(static_cast<float>(logged.servos[i].position_rad));
    t.sim_position[i].push_back(static_cast<float>(sim.servos[i].position_rad));
    t.logged_speed[i].push_back(static_cast<float>(logged.servos[i].speed_rad_s));
    t.sim_speed[i].push_back(static_cast<float>(sim.servos[i].speed_rad_s));
    t.logged_load[i].push_back(static_cast<float>(logged.servos[i].load));
    t.sim_load[i].push_back(static_cast<float>(sim.servos[i].load));
  }
  t.logged_roll.push_back(static_cast<float>(logged_tilt.roll()));
  t.sim_roll.push_back(static_cast<float>(sim_tilt.roll()));
  t.logged_pitch.push_back(static_cast<float>(logged_tilt.pitch()));
  t.sim_pitch.push_back(static_cast<float>(sim_tilt.pitch()));
  for (std::size_t k = 0; k < 3; ++k) {
    t.logged_gyro[k].push_back(static_cast<float>(logged.cm730.gyro_rad_s[k]));
    t.sim_gyro[k].push_back(static_cast<float>(sim.cm730.gyro_rad_s[k]));
    t.logged_accel[k].push_back(static_cast<float>(logged.cm730.accel_mps2[k]));
    t.sim_accel[k].push_back(static_cast<float>(sim.cm730.accel_mps2[k]));
  }
}

}  // namespace

namespace {

/// The first tick index of every window: runs of n periods of consecutive ticks, one after the
/// other, restarting after a gap.
std::vector<std::size_t> window_starts(const fw::FlightLog& log, std::size_t n) {
  std::vector<std::size_t> starts;
  for (std::size_t first = 0; first + n < log.ticks.size();) {
    std::size_t last = first + 1;
    while (last <= first + n && follows(log, last)) ++last;
    if (last <= first + n) {  // a gap before the window's end: start again after it
      first = last;
      continue;
    }
    starts.push_back(first);
    first += n;
  }
  return starts;
}

/// Replays one window of n periods from log tick `first` on `robot`; `used` marks the log
/// ticks compared.
ReplayWindow replay_window(SimRobot& robot, const fw::FlightLog& log,
                           const std::vector<fw::AttitudeEstimator>& tilt, std::size_t first,
                           std::size_t n, double period_s, std::uint64_t seed,
                           const ReplayOptions& options, ErrorSums& sums, std::vector<char>& used) {
  ReplayWindow window;
  window.first_index = first;
  window.start_tick = log.ticks[first].meta.tick;
  window.start_s = static_cast<double>(window.start_tick) * period_s;
  const hal::SensorFrame& start = log.ticks[first].sensors;
  fw::AttitudeEstimator logged_tilt = tilt[first], sim_tilt = tilt[first];
  window.start_roll_pitch = {logged_tilt.roll(), logged_tilt.pitch()};

  ResetSpec spec;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    spec.joint_angles[i] = start.servos[i].position_rad;
    if (options.start_with_logged_speeds) spec.joint_speeds[i] = start.servos[i].speed_rad_s;
  }
  spec.torso_orientation = trunk_orientation(logged_tilt.roll(), logged_tilt.pitch());
  spec.still_lower_foot = options.start_with_logged_speeds;
  spec.sink_into_grass = options.sink_into_grass;
  spec.level_feet = false;  // the trunk's attitude is the logged one, not the feet's
  // The commands the servos were acting on (command latency), the latest first.
  for (std::size_t k = 1; k <= RobotCalibration::kMaxLatencyTicks + 1 && k <= first; ++k)
    spec.previous_commands.push_back(log.ticks[first - k].commands);
  // The same randomisation as the logged run's first reset (that world's seed).
  robot.world().reseed(seed);
  if (Status s = robot.world().reset(spec); !s) {
    window.failure = s.message();
    return window;
  }
  used[first] = 1;
  hal::SensorFrame sim{};
  for (std::size_t k = 0; k < n; ++k) {
    robot.write(log.ticks[first + k].commands);
    robot.sleep_until(robot.current_tick() + 1);
    if (robot.world().status() != WorldStatus::kRunning) {
      window.failure = robot.world().failure_reason();
      break;
    }
    robot.read(sim);
    const fw::FlightLogTick& logged_tick = log.ticks[first + k + 1];
    const hal::SensorFrame& logged = logged_tick.sensors;
    used[first + k + 1] = 1;
    ++sums.ticks;
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      if (logged.servos[i].health != hal::DeviceHealth::kOk) continue;  // stale reading
      const auto sq = [](double d) { return d * d; };
      sums.position[i] += sq(sim.servos[i].position_rad - logged.servos[i].position_rad);
      sums.speed[i] += sq(sim.servos[i].speed_rad_s - logged.servos[i].speed_rad_s);
      sums.load[i] += sq(sim.servos[i].load - logged.servos[i].load);
      ++sums.servo_samples[i];
    }
    logged_tilt.update(accel_of(logged), gyro_of(logged));
    sim_tilt.update(accel_of(sim), gyro_of(sim));
    if (logged.cm730.health == hal::DeviceHealth::kOk) {
      sums.roll += std::pow(sim_tilt.roll() - logged_tilt.roll(), 2);
      sums.pitch += std::pow(sim_tilt.pitch() - logged_tilt.pitch(), 2);
      sums.gyro += (gyro_of(sim) - gyro_of(logged)).cwiseAbs2();
      sums.accel += (accel_of(sim) - accel_of(logged)).cwiseAbs2();
      if (static_cast<double>(k + 1) * period_s >= kSettleS) {
        sums.gyro_diff += gyro_of(logged) - gyro_of(sim);
        sums.accel_diff += accel_of(logged) - accel_of(sim);
        ++sums.settled_samples;
        sums.peak_logged = std::max(sums.peak_logged, accel_of(logged).norm());
        sums.peak_sim = std::max(sums.peak_sim, accel_of(sim).norm());
      }
      ++sums.imu_samples;
    }
    if (options.keep_traces)
      keep(window.traces, static_cast<double>(logged_tick.meta.tick) * period_s, first + k + 1,
           logged, sim, logged_tilt, sim_tilt);
  }
  window.ticks = sums.ticks;
  window.errors = sums.rms();
  return window;
}

}  // namespace

std::size_t count_windows(const fw::FlightLog& log, double window_s) {
  std::int64_t period_ns = 0;
  if (!log_period_ns(log, period_ns)) return 0;
  const std::size_t n = window_ticks(window_s, period_ns);
  return n == 0 ? 0 : window_starts(log, n).size();
}

std::vector<std::size_t> window_first_indices(const fw::FlightLog& log, double window_s,
                                              std::size_t* ticks) {
  std::int64_t period_ns = 0;
  if (!log_period_ns(log, period_ns)) return {};
  const std::size_t n = window_ticks(window_s, period_ns);
  if (ticks != nullptr) *ticks = n;
  return n == 0 ? std::vector<std::size_t>{} : window_starts(log, n);
}

Status replay_flight_log(const fw::FlightLog& log, const WorldOptions& world,
                         const ReplayOptions& options, ReplayResult& out) {
  out = {};
  std::int64_t period_ns = 0;
  if (Status s = log_period_ns(log, period_ns); !s) return s;
  if (Status s = check_window(log, options.window_s); !s) return s;
  const double period_s = static_cast<double>(period_ns) * 1e-9;
  const std::size_t n = window_ticks(options.window_s, period_ns);
  out.period_s = period_s;
  out.window_ticks = n;
  out.ticks_in_log = log.ticks.size();
  const nlohmann::json table = log.header.value("servo_table", nlohmann::json::array());
  for (std::size_t i = 0; i < hal::kServoCount; ++i)
    out.servo_names[i] = i < table.size() && table[i].is_object()
                             ? table[i].value("name", "servo " + std::to_string(i + 1))
                             : "servo " + std::to_string(i + 1);

  WorldOptions world_options = world;
  world_options.control_period_ns = period_ns;
  world_options.ball.present = false;  // the log does not say where a ball was
  const std::vector<fw::AttitudeEstimator> tilt = tilt_over_log(log, period_s);

  // The windows to replay, then each thread takes every threads-th of them on its own world;
  // the sums are merged in window order, so the result is the same for any thread count.
  const std::vector<std::size_t> starts = window_starts(log, n);
  std::vector<std::size_t> chosen;
  for (std::size_t w = 0; w < starts.size(); ++w)
    if (options.only_windows.empty() ||
        std::find(options.only_windows.begin(), options.only_windows.end(), w) !=
            options.only_windows.end())
      chosen.push_back(w);
  std::vector<ReplayWindow> windows(chosen.size());
  std::vector<ErrorSums> sums(chosen.size());
  const std::size_t threads = std::max<std::size_t>(
      1,
      std::min<std::size_t>(static_cast<std::size_t>(std::max(1, options.threads)), chosen.size()));
  std::vector<std::vector<char>> used(threads, std::vector<char>(log.ticks.size(), 0));
  std::vector<Status> status(threads, Status::ok());
  const auto work = [&](std::size_t t) {
    std::unique_ptr<SimWorld> sim_world;
    if (Status s = SimWorld::create(world_options, sim_world); !s) {
      status[t] = s;
      return;
    }
    SimRobot robot(std::move(sim_world));
    for (std::size_t k = t; k < chosen.size(); k += threads) {
      windows[k] = replay_window(robot, log, tilt, starts[chosen[k]], n, period_s,
                                 world_options.seed, options, sums[k], used[t]);
      windows[k].index = chosen[k];
    }
  };
  if (threads == 1) {
    work(0);
  } else {
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(work, t);
    for (std::thread& th : pool) th.join();
  }
  for (const Status& s : status)
    if (!s) return s;
  ErrorSums overall;
  for (const ErrorSums& s : sums) overall.merge(s);
  out.windows = std::move(windows);
  out.overall = overall.rms();
  std::size_t replayed = 0;
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    bool any = false;
    for (const auto& u : used) any = any || u[i] != 0;
    replayed += any ? 1 : 0;
  }
  out.ticks_not_replayed = log.ticks.size() - replayed;
  return Status::ok();
}

}  // namespace stride::sim
