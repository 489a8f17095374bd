// The identification routine in the simulator (identification_run.hpp): the firmware's control
// loop in lockstep with a SimWorld, the operator's console commands issued as motion requests
// at the moments the routine's description gives, the flight recorder on the loop.
#include "stride/sim_hal/identification_run.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <system_error>

#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/motion_manager.hpp"
#include "stride/firmware/motion_request.hpp"
#include "stride/firmware/recorder/flight_recorder.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {

const std::vector<std::string>& identification_parts() {
  static const std::vector<std::string> parts = {
      "stand", "identify_arms", "identify_stand", "identify_shift", "identify_steps", "walk"};
  return parts;
}

namespace {

/// Runs the loop tick by tick; stops early at a fall or a world failure.
class Player {
 public:
  Player(fw::ControlLoop& loop, fw::Firmware& firmware, SimRobot& robot, double period_s,
         IdentificationSummary& out)
      : loop_(loop), firmware_(firmware), robot_(robot), period_s_(period_s), out_(out) {}

  bool stopped() const { return !out_.failure.empty() || out_.fell; }

  /// One tick; false once the run must stop.
  bool tick() {
    if (stopped()) return false;
    loop_.run_once();
    ++out_.ticks;
    if (robot_.world().status() != WorldStatus::kRunning) {
      out_.failure = "the simulation stopped: " + robot_.world().failure_reason();
    } else if (firmware_.controller().motion().state() == fw::MotionState::kFallen) {
      out_.fell = true;
    }
    return !stopped();
  }

  void wait(double seconds) {
    const auto n = static_cast<std::int64_t>(std::llround(seconds / period_s_));
    for (std::int64_t k = 0; k < n && tick(); ++k) {
    }
  }

  /// Requests script `name` and waits until it has played and the robot stands again.
  void play(const std::string& name, double timeout_s) {
    const fw::MotionManager& motion = firmware_.controller().motion();
    const auto refused = motion.refused_requests();
    firmware_.controller().request(fw::MotionRequest::play(name));
    const auto limit = static_cast<std::int64_t>(std::llround(timeout_s / period_s_));
    bool started = false;
    for (std::int64_t k = 0; k < limit && tick(); ++k) {
      const fw::MotionState state = motion.state();
      started = started || state == fw::MotionState::kScript;
      if (started && state == fw::MotionState::kStand) return;
      if (motion.refused_requests() != refused) break;
    }
    if (!stopped())
      out_.failure = started ? "script " + name + " did not end within " +
                                   std::to_string(static_cast<int>(timeout_s)) + " s"
                             : "script " + name + " did not start (refused by the firmware)";
  }

  void request(const fw::MotionRequest& r) { firmware_.controller().request(r); }
  double now_s() const { return static_cast<double>(out_.ticks) * period_s_; }

 private:
  fw::ControlLoop& loop_;
  fw::Firmware& firmware_;
  SimRobot& robot_;
  double period_s_;
  IdentificationSummary& out_;
};

/// The run's parts are known, its durations in [0, 3600] s, its walk command in [-1, 1].
Status check_run(const IdentificationRun& run) {
  const auto& known = identification_parts();
  for (const std::string& part : run.parts)
    if (std::find(known.begin(), known.end(), part) == known.end())
      return Status::error(
          "unknown part '" + part +
          "' (stand, identify_arms, identify_stand, identify_shift, identify_steps, walk)");
  for (double s : {run.stand_s, run.pause_s, run.walk_in_place_s, run.walk_s, run.stop_s})
    if (!(s >= 0.0 && s <= 3600.0)) return Status::error("part durations must be in [0, 3600] s");
  if (!(run.walk_vx >= -1.0 && run.walk_vx <= 1.0))
    return Status::error("walk command must be in [-1, 1]");
  return Status::ok();
}

/// The flight recorder writing to `path`, its header naming the firmware's files and the sim HAL.
Status open_recorder(const IdentificationRun& run, fw::Firmware& firmware,
                     const std::filesystem::path& path, std::unique_ptr<fw::FlightRecorder>& out) {
  fw::flight_log::HeaderInputs header;
  header.params = &firmware.params();
  header.servos = &firmware.servos();
  header.servo_table_file = run.firmware.servo_table;
  header.robot = &firmware.robot();
  header.robot_description_file = run.firmware.robot_description.empty()
                                      ? fw::RobotDescription::default_path()
                                      : run.firmware.robot_description;
  header.params_file = run.firmware.params_file.value_or(std::filesystem::path());
  header.period_ns = firmware.period_ns();
  header.hal = "sim";
  fw::RecorderOptions recorder_options;
  recorder_options.path = path;
  // Large enough for the whole routine: a simulation running faster than the writer never
  // drops a tick, so the log is the same on every host.
  recorder_options.buffer_bytes = 128U << 20;
  return fw::FlightRecorder::open(recorder_options, header, firmware.controller(), out);
}

/// One part of the routine, then the pause after it.
void play_part(Player& player, const IdentificationRun& run, const std::string& part) {
  if (part == "stand") {
    player.wait(run.stand_s);
  } else if (part == "walk") {
    player.request(fw::MotionRequest::walk(0.0, 0.0, 0.0));
    player.wait(run.walk_in_place_s);
    player.request(fw::MotionRequest::stand());
    player.wait(run.stop_s);
    player.request(fw::MotionRequest::walk(run.walk_vx, 0.0, 0.0));
    player.wait(run.walk_s);
    player.request(fw::MotionRequest::stand());
    player.wait(run.stop_s);
  } else {
    player.play(part, run.script_timeout_s);
  }
  player.wait(run.pause_s);
}

}  // namespace

Status record_identification(const IdentificationRun& run, WorldOptions world,
                             const std::filesystem::path& log, IdentificationSummary& out) {
  out = {};
  if (Status s = check_run(run); !s) return s;

  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = fw::Firmware::create(run.firmware, firmware); !s) return s;
  world.control_period_ns = firmware->period_ns();
  world.ball.present = false;  // the routine needs no ball; a replay could not place one
  std::unique_ptr<SimWorld> sim_world;
  if (Status s = SimWorld::create(world, sim_world); !s) return s;
  SimRobot robot(std::move(sim_world));

  std::filesystem::path part_file = log;
  part_file += ".part";
  std::unique_ptr<fw::FlightRecorder> recorder;
  if (Status s = open_recorder(run, *firmware, part_file, recorder); !s) return s;

  fw::ControlLoop loop(robot, firmware->controller(), firmware->params());
  loop.set_recorder(recorder.get());
  const double period_s = static_cast<double>(firmware->period_ns()) * 1e-9;
  out.period_s = period_s;
  Player player(loop, *firmware, robot, period_s, out);
  for (const std::string& part : run.parts) {
    if (player.stopped()) break;
    out.part_start_s.emplace_back(part, player.now_s());
    play_part(player, run, part);
  }
  out.accel_bias_mps2 = robot.world().episode_accel_bias();
  out.gyro_bias_rad_s = robot.world().episode_gyro_bias();
  const fw::RecorderTotals totals = recorder->close();
  out.ticks_dropped = static_cast<std::int64_t>(totals.ticks_dropped);
  std::error_code error;
  if (!totals.write_error.empty()) {
    std::filesystem::remove(part_file, error);
    return Status::error(log.string() + ": " + totals.write_error);
  }
  std::filesystem::rename(part_file, log, error);
  if (error) {
    std::filesystem::remove(part_file, error);
    return Status::error(log.string() + ": cannot write the log");
  }
  return Status::ok();
}

}  // namespace stride::sim
