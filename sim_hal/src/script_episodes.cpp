// Script episodes: kick and push/get-up with the firmware against the simulated robot.
#include "stride/sim_hal/script_episodes.hpp"

#include <memory>

#include "stride/firmware/motion_request.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {

namespace {

Status make_robot(const WorldOptions& world_options, const ResetSpec& spec,
                  std::unique_ptr<SimRobot>& out) {
  std::unique_ptr<SimWorld> world;
  if (Status s = SimWorld::create(world_options, world); !s) return s;
  if (Status s = world->reset(spec); !s) return s;
  out = std::make_unique<SimRobot>(std::move(world));
  return {};
}

Status make_firmware(const fw::FirmwareOptions& options, std::int64_t period_ns,
                     std::unique_ptr<fw::Firmware>& out) {
  if (Status s = fw::Firmware::create(options, out); !s) return s;
  if (out->period_ns() != period_ns) {
    return Status::error("loop.rate_hz: the firmware period (" + std::to_string(out->period_ns()) +
                         " ns) differs from the simulator's control period (" +
                         std::to_string(period_ns) + " ns)");
  }
  return {};
}

}  // namespace

ResetSpec kick_reset_spec(const Eigen::Vector3d& ball_position) {
  ResetSpec spec = ResetSpec::standing();
  spec.ball_position = ball_position;
  return spec;
}

Eigen::Vector3d kick_ball_position(const std::string& script) {
  Eigen::Vector3d ball = KickEpisodeOptions{}.ball_position;  // before the right foot
  if (script == "kick_left") ball.y() = -ball.y();
  return ball;
}

Status check_kick_script(const fw::Firmware& firmware, const std::string& script) {
  if (script.empty() || script.size() >= 32 ||
      firmware.params().list("script." + script + ".frame").empty()) {
    return Status::error("unknown kick script '" + script + "'");
  }
  return {};
}

KickRequest::KickRequest(std::string script, double kick_at_s, double period_s)
    : script_(std::move(script)),
      kick_tick_(static_cast<hal::Tick>(std::llround(kick_at_s / period_s))) {}

void KickRequest::before_step(hal::Tick tick, fw::Controller& controller) {
  if (!requested_ && tick >= kick_tick_) {
    controller.request(fw::MotionRequest::play(script_));
    requested_ = true;
  }
}

Status run_kick_episode(const WorldOptions& world_options, const KickEpisodeOptions& options,
                        EpisodeResult& out, std::unique_ptr<SimRobot>* robot_out) {
  std::unique_ptr<SimRobot> robot;
  if (Status s = make_robot(world_options, kick_reset_spec(options.ball_position), robot); !s)
    return s;
  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = make_firmware(options.firmware, robot->period_ns(), firmware); !s) return s;
  fw::Controller& controller = firmware->controller();
  if (controller.motion().state() != fw::MotionState::kStand) {
    return Status::error("firmware: not standing at the start");
  }
  if (Status s = check_kick_script(*firmware, options.script); !s) return s;
  KickRequest kick(options.script, options.kick_at_s,
                   static_cast<double>(robot->period_ns()) * 1e-9);
  const StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    kick.before_step(tick, controller);
    return controller.step(sensors, tick);
  };
  EpisodeOptions episode = options.episode;
  episode.duration_s = options.duration_s;
  episode.stop_on_fall = true;
  out = run_episode(*robot, step, episode);
  if (controller.motion().refused_requests() > 0) {
    return Status::error("kick script '" + options.script + "' was refused (not loaded?)");
  }
  if (robot_out != nullptr) *robot_out = std::move(robot);
  return {};
}

Status run_push_episode(const WorldOptions& world_options, const PushEpisodeOptions& options,
                        PushEpisodeResult& out) {
  ResetSpec spec = ResetSpec::standing();
  // The scripted impulse: the ball flies at the chest (torso origin height + 4 cm).
  const double direction = options.from_behind ? 1.0 : -1.0;
  spec.ball_position = {-direction * 0.45, 0.0, 0.62};
  spec.ball_velocity = {direction * options.push_speed, 0.0, 1.0};
  std::unique_ptr<SimRobot> robot;
  if (Status s = make_robot(world_options, spec, robot); !s) return s;
  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = make_firmware(options.firmware, robot->period_ns(), firmware); !s) return s;
  fw::Controller& controller = firmware->controller();
  PushEpisodeResult result;
  GetUpWatch watch(static_cast<double>(robot->period_ns()) * 1e-9);
  const StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    hal::CommandFrame commands = controller.step(sensors, tick);
    watch.after_step(controller, tick);
    return commands;
  };
  EpisodeOptions episode = options.episode;
  episode.duration_s = options.duration_s;
  episode.stop_on_fall = false;
  result.episode = run_episode(*robot, step, episode);
  result.get_up_attempts = watch.attempts();
  result.get_up_script = watch.first_script();
  result.stand_again_s = watch.stand_again_s();
  result.final_upright = robot->world().ground_truth().torso.linear()(2, 2);
  result.got_up = stands_at_end(robot->world(), result.episode.status, controller);
  out = std::move(result);
  return {};
}

}  // namespace stride::sim
