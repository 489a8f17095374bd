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

Status run_kick_episode(const WorldOptions& world_options, const KickEpisodeOptions& options,
                        EpisodeResult& out, std::unique_ptr<SimRobot>* robot_out) {
  ResetSpec spec = ResetSpec::standing();
  spec.ball_position = options.ball_position;
  std::unique_ptr<SimRobot> robot;
  if (Status s = make_robot(world_options, spec, robot); !s) return s;
  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = make_firmware(options.firmware, robot->period_ns(), firmware); !s) return s;
  fw::Controller& controller = firmware->controller();
  if (controller.motion().state() != fw::MotionState::kStand) {
    return Status::error("firmware: not standing at the start");
  }
  if (options.script.empty() || options.script.size() >= 32 ||
      firmware->params().list("script." + options.script + ".frame").empty()) {
    return Status::error("unknown kick script '" + options.script + "'");
  }
  const double period_s = static_cast<double>(robot->period_ns()) * 1e-9;
  const auto kick_tick = static_cast<hal::Tick>(std::llround(options.kick_at_s / period_s));
  bool requested = false;
  const StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    if (!requested && tick >= kick_tick) {
      controller.request(fw::MotionRequest::play(options.script));
      requested = true;
    }
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
  const double period_s = static_cast<double>(robot->period_ns()) * 1e-9;
  fw::MotionState previous = fw::MotionState::kStand;
  const StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    hal::CommandFrame commands = controller.step(sensors, tick);
    const fw::MotionState state = controller.motion().state();
    if (state == fw::MotionState::kGetUp && previous != fw::MotionState::kGetUp) {
      ++result.get_up_attempts;
      if (result.get_up_script.empty()) {
        result.get_up_script = std::string(controller.motion().active_script());
      }
    }
    if (state == fw::MotionState::kStand && previous == fw::MotionState::kGetUp) {
      result.stand_again_s = static_cast<double>(tick) * period_s;
    }
    previous = state;
    return commands;
  };
  EpisodeOptions episode = options.episode;
  episode.duration_s = options.duration_s;
  episode.stop_on_fall = false;
  result.episode = run_episode(*robot, step, episode);
  const GroundTruth g = robot->world().ground_truth();
  result.final_upright = g.torso.linear()(2, 2);
  result.got_up = result.episode.status == WorldStatus::kRunning &&
                  result.final_upright > std::cos(25.0 * 3.14159265358979 / 180.0) &&
                  g.torso.translation().z() > 0.45 &&
                  controller.motion().state() == fw::MotionState::kStand;
  out = std::move(result);
  return {};
}

}  // namespace stride::sim
