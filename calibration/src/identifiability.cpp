// Identifiability of the calibration's values (identifiability.hpp): the finite-difference
// sensitivities of the replayed logs, the Fisher matrix, the standard errors and correlations,
// the routine's parts, and the table stride calibrate --identifiability prints.
#include "stride/calibration/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include <Eigen/Cholesky>

#include "stride/calibration/calibration.hpp"
#include "stride/sim_hal/identification_run.hpp"
#include "stride/sim_hal/servo_model.hpp"

namespace stride::calibration {

namespace {

constexpr std::size_t kServos = hal::kServoCount;
/// Per compared tick: position, speed and load of every servo, gyro, accelerometer.
constexpr std::size_t kChannels = 3 * kServos + 6;
/// The MX's present-speed register unit (0.114 rpm, as SimWorld quantises it) [rad/s].
constexpr double kSpeedUnit = 0.114 * 2.0 * 3.14159265358979323846 / 60.0;
/// The MX's present-load register unit: 1/1023 of the maximum torque.
constexpr double kLoadUnit = 1.0 / 1023.0;
/// Relative ridge added to the Fisher matrix before it is inverted, so that two values that
/// move the logs identically come out with a correlation of -+1 instead of a failed inversion.
constexpr double kRidge = 1e-9;

/// The simulated channels of every compared tick: [log][window][row * kChannels + channel], and
/// the log tick of each row.
struct Simulated {
  std::vector<std::vector<std::vector<float>>> values;
  std::vector<std::vector<std::vector<std::size_t>>> log_index;
};

/// The channel group of a channel: position, speed, load, gyro, accelerometer.
std::size_t group_of(std::size_t channel) {
  return channel < 3 * kServos ? channel / kServos : (channel < 3 * kServos + 3 ? 3 : 4);
}

/// Sums of squared residuals (simulated - logged) and sample counts per channel group.
struct Residuals {
  std::array<double, 5> sum_sq{};
  std::array<double, 5> count{};
};

Status simulate(const std::vector<const fw::FlightLog*>& logs, const sim::WorldOptions& base,
                const sim::WorldFile& world_file, const sim::ReplayOptions& replay, Simulated& out,
                Residuals* residuals = nullptr) {
  sim::WorldOptions world = base;
  world_file.apply_calibration(world);
  out.values.assign(logs.size(), {});
  out.log_index.assign(logs.size(), {});
  for (std::size_t l = 0; l < logs.size(); ++l) {
    sim::ReplayOptions options = replay;
    options.keep_traces = true;
    options.only_windows.clear();
    sim::ReplayResult result;
    if (Status s = sim::replay_flight_log(*logs[l], world, options, result); !s) return s;
    for (const sim::ReplayWindow& w : result.windows) {
      const sim::ReplayTraces& t = w.traces;
      const std::size_t rows = t.time_s.size();
      std::vector<float> v(rows * kChannels);
      for (std::size_t r = 0; r < rows; ++r) {
        float* row = v.data() + r * kChannels;
        for (std::size_t i = 0; i < kServos; ++i) {
          row[i] = t.sim_position[i][r];
          row[kServos + i] = t.sim_speed[i][r];
          row[2 * kServos + i] = t.sim_load[i][r];
        }
        for (std::size_t k = 0; k < 3; ++k) {
          row[3 * kServos + k] = t.sim_gyro[k][r];
          row[3 * kServos + 3 + k] = t.sim_accel[k][r];
        }
        if (residuals == nullptr) continue;
        const hal::SensorFrame& logged = logs[l]->ticks[t.log_index[r]].sensors;
        const auto add = [&residuals](std::size_t group, double d) {
          residuals->sum_sq[group] += d * d;
          residuals->count[group] += 1.0;
        };
        for (std::size_t i = 0; i < kServos; ++i) {
          if (logged.servos[i].health != hal::DeviceHealth::kOk) continue;
          add(0, row[i] - logged.servos[i].position_rad);
          add(1, row[kServos + i] - logged.servos[i].speed_rad_s);
          add(2, row[2 * kServos + i] - logged.servos[i].load);
        }
        if (logged.cm730.health != hal::DeviceHealth::kOk) continue;
        for (std::size_t k = 0; k < 3; ++k) {
          add(3, row[3 * kServos + k] - logged.cm730.gyro_rad_s[k]);
          add(4, row[3 * kServos + 3 + k] - logged.cm730.accel_mps2[k]);
        }
      }
      out.values[l].push_back(std::move(v));
      out.log_index[l].push_back(t.log_index);
    }
  }
  return Status::ok();
}

/// The part of the routine each tick of `log` belongs to (an index into `parts`, which grows).
std::vector<int> label_parts(const fw::FlightLog& log, std::vector<std::string>& parts) {
  std::vector<std::string> scripts;
  for (const std::string& part : sim::identification_parts())
    if (part.rfind("identify_", 0) == 0) scripts.push_back(part);
  int script_runs = 0;
  fw::MotionState previous = fw::MotionState::kStand;
  for (const fw::FlightLogTick& t : log.ticks) {
    if (t.meta.motion == fw::MotionState::kScript && previous != fw::MotionState::kScript)
      ++script_runs;
    previous = t.meta.motion;
  }
  const bool routine = script_runs == static_cast<int>(scripts.size());
  const auto index_of = [&parts](const std::string& name) {
    const auto it = std::find(parts.begin(), parts.end(), name);
    if (it != parts.end()) return static_cast<int>(it - parts.begin());
    parts.push_back(name);
    return static_cast<int>(parts.size() - 1);
  };
  std::vector<int> out(log.ticks.size());
  int current = index_of("stand");
  int script = 0;
  previous = fw::MotionState::kStand;
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    const fw::MotionState state = log.ticks[i].meta.motion;
    if (state != previous) {
      if (state == fw::MotionState::kScript)
        current = index_of(routine ? scripts[static_cast<std::size_t>(script)]
                                   : "script " + std::to_string(script + 1));
      if (state == fw::MotionState::kScript) ++script;
      if (state == fw::MotionState::kWalk) current = index_of("walk");
      if (state == fw::MotionState::kFallen || state == fw::MotionState::kFalling ||
          state == fw::MotionState::kGetUp)
        current = index_of("fallen");
    }
    previous = state;
    out[i] = current;
  }
  return out;
}

const CalibrationParameter& parameter(const std::string& name) {
  for (const CalibrationParameter& p : calibration_parameters())
    if (p.name == name) return p;
  return calibration_parameters().front();  // names are checked by parse_fit_names
}

/// The covariance of the estimates (a small ridge keeps identical columns invertible) and their
/// correlation.
Eigen::MatrixXd invert(const Eigen::MatrixXd& fisher, Eigen::MatrixXd& correlation) {
  const double largest = fisher.rows() > 0 ? fisher.diagonal().maxCoeff() : 0.0;
  Eigen::MatrixXd regular = fisher;
  regular.diagonal().array() += kRidge * std::max(largest, 1e-300);
  const Eigen::MatrixXd covariance =
      regular.ldlt().solve(Eigen::MatrixXd::Identity(regular.rows(), regular.cols()));
  correlation = covariance;
  for (Eigen::Index i = 0; i < covariance.rows(); ++i)
    for (Eigen::Index j = 0; j < covariance.cols(); ++j)
      correlation(i, j) = covariance(i, j) / std::sqrt(covariance(i, i) * covariance(j, j));
  return covariance;
}

/// Value i's errors and most correlated partner under one Fisher matrix.
void summarise(const Eigen::MatrixXd& fisher, const Eigen::MatrixXd& covariance,
               const Eigen::MatrixXd& correlation, const std::vector<std::string>& names,
               std::size_t i, double step, ValueErrors& out) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const auto ii = static_cast<Eigen::Index>(i);
  const double f = fisher(ii, ii);
  out.alone_error = f > 0.0 ? step / std::sqrt(f) : kInf;
  out.standard_error = f > 0.0 ? step * std::sqrt(covariance(ii, ii)) : kInf;
  for (std::size_t j = 0; j < names.size(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    const double r = correlation(ii, jj);
    if (j != i && f > 0.0 && fisher(jj, jj) > 0.0 &&
        (out.partner.empty() || std::abs(r) > std::abs(out.correlation))) {
      out.partner = names[j];
      out.correlation = r;
    }
  }
}

}  // namespace

SensorNoise sensor_noise(const sim::WorldOptions& world) {
  sim::ImuOptions imu = world.imu;
  imu.set_noise(true);
  const auto quantised = [](double lsb) { return lsb / std::sqrt(12.0); };
  SensorNoise n;
  n.position_rad = quantised(sim::kEncoderRadPerTick);
  n.speed_rad_s = quantised(kSpeedUnit);
  n.load = quantised(kLoadUnit);
  const sim::ImuChain& c = imu.chain;
  if (c.is_ideal()) {
    n.gyro_rad_s = imu.gyro_noise_std;
    n.accel_mps2 = imu.accel_noise_std;
    return n;
  }
  // A chip's white noise over its noise bandwidth (pi/2 x cut-off), averaged over the distinct
  // chip samples among the CM730's last readings, then the chip's and the register's LSB.
  const auto chip_noise = [&c](const sim::ImuChip& chip, double register_lsb) {
    const double span_s = c.cm730_average / c.cm730_read_rate_hz;
    const double distinct =
        std::clamp(span_s * chip.output_rate_hz, 1.0, static_cast<double>(c.cm730_average));
    const double white = chip.noise_density * std::sqrt(0.5 * M_PI * chip.cutoff_hz);
    const double chip_lsb = chip.resolution / std::sqrt(12.0);
    return std::sqrt(white * white / distinct + chip_lsb * chip_lsb +
                     register_lsb * register_lsb / 12.0);
  };
  n.gyro_rad_s = chip_noise(c.gyro, c.gyro_register_lsb);
  n.accel_mps2 = chip_noise(c.accel, c.accel_register_lsb);
  return n;
}

Status analyse_identifiability(const std::vector<const fw::FlightLog*>& logs,
                               const sim::WorldOptions& base, const sim::WorldFile& start,
                               const IdentifiabilityOptions& options, IdentifiabilityResult& out) {
  out = {};
  out.noise = sensor_noise(base);
  std::array<double, kChannels> weight{};  // 1 / sigma per channel
  for (std::size_t i = 0; i < kServos; ++i) {
    weight[i] = 1.0 / out.noise.position_rad;
    weight[kServos + i] = 1.0 / out.noise.speed_rad_s;
    weight[2 * kServos + i] = 1.0 / out.noise.load;
  }
  for (std::size_t k = 0; k < 3; ++k) {
    weight[3 * kServos + k] = out.noise.gyro_rad_s > 0.0 ? 1.0 / out.noise.gyro_rad_s : 0.0;
    weight[3 * kServos + 3 + k] = out.noise.accel_mps2 > 0.0 ? 1.0 / out.noise.accel_mps2 : 0.0;
  }

  Simulated nominal;
  Residuals residuals;
  if (Status s = simulate(logs, base, start, options.replay, nominal, &residuals); !s) return s;
  out.replays = 1;
  // The part of every row, in the nominal replay's layout.
  std::vector<int> row_part;
  for (std::size_t l = 0; l < logs.size(); ++l) {
    const std::vector<int> part_of_tick = label_parts(*logs[l], out.parts);
    for (const auto& window : nominal.log_index[l])
      for (std::size_t index : window) row_part.push_back(part_of_tick[index]);
  }
  out.part_samples.assign(out.parts.size(), 0);
  for (int p : row_part) ++out.part_samples[static_cast<std::size_t>(p)];
  const std::size_t rows = row_part.size();

  // One column per value: d(sample)/d(value) x step / sigma, row-major over the nominal layout.
  const std::size_t n = options.names.size();
  std::vector<std::vector<float>> columns(n, std::vector<float>(rows * kChannels, 0.0F));
  for (std::size_t v = 0; v < n; ++v) {
    const CalibrationParameter& p = parameter(options.names[v]);
    const double origin = calibration_value(start, p.name);
    const double h = p.whole ? 1.0 : p.step;
    const bool up = origin + h <= p.upper + 1e-12, down = origin - h >= p.lower - 1e-12;
    Simulated plus, minus;
    sim::WorldFile moved = start;
    if (up) {
      set_calibration_value(moved, p.name, origin + h);
      if (Status s = simulate(logs, base, moved, options.replay, plus); !s) return s;
      ++out.replays;
    }
    if (down || !up) {
      set_calibration_value(moved, p.name, origin - h);
      if (Status s = simulate(logs, base, moved, options.replay, minus); !s) return s;
      ++out.replays;
    }
    const Simulated& hi = up ? plus : nominal;
    const Simulated& lo = (down || !up) ? minus : nominal;
    const double span = (up && down) ? 2.0 * h : h;
    std::size_t row0 = 0;
    for (std::size_t l = 0; l < logs.size(); ++l) {
      for (std::size_t w = 0; w < nominal.values[l].size(); ++w) {
        const std::size_t n_rows = nominal.values[l][w].size() / kChannels;
        // A window whose simulation stopped early in one run counts up to the stop.
        const std::size_t common = std::min(
            {n_rows, hi.values[l][w].size() / kChannels, lo.values[l][w].size() / kChannels});
        for (std::size_t r = 0; r < common; ++r)
          for (std::size_t c = 0; c < kChannels; ++c) {
            const std::size_t at = r * kChannels + c;
            const double d = (static_cast<double>(hi.values[l][w][at]) - lo.values[l][w][at]) /
                             span * p.step * weight[c];
            columns[v][(row0 + r) * kChannels + c] = static_cast<float>(d);
          }
        row0 += n_rows;
      }
    }
  }

  // Fisher matrices per step of each value (sensor noise; replay floor: each channel group's
  // noise raised to the RMS residual of the start world), and the first's diagonal per part.
  std::array<double, kChannels> floor_factor{};  // (sigma_sensor / sigma_floor)^2
  const std::array<double, 5> sensor = {out.noise.position_rad, out.noise.speed_rad_s,
                                        out.noise.load, out.noise.gyro_rad_s, out.noise.accel_mps2};
  std::array<double, 5> floor{};
  for (std::size_t g = 0; g < 5; ++g) {
    const double rms =
        residuals.count[g] > 0 ? std::sqrt(residuals.sum_sq[g] / residuals.count[g]) : 0.0;
    floor[g] = std::max(sensor[g], rms);
  }
  out.floor = {floor[0], floor[1], floor[2], floor[3], floor[4]};
  for (std::size_t c = 0; c < kChannels; ++c) {
    const std::size_t g = group_of(c);
    floor_factor[c] = floor[g] > 0.0 ? std::pow(sensor[g] / floor[g], 2) : 0.0;
  }
  const auto size = static_cast<Eigen::Index>(n);
  out.fisher = Eigen::MatrixXd::Zero(size, size);
  out.fisher_floor = Eigen::MatrixXd::Zero(size, size);
  std::vector<std::vector<double>> part_diagonal(n, std::vector<double>(out.parts.size(), 0.0));
  for (std::size_t r = 0; r < rows; ++r) {
    const auto part = static_cast<std::size_t>(row_part[r]);
    for (std::size_t i = 0; i < n; ++i) {
      const float* a = columns[i].data() + r * kChannels;
      for (std::size_t j = i; j < n; ++j) {
        const float* b = columns[j].data() + r * kChannels;
        double dot = 0.0, dot_floor = 0.0;
        for (std::size_t c = 0; c < kChannels; ++c) {
          const double ab = static_cast<double>(a[c]) * b[c];
          dot += ab;
          dot_floor += ab * floor_factor[c];
        }
        const auto ii = static_cast<Eigen::Index>(i), jj = static_cast<Eigen::Index>(j);
        out.fisher(ii, jj) += dot;
        out.fisher_floor(ii, jj) += dot_floor;
        if (i == j) part_diagonal[i][part] += dot;
      }
    }
  }
  out.fisher = out.fisher.selfadjointView<Eigen::Upper>();
  out.fisher_floor = out.fisher_floor.selfadjointView<Eigen::Upper>();
  const Eigen::MatrixXd covariance = invert(out.fisher, out.correlation);
  const Eigen::MatrixXd covariance_floor = invert(out.fisher_floor, out.correlation_floor);

  for (std::size_t i = 0; i < n; ++i) {
    ValueIdentifiability v;
    v.name = options.names[i];
    v.step = parameter(v.name).step;
    for (double d : part_diagonal[i]) v.per_part.push_back(std::sqrt(d));
    const auto ii = static_cast<Eigen::Index>(i);
    v.total = std::sqrt(out.fisher(ii, ii));
    summarise(out.fisher, covariance, out.correlation, options.names, i, v.step, v.sensor);
    summarise(out.fisher_floor, covariance_floor, out.correlation_floor, options.names, i, v.step,
              v.floor);
    out.values.push_back(v);
  }
  return Status::ok();
}

std::vector<ConfoundedPair> confounded_pairs(const IdentifiabilityResult& result,
                                             double threshold) {
  std::vector<ConfoundedPair> out;
  const std::size_t n = result.values.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (result.values[i].total <= 0.0 || result.values[j].total <= 0.0) continue;
      const auto ii = static_cast<Eigen::Index>(i), jj = static_cast<Eigen::Index>(j);
      const double r = result.correlation(ii, jj), r_floor = result.correlation_floor(ii, jj);
      const bool floor = std::abs(r_floor) > std::abs(r);
      if (std::max(std::abs(r), std::abs(r_floor)) > threshold)
        out.push_back({result.values[i].name, result.values[j].name, floor ? r_floor : r, floor});
    }
  std::sort(out.begin(), out.end(), [](const ConfoundedPair& a, const ConfoundedPair& b) {
    return std::abs(a.correlation) > std::abs(b.correlation);
  });
  return out;
}

std::string what_separates(const std::string& first, const std::string& second) {
  const std::set<std::string> pair = {first, second};
  const auto has = [&pair](const std::string& prefix) {
    return std::any_of(pair.begin(), pair.end(),
                       [&prefix](const std::string& n) { return n.rfind(prefix, 0) == 0; });
  };
  if (has("voltage"))
    return "the supply is measured (the CM730 reads it): leave voltage out of --fit";
  if (has("trunk_mass")) return "weigh the robot (--robot-mass) instead of fitting trunk_mass";
  if (has("torque_") && has("friction"))
    return "holds at several knee angles and torque steps (the load grows with the angle, "
           "friction does not), or moves at several speeds";
  if (has("trunk_com_") && (has("accel_bias_") || has("gyro_bias_")))
    return "slow leans to the support limits and single-leg stands (the centre of mass moves "
           "the joint loads, a bias only the IMU)";
  if (has("latency")) return "torque steps (a delay shifts the whole response in time)";
  return "a part of the routine that moves one and not the other (the evidence per part: "
         "stride calibrate --identifiability)";
}

std::string identifiability_table(const IdentifiabilityResult& r) {
  std::string out;
  char line[512];
  const auto add = [&out, &line](const char* format, auto... args) {
    std::snprintf(line, sizeof line, format, args...);
    out += line;
  };
  std::size_t samples = 0;
  for (std::size_t s : r.part_samples) samples += s;
  add("identifiability: %zu values, %zu compared ticks, %d replays\n", r.values.size(), samples,
      r.replays);
  const auto noise_line = [&add](const char* what, const SensorNoise& n) {
    add("%s: position %.2e rad, speed %.2e rad/s, load %.2e, gyro %.2e rad/s, accel %.2e m/s^2\n",
        what, n.position_rad, n.speed_rad_s, n.load, n.gyro_rad_s, n.accel_mps2);
  };
  noise_line("sensor noise per sample", r.noise);
  noise_line("replay floor (RMS residual in the start world, at least the noise)", r.floor);
  out +=
      "evidence: sqrt of the chi-square one step of the value adds, in sensor noise units, per\n"
      "part; se: standard error fitted together, with the sensor noise (alone: with the others\n"
      "known) and with the replay floor; partner: the most correlated estimate, corr: r\n";
  add("%-13s %6s", "value", "step");
  for (std::size_t p = 0; p < r.parts.size(); ++p) add(" %14s", r.parts[p].c_str());
  add(" %8s %9s %9s %-13s %6s %9s %-13s %6s\n", "total", "se", "alone", "partner", "corr",
      "se floor", "partner", "corr");
  for (const ValueIdentifiability& v : r.values) {
    add("%-13s %6.3g", v.name.c_str(), v.step);
    for (double e : v.per_part) add(" %14.3g", e);
    add(" %8.3g %9.2g %9.2g %-13s %+6.2f %9.2g %-13s %+6.2f\n", v.total, v.sensor.standard_error,
        v.sensor.alone_error, v.sensor.partner.empty() ? "-" : v.sensor.partner.c_str(),
        v.sensor.correlation, v.floor.standard_error,
        v.floor.partner.empty() ? "-" : v.floor.partner.c_str(), v.floor.correlation);
  }
  out += "correlation of the estimates (upper: sensor noise, lower: replay floor):\n";
  add("%16s", "");
  for (std::size_t j = 0; j < r.values.size(); ++j) add(" %6zu", j + 1);
  out += "\n";
  for (std::size_t i = 0; i < r.values.size(); ++i) {
    add("%2zu %-13s", i + 1, r.values[i].name.c_str());
    for (std::size_t j = 0; j < r.values.size(); ++j) {
      const auto ii = static_cast<Eigen::Index>(i), jj = static_cast<Eigen::Index>(j);
      add(" %+6.2f", j >= i ? r.correlation(ii, jj) : r.correlation_floor(ii, jj));
    }
    out += "\n";
  }
  return out;
}

}  // namespace stride::calibration
