// Episode runner: controller against SimRobot, with the `stride sim` metrics.
#include "stride/sim_hal/episode.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "stride/sim_hal/trajectory_recorder.hpp"

namespace stride::sim {

StepFunction hold_pose_controller(const std::array<double, hal::kServoCount>& pose, double p_gain) {
  return [pose, p_gain](const hal::SensorFrame&, hal::Tick tick) {
    hal::CommandFrame frame;
    frame.tick = tick;
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      frame.servos[i].position_rad = pose[i];
      frame.servos[i].p_gain = p_gain;
      frame.servos[i].torque_enable = true;
    }
    return frame;
  };
}

std::string hash_hex(std::uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

namespace {

/// The links' and the ball's poses at time `t`.
PoseSnapshot snapshot(const SimWorld& world, double t) {
  PoseSnapshot snapshot;
  snapshot.time_s = t;
  snapshot.links = world.link_poses();
  snapshot.ball = world.ground_truth().ball_position;
  return snapshot;
}

/// The impact's peaks from the first body contact over EpisodeOptions::impact_window_s, until
/// EpisodeOptions::impact_over says the landing is over (`closed`).
void measure_impact(const SimWorld& world, const EpisodeOptions& options, double t, bool& closed,
                    ImpactMeasure& m) {
  if (!m.body_contact_s && world.ground_truth().other_contacts > 0) m.body_contact_s = t;
  if (m.body_contact_s && !closed && options.impact_over && options.impact_over()) closed = true;
  if (m.body_contact_s && !closed && t <= *m.body_contact_s + options.impact_window_s) {
    const SimWorld::PeriodPeaks& p = world.last_period_peaks();
    m.peak_accel_mps2 = std::max(m.peak_accel_mps2, p.torso_accel_mps2);
    m.peak_joint_torque_nm = std::max(m.peak_joint_torque_nm, p.joint_torque_nm);
    if (p.servo_torque_nm > m.peak_servo_torque_nm) {
      m.peak_servo_torque_nm = p.servo_torque_nm;
      m.peak_servo_index = p.servo_index;
    }
  }
}

}  // namespace

EpisodeResult run_episode(SimRobot& robot, const StepFunction& controller,
                          const EpisodeOptions& options) {
  EpisodeResult result;
  SimWorld& world = robot.world();
  const double period_s = static_cast<double>(robot.period_ns()) * 1e-9;
  const auto total_ticks = static_cast<hal::Tick>(std::llround(options.duration_s / period_s));
  const GroundTruth start = world.ground_truth();
  std::size_t next_snapshot = 0;
  std::vector<double> snapshot_times = options.snapshot_times_s;
  std::sort(snapshot_times.begin(), snapshot_times.end());
  hal::SensorFrame sensors;
  hal::CommandFrame commands;
  const auto wall_start = std::chrono::steady_clock::now();
  hal::Tick tick = robot.current_tick();
  const hal::Tick first_tick = tick;
  const auto yaw_of = [](const Eigen::Isometry3d& pose) {
    return std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
  };
  double last_yaw = yaw_of(start.torso);
  bool impact_closed = false;  // EpisodeOptions::impact_over said the landing is over
  for (;;) {
    robot.read(sensors);
    commands = controller(sensors, tick);
    robot.write(commands);
    const Eigen::Isometry3d torso = world.torso_pose();
    const double t = static_cast<double>(tick - first_tick) * period_s;
    if (options.recorder) options.recorder->record(tick - first_tick, world, sensors, commands);
    if (options.on_tick) options.on_tick(tick - first_tick, world, sensors);
    while (next_snapshot < snapshot_times.size() && snapshot_times[next_snapshot] <= t + 1e-9) {
      result.snapshots.push_back(snapshot(world, t));
      ++next_snapshot;
    }
    if (world.status() != WorldStatus::kRunning) break;
    if (options.impact_metrics) measure_impact(world, options, t, impact_closed, result.impact);
    if (t >= options.metrics_start_s) {
      const auto& a = sensors.cm730.accel_mps2;
      result.max_accel =
          std::max(result.max_accel, std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]));
      result.max_fps = std::max(result.max_fps, std::sqrt(a[0] * a[0] + a[1] * a[1]));
      result.peak_servo_torque_nm =
          std::max(result.peak_servo_torque_nm, world.last_period_peaks().servo_torque_nm);
    }
    const double yaw = yaw_of(torso);  // unwrapped into turned_rad, tick by tick
    result.turned_rad += std::remainder(yaw - last_yaw, 2.0 * std::numbers::pi);
    last_yaw = yaw;
    const double forward = torso.translation().x() - start.torso.translation().x();
    if (!result.time_to_goal_s && forward >= options.goal_distance_m) result.time_to_goal_s = t;
    const double up = torso.linear()(2, 2);  // world z of the torso's z axis
    if (!result.fell && (up < 0.5 || torso.translation().z() < 0.25)) {
      result.fell = true;
      result.fall_time_s = t;
      if (options.stop_on_fall) break;
    }
    if (options.stop_at_goal && result.time_to_goal_s) break;
    if (options.stop_when && options.stop_when()) break;
    if (tick - first_tick >= total_ticks) break;
    ++tick;
    robot.sleep_until(tick);
  }
  const auto wall_end = std::chrono::steady_clock::now();
  const GroundTruth end = world.ground_truth();
  result.ticks = tick - first_tick;
  result.sim_time_s = static_cast<double>(result.ticks) * period_s;
  result.wall_time_s = std::chrono::duration<double>(wall_end - wall_start).count();
  result.rtf = result.wall_time_s > 0 ? result.sim_time_s / result.wall_time_s : 0.0;
  result.distance_m = end.torso.translation().x() - start.torso.translation().x();
  result.lateral_m = end.torso.translation().y() - start.torso.translation().y();
  result.ball_distance_m = (end.ball_position - start.ball_position).head<2>().norm();
  result.state_hash = world.state_hash();
  result.status = world.status();
  result.failure_reason = world.failure_reason();
  return result;
}

nlohmann::json to_json(const EpisodeResult& r) {
  nlohmann::json j = {{"fell", r.fell},
                      {"distance_m", r.distance_m},
                      {"lateral_m", r.lateral_m},
                      {"turned_rad", r.turned_rad},
                      {"time_to_goal_s", nullptr},
                      {"max_accel", r.max_accel},
                      {"max_fps", r.max_fps},
                      {"peak_servo_torque_nm", r.peak_servo_torque_nm},
                      {"ball_distance_m", r.ball_distance_m},
                      {"sim_time_s", r.sim_time_s},
                      {"wall_time_s", r.wall_time_s},
                      {"rtf", r.rtf},
                      {"state_hash", hash_hex(r.state_hash)},
                      {"ticks", r.ticks},
                      {"status", to_string(r.status)}};
  if (r.time_to_goal_s) j["time_to_goal_s"] = *r.time_to_goal_s;
  if (r.fell) j["fall_time_s"] = r.fall_time_s;
  if (!r.failure_reason.empty()) j["failure_reason"] = r.failure_reason;
  if (r.impact.body_contact_s) {
    j["impact"] = {{"body_contact_s", *r.impact.body_contact_s},
                   {"peak_accel_mps2", r.impact.peak_accel_mps2},
                   {"peak_servo_torque_nm", r.impact.peak_servo_torque_nm},
                   {"peak_servo_id", r.impact.peak_servo_index + 1},
                   {"peak_joint_torque_nm", r.impact.peak_joint_torque_nm}};
  }
  return j;
}

}  // namespace stride::sim
