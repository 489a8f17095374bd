// Episode runner: a controller (anything that turns a SensorFrame into a CommandFrame each
// tick) against a SimRobot for a fixed duration, with the metrics of the `stride sim --json`
// contract (docs/command-line.md). Used by `stride sim`, the tests and the optimiser's tasks.
//
// Metrics (sensor-based ones start after EpisodeOptions::metrics_start_s, as in the seed's
// evaluator, to skip the settling transient):
//   fell             torso tilted more than 60 deg from upright or its origin below 0.25 m
//   distance_m       forward (x) displacement of the torso from the start [m]
//   lateral_m        sideways (y, left) displacement of the torso from the start [m]
//   turned_rad       the torso's yaw change, unwrapped tick by tick (anticlockwise) [rad]
//   time_to_goal_s   first time the torso was goal_distance_m ahead of its start (null if never)
//   max_accel        max over samples of |a| of the IMU accelerometer [m/s^2] (seed walk Obj2)
//   max_fps          max over samples of sqrt(ax^2 + ay^2), the field-plane sway (seed kick Obj1)
//   peak_servo_torque_nm  the largest |motor torque| of any servo over the physics steps, the
//                    load the gear train carries (SimWorld::last_period_peaks; the get-up
//                    task's Obj2) [N m]
//   ball_distance_m  distance the ball moved in the field plane [m]
//   sim_time_s, wall_time_s, rtf (= sim / wall), state_hash (SimWorld::state_hash, hex)
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {

/// The controller side of an episode (the firmware Controller or a test source).
using StepFunction = std::function<hal::CommandFrame(const hal::SensorFrame&, hal::Tick)>;

/// Holds a fixed pose with one P gain (the stand pose by default): a minimal controller.
StepFunction hold_pose_controller(const std::array<double, hal::kServoCount>& pose,
                                  double p_gain = 76.0);

/// Link poses at one moment, for pictures; the replays also keep the joint angles and the feet's
/// contact forces (EpisodeCapturer fills them; empty or zero elsewhere).
struct PoseSnapshot {
  double time_s = 0.0;
  std::vector<Eigen::Isometry3d> links;
  Eigen::Vector3d ball = Eigen::Vector3d::Zero();
  std::vector<double> joint_angles;                            ///< model().joints() order [rad]
  Eigen::Vector3d left_foot_force = Eigen::Vector3d::Zero();   ///< contact force, world [N]
  Eigen::Vector3d right_foot_force = Eigen::Vector3d::Zero();  ///< contact force, world [N]
};

class TrajectoryRecorder;

struct EpisodeOptions {
  double duration_s = 10.0;
  double goal_distance_m = 2.5;
  double metrics_start_s = 0.25;
  bool stop_on_fall = true;
  bool stop_at_goal = false;               ///< end once goal_distance_m is covered
  TrajectoryRecorder* recorder = nullptr;  ///< optional, records every tick
  /// Optional observer called every tick after the commands are written (replays, pictures);
  /// it only reads the world, so the episode is the same with or without it.
  std::function<void(hal::Tick, const SimWorld&, const hal::SensorFrame&)> on_tick;
  std::vector<double> snapshot_times_s;  ///< moments to capture link poses at
  /// Optional: asked after every tick; true ends the episode there (a task that has measured
  /// what it needs). Unset: the episode runs to its other ends.
  std::function<bool()> stop_when;
  /// Measure the landing of a fall (EpisodeResult::impact): the first moment a link other than
  /// the feet touches the ground, and the peaks of the torso's acceleration and of the servo
  /// torques over impact_window_s from then (per physics step, SimWorld::last_period_peaks).
  /// It reads the ground truth every tick until that contact; the episode is the same.
  bool impact_metrics = false;
  double impact_window_s = 0.8;
  /// Optional: true closes the impact window early (`stride sim`: once a get-up has started,
  /// whose own pushes are not the landing). Asked every tick inside the window.
  std::function<bool()> impact_over;
};

/// The landing of a fall (EpisodeOptions::impact_metrics).
struct ImpactMeasure {
  std::optional<double> body_contact_s;  ///< first contact of a link other than the feet [s]
  double peak_accel_mps2 = 0.0;          ///< torso acceleration magnitude, peak [m/s^2]
  double peak_servo_torque_nm = 0.0;     ///< largest |motor torque| of a servo [N m]
  int peak_servo_index = -1;             ///< the servo of that torque (Dynamixel ID - 1)
  double peak_joint_torque_nm = 0.0;     ///< largest |torque| on a servo's joint [N m]
};

struct EpisodeResult {
  bool fell = false;
  double fall_time_s = -1.0;
  double distance_m = 0.0;  ///< the torso's displacement along the world's x axis [m]
  double lateral_m = 0.0;   ///< and along its y axis (left) [m]
  double turned_rad = 0.0;  ///< the torso's yaw change, unwrapped (anticlockwise) [rad]
  std::optional<double> time_to_goal_s;
  double max_accel = 0.0;
  double max_fps = 0.0;
  double peak_servo_torque_nm = 0.0;
  double ball_distance_m = 0.0;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  double rtf = 0.0;
  std::uint64_t state_hash = 0;
  std::int64_t ticks = 0;
  WorldStatus status = WorldStatus::kRunning;
  std::string failure_reason;  ///< empty unless the world failed
  std::vector<PoseSnapshot> snapshots;
  ImpactMeasure impact;  ///< filled with EpisodeOptions::impact_metrics
};

/// Runs `controller` against `robot` from its current state (reset it first) for
/// options.duration_s, or until a fall (stop_on_fall) or a world failure.
EpisodeResult run_episode(SimRobot& robot, const StepFunction& controller,
                          const EpisodeOptions& options);

/// The `stride sim --json` object. state_hash is a 16-digit hex string.
nlohmann::json to_json(const EpisodeResult& result);

/// "%016llx" of a hash.
std::string hash_hex(std::uint64_t hash);

}  // namespace stride::sim
