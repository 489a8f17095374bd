// RobotTask: walk and kick episodes of the firmware against the simulated robot.
#include "stride/optimiser/tasks/robot_task.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

#include "stride/firmware/firmware.hpp"
#include "stride/firmware/motion_request.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::opt {

namespace {

constexpr double kFallPenalty = 1000.0;

sim::WorldOptions world_for_trial(const TaskConfig& config, int world) {
  sim::WorldOptions w;
  const int trial = world % config.trials;
  w.engine =
      config.engines[static_cast<std::size_t>(world / config.trials) % config.engines.size()];
  w.seed = config.trial_seed + static_cast<std::uint64_t>(trial);
  if (config.trials > 1) {
    if (config.randomisation.imu_noise) w.imu.set_noise(true);
    w.randomise.friction_range = config.randomisation.friction_range;
    w.randomise.mass_range = config.randomisation.mass_range;
    w.randomise.strength_range = config.randomisation.strength_range;
  }
  if (config.task != "kick") w.ball.present = false;
  if (!config.urdf.empty()) w.urdf = config.urdf;
  w.servo.law = config.servo_law;
  w.use_cm730_imu(config.imu_cm730);
  w.physics_step_ns = config.physics_step_us * 1000;
  sim::parse_contact_kind(config.contact, w.contact);  // checked when the config was read
  if (config.world_file) config.world_file->apply_calibration(w);
  return w;
}

}  // namespace

RobotTask::RobotTask(TaskConfig config) : config_(std::move(config)) {
  for (const auto& g : config_.genes) shape_.reals.push_back({g.min, g.max});
  shape_.objectives = 2;
  shape_.constraints = config_.task == "kick" ? 2 : config_.task == "walk" ? 3 : 4;
  auto files = std::make_shared<fw::FirmwareFiles>();
  if (fw::FirmwareFiles::load({}, *files)) firmware_files_ = std::move(files);
  auto model = std::make_shared<sim::RobotModel>();
  const std::filesystem::path urdf = config_.urdf.empty() ? sim::WorldOptions{}.urdf : config_.urdf;
  if (sim::RobotModel::load_file(urdf, *model)) robot_model_ = std::move(model);
}

Genome RobotTask::start_genome() const {
  Genome g;
  for (const auto& gene : config_.genes) g.reals.push_back(gene.start);
  return g;
}

nlohmann::json RobotTask::parameter_file(const Genome& genome) const {
  nlohmann::json doc = nlohmann::json::object();
  for (std::size_t i = 0; i < config_.genes.size() && i < genome.reals.size(); ++i)
    doc[config_.genes[i].parameter] = genome.reals[i];
  return doc;
}

std::optional<FrontReference> RobotTask::reference() const {
  if (config_.hv_ideal.empty()) return std::nullopt;
  FrontReference r;
  r.ideal = config_.hv_ideal;
  r.nadir = config_.hv_nadir;
  return r;
}

sim::WorldOptions RobotTask::world_options(int world) const {
  return world_for_trial(config_, world);
}

Status RobotTask::run_trial(const Genome& genome, int world, EpisodeScore& out,
                            sim::EpisodeCapturer* capture) const {
  if (Status s = run_world(genome, world_for_trial(config_, world), out, capture); !s) return s;
  if (!out.world_failure.empty()) return Status::error("simulation: " + out.world_failure);
  return {};
}

Status RobotTask::run_world(const Genome& genome, sim::WorldOptions options, EpisodeScore& out,
                            sim::EpisodeCapturer* capture) const {
  if (genome.reals.size() != config_.genes.size())
    return Status::error("genome has " + std::to_string(genome.reals.size()) + " genes, the task " +
                         std::to_string(config_.genes.size()));
  const bool walk = config_.task == "walk";
  const bool omni = config_.task == "walk-omni";
  using Clock = std::chrono::steady_clock;
  const auto setup_start = Clock::now();
  if (options.urdf == (config_.urdf.empty() ? sim::WorldOptions{}.urdf : config_.urdf))
    options.model = robot_model_;
  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = firmware_files_ ? fw::Firmware::create({}, *firmware_files_, firmware)
                                 : fw::Firmware::create({}, firmware);
      !s)
    return s;
  options.control_period_ns = firmware->period_ns();
  sim::ResetSpec spec = sim::ResetSpec::standing();
  spec.ball_position = {0.25, -0.06, std::nan("")};  // in front of the right (kicking) foot
  std::unique_ptr<sim::SimWorld> world;
  if (Status s = sim::SimWorld::create(options, world); !s) return s;
  if (Status s = world->reset(spec); !s) return s;
  sim::SimRobot robot(std::move(world));

  // The config's base parameters first (set now: the firmware's start-up values), then the
  // genome: one validated batch, staged, applied atomically at tick 0.
  fw::ParameterStore& params = firmware->params();
  if (!config_.base_params.empty()) {
    if (Status s = params.set_now(config_.base_params); !s)
      return Status::error("params: " + s.message());
  }
  std::vector<fw::ParamWrite> batch;
  for (std::size_t i = 0; i < config_.genes.size(); ++i)
    batch.push_back({config_.genes[i].parameter, genome.reals[i]});
  if (Status s = params.stage(batch); !s) return s;

  fw::Controller& controller = firmware->controller();
  const double period_s = static_cast<double>(robot.period_ns()) * 1e-9;
  const auto kick_tick = static_cast<hal::Tick>(std::llround(config_.kick_at_s / period_s));
  bool requested = false;
  double yaw_integral = 0.0;
  OmniEpisode omni_episode(config_.omni, period_s);
  std::array<double, 3> omni_requested{0.0, 0.0, 0.0};
  const sim::GroundTruth start_truth = robot.world().ground_truth();
  YawTracker yaw_tracker;
  yaw_tracker.reset(torso_yaw(start_truth.torso));
  double controller_s = 0.0;
  const double setup_s = std::chrono::duration<double>(Clock::now() - setup_start).count();
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    params.apply_staged();
    if (omni) {
      omni_episode.observe(tick, robot.world());
      const auto c = omni_episode.command(tick);
      if (!requested || c != omni_requested) {
        controller.request(fw::MotionRequest::walk(c[0], c[1], c[2]));
        omni_requested = c;
        requested = true;
      }
    } else if (walk) {
      yaw_tracker.update(torso_yaw(robot.world().torso_pose()));
    }
    if (!requested) {
      if (walk) {
        controller.request(fw::MotionRequest::walk(config_.walk_vx, 0.0, 0.0));
        requested = true;
      } else if (tick >= kick_tick) {
        controller.request(fw::MotionRequest::play(config_.script));
        requested = true;
      }
    }
    if (static_cast<double>(tick) * period_s > 0.25)
      yaw_integral += sensors.cm730.gyro_rad_s[2] * period_s;
    const auto before = Clock::now();
    hal::CommandFrame commands = controller.step(sensors, tick);
    controller_s += std::chrono::duration<double>(Clock::now() - before).count();
    return commands;
  };
  sim::EpisodeOptions episode;
  episode.duration_s = omni ? omni_episode.duration_s() : config_.duration_s;
  episode.goal_distance_m = omni ? 1e9 : config_.goal_distance_m;
  episode.stop_on_fall = true;
  episode.stop_at_goal = walk;
  if (capture != nullptr) episode.on_tick = capture->observer();
  sim::EpisodeResult r = sim::run_episode(robot, step, episode);
  if (params.has_staged()) return Status::error("the genome was never applied");
  if (controller.motion().refused_requests() > 0)
    return Status::error(walk || omni ? "walk request refused"
                                      : "kick script '" + config_.script + "' refused");
  // A failed world ends the episode: scored below as a fall at that moment.
  const bool failed = r.status != sim::WorldStatus::kRunning;
  if (failed && !r.fell) {
    r.fell = true;
    r.fall_time_s = r.sim_time_s;
    r.time_to_goal_s.reset();
  }

  out = {};
  if (failed)
    out.world_failure =
        r.failure_reason.empty() ? std::string(sim::to_string(r.status)) : r.failure_reason;
  out.fell = r.fell;
  out.distance_m = r.distance_m;
  out.time_to_goal_s = r.time_to_goal_s ? *r.time_to_goal_s : -1.0;
  out.max_accel = r.max_accel;
  out.max_fps = r.max_fps;
  out.ball_distance_m = r.ball_distance_m;
  out.sim_time_s = r.sim_time_s;
  out.wall_time_s = r.wall_time_s;
  out.setup_s = setup_s;
  out.controller_s = controller_s;
  if (walk) {
    // Straightness in the start's walking frame, at the goal or the episode's end.
    const PlanarPose a = walking_frame(start_truth, torso_yaw(start_truth.torso));
    const PlanarPose b = walking_frame(robot.world().ground_truth(), yaw_tracker.yaw());
    const Translation t = measure_translation(a, b, 1.0, 0.0);
    out.lateral_drift_m = t.off_axis_m;
    out.heading_change_rad = t.heading_change_rad;
    const double heading_limit = config_.max_heading_change_deg * std::numbers::pi / 180.0;
    const double missing = std::max(0.0, config_.goal_distance_m - r.distance_m);
    const double time = r.time_to_goal_s ? *r.time_to_goal_s : config_.duration_s + 10.0 * missing;
    out.objectives = {time, r.max_accel};
    const double lost = r.fell ? std::max(0.0, config_.duration_s - r.fall_time_s) : 0.0;
    out.constraints = {
        r.fell ? -(1.0 + lost / config_.duration_s) : 0.0,
        config_.max_drift_ratio > 0.0
            ? limit_violation(t.drift_ratio() / config_.max_drift_ratio, 1.0)
            : limit_violation(t.drift_ratio(), config_.max_drift_ratio),
        heading_limit > 0.0 ? limit_violation(t.heading_change_rad / heading_limit, 1.0) : 0.0};
  } else if (omni) {
    out.omni = omni_episode.segments();
    out.objectives = {omni_speed_objective(out.omni), r.max_accel};
    const double length = omni_episode.duration_s();
    const double lost = r.fell ? std::max(0.0, length - r.fall_time_s) : 0.0;
    const auto c = omni_constraints(out.omni, config_);
    out.constraints = {r.fell ? -(1.0 + lost / length) : 0.0, c[0], c[1], c[2]};
  } else {
    const double d = std::clamp(r.ball_distance_m, 0.001, 10.0);
    double sway = r.max_fps;
    if (r.fell || sway <= 0.0 || sway > kFallPenalty) sway = kFallPenalty;
    out.objectives = {sway, r.fell ? kFallPenalty : 1.0 / d};
    const double yaw = std::abs(yaw_integral);
    out.constraints = {r.fell ? -10.0 : 0.0, yaw > config_.yaw_drift_limit_rad
                                                 ? -(yaw - config_.yaw_drift_limit_rad)
                                                 : 0.0};
  }
  return {};
}

EvaluationOutcome RobotTask::evaluate(const Genome& genome) const {
  EvaluationOutcome outcome;
  const int worlds = config_.world_count();
  for (int k = 0; k < worlds; ++k) {
    EpisodeScore score;
    if (Status s = run_trial(genome, k, score); !s)
      return EvaluationOutcome::failure("trial " + std::to_string(k) + ": " + s.message());
    if (k == 0) {
      outcome.objectives = score.objectives;
      outcome.constraints = score.constraints;
      continue;
    }
    for (std::size_t i = 0; i < score.objectives.size(); ++i)
      outcome.objectives[i] = config_.aggregate == Aggregate::kMean
                                  ? outcome.objectives[i] + score.objectives[i]
                                  : std::max(outcome.objectives[i], score.objectives[i]);
    for (std::size_t i = 0; i < score.constraints.size(); ++i)
      outcome.constraints[i] = config_.aggregate == Aggregate::kMean
                                   ? outcome.constraints[i] + score.constraints[i]
                                   : std::min(outcome.constraints[i], score.constraints[i]);
  }
  if (config_.aggregate == Aggregate::kMean && worlds > 1) {
    const double n = worlds;
    for (double& v : outcome.objectives) v /= n;
    for (double& v : outcome.constraints) v /= n;
  }
  return outcome;
}

}  // namespace stride::opt
