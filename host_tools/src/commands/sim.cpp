// `stride sim stand|walk|kick|getup`: one simulated episode of the firmware against the simulated
// world, with the metrics of docs/command-line.md (--json), a trajectory recording, pose pictures
// and a replay page (--html, the replay of report.html for one episode). getup starts lying still
// and times the firmware's get-up; stand and walk can go on through a get-up after a fall
// (--after-fall).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "stride/core/atomic_file.hpp"
#include "stride/core/cli_args.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/firmware/motion_request.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/optimiser/report/report_page.hpp"
#include "stride/optimiser/report/run_plots.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/episode_capture.hpp"
#include "stride/sim_hal/get_up_watch.hpp"
#include "stride/sim_hal/pose_svg.hpp"
#include "stride/sim_hal/script_episodes.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/trajectory_recorder.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace {

using stride::Status;
namespace sim = stride::sim;
namespace hal = stride::hal;

const stride::tools::CommandErrors errors("sim");

Status parse_times(const std::string& text, std::vector<double>& out) {
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      const double t = std::stod(item, &used);
      if (used != item.size() || !(t >= 0.0)) throw std::invalid_argument(item);
      out.push_back(t);
    } catch (const std::exception&) {
      return Status::error("--snapshot-times: bad time '" + item + "' (expected e.g. 0,1,2.5)");
    }
  }
  return Status::ok();
}

std::string fixed(double v, const char* unit) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3f %s", v, unit);
  return text;
}

// A get-up followed through the episode (getup, or stand/walk with --after-fall getup).
struct GetUpOutcome {
  bool watched = false;
  std::string lying;                 ///< getup: "front" or "back"; "" after a fall
  std::optional<double> stood_up_s;  ///< from lying still (getup) or from the fall [s]
  int attempts = 0;
  std::string first_script;
  /// walk --after-fall getup: how far the torso went (horizontally) from the moment it stood
  /// up, walking its command again, to the episode's end [m]; unset if it did not stand.
  std::optional<double> walked_after_m;
};

// "stood up after 9.78 s (2 get-up attempts)" or "stayed down (3 get-up attempts)".
std::string get_up_text(const GetUpOutcome& g) {
  char text[96];
  if (g.stood_up_s)
    std::snprintf(text, sizeof text, "stood up after %.2f s (%d get-up attempt%s)", *g.stood_up_s,
                  g.attempts, g.attempts == 1 ? "" : "s");
  else
    std::snprintf(text, sizeof text, "stayed down (%d get-up attempt%s)", g.attempts,
                  g.attempts == 1 ? "" : "s");
  return text;
}

// The episode's outcome in a few words: "standing", "fell at 3.21 s", "stood up after ...",
// "fell at 3.21 s, stood up after ...".
std::string outcome_text(const sim::EpisodeResult& result, const GetUpOutcome& get_up) {
  if (get_up.watched && !get_up.lying.empty()) return get_up_text(get_up);
  if (!result.fell) return "standing";
  std::string text = "fell at " + fixed(result.fall_time_s, "s");
  if (get_up.watched) text += ", " + get_up_text(get_up);
  return text;
}

// The --html page: the episode's settings and results, accelerometer, poses and replay.
Status write_html(const stride::core::CliArgs& args, const std::string& params_name,
                  const std::string& motion, const std::string& duration_text,
                  const sim::WorldOptions& world, sim::SimRobot& robot,
                  const sim::EpisodeResult& result, const GetUpOutcome& get_up,
                  const sim::EpisodeCapture& capture) {
  namespace report = stride::opt::report;
  report::ReplayIndividual episode;
  episode.name = params_name;
  episode.colour = report::individual_colour(0);
  episode.capture = capture;
  const double end = capture.frames.empty() ? 0.0 : capture.frames.back().time_s;
  char note[128];
  std::snprintf(note, sizeof note, "%s: %s after %.2f s, %.2f m forward", motion.c_str(),
                result.fell ? "fell" : "standing", end, result.distance_m);
  episode.note = get_up.watched ? motion + ": " + outcome_text(result, get_up) : note;
  report::ReplayScene scene;
  scene.ground = sim::contact_kind_name(robot.world().ground());  // the episode's (drawn) ground
  scene.grass_m = robot.world().ground().grass_thickness_m;
  scene.ball_radius_m = world.ball.present ? world.ball.radius_m : 0.0;
  if (motion == "walk") scene.goal_m = sim::EpisodeOptions{}.goal_distance_m;  // time_to_goal_s
  const std::vector<double> times =
      motion == "kick"
          ? report::strip_times(std::max(1.0, report::first_ball_motion_s({episode}, 2.0) - 1.5),
                                0.25, 9, end)
      : motion == "walk" ? report::strip_times(std::min(4.0, end / 3), 0.25, 9, end)
                         : report::strip_times(0.0, end / 8, 9, end);
  const std::vector<std::pair<std::string, std::string>> facts = {
      {"motion", motion + (motion == "kick"    ? " (" + args.get("script") + ")"
                           : motion == "getup" ? " (lying on the " + get_up.lying + ")"
                           : get_up.watched    ? " (after a fall: get up)"
                                               : "")},
      {"parameters", episode.name},
      {"walk command", motion == "walk" ? "vx " + args.get("vx") + ", vy " + args.get("vy") +
                                              ", vth " + args.get("vth")
                                        : "-"},
      {"seed, noise", args.get("seed") + ", " + args.get("noise")},
      {"duration", duration_text + " s"},
      {"result", outcome_text(result, get_up)},
      {"distance (torso, x)", fixed(result.distance_m, "m")},
      {"max |a|", fixed(result.max_accel, "m/s^2")},
      {"max field-plane sway", fixed(result.max_fps, "m/s^2")},
      {"ball moved", fixed(result.ball_distance_m, "m")},
      {"state hash", sim::hash_hex(result.state_hash)}};
  std::vector<std::string> warnings;
  Status written =
      report::write_episode_html(args.get("html"), "Stride sim " + motion, facts,
                                 robot.world().model(), episode, scene, times, &warnings);
  for (const std::string& w : warnings) errors.warning(w + " (see " + args.get("html") + ")");
  return written;
}

void declare_options(stride::core::CliArgs& args) {
  args.option("help", "show this help", false);
  args.option("params",
              "parameter file (JSON) loaded into the controller (default: none; with --world "
              "seed the seed world's walk, config/seed-walk.json)",
              true);
  args.option("vx", "walk forward command, normalised [-1, 1]", true, "0");
  args.option("vy", "walk sideways command, normalised [-1, 1]", true, "0");
  args.option("vth", "walk turning command, normalised [-1, 1]", true, "0");
  args.option("script", "kick: the script to play", true, "kick_right");
  args.option("duration",
              "episode length [s] (default 10; getup 20, the rules' time to get up; with "
              "--after-fall getup 30)",
              true);
  args.option("lying",
              "getup: the side the robot lies still on at the start, front (face down) or back",
              true);
  args.option("after-fall",
              "stand/walk: 'getup' goes on after a fall through the firmware's get-up (without it "
              "the episode ends at the fall)",
              true);
  args.option("metrics-from",
              "count the sensor metrics (max |a|, sway) from this time on [s] (the seed's 0.25; "
              "kick: 1 measures the kick alone, not the settling after the reset)",
              true, "0.25");
  args.option("record", "write the trajectory (JSON lines, see trajectory_recorder.hpp)", true);
  args.option("snapshot", "write an SVG picture of the robot's pose at --snapshot-times", true);
  args.option("snapshot-times", "comma-separated times [s] for --snapshot", true, "0,1,2,5,10");
  args.option("html", "write a self-contained replay page (accelerometer, poses, animation)", true);
  args.option("json", "print the result as one JSON object", false);
  sim::declare_world_options(args);
}

void print_help(const stride::core::CliArgs& args) {
  std::printf(
      "usage: stride sim stand|walk|kick [options] [--after-fall getup (stand, walk)]\n"
      "       stride sim getup --lying front|back [options]\n"
      "       stride sim servo --help   (one servo on a bench)\n\n"
      "getup places the robot lying still on its front or back (joints in the Stand pose)\n"
      "and runs the firmware: its motion manager sees the fall, waits until the robot lies\n"
      "still (motion.fallen_still_time) and plays get_up_front or get_up_back, retrying while\n"
      "the robot stays down. --json then reports stood_up_s: seconds from lying still to\n"
      "standing, or null if it did not stand within --duration (20 s by default, the time\n"
      "the rules give a fallen robot). Standing: the motion manager is back in Stand after\n"
      "a get-up script, the trunk's z axis within 25 deg of vertical and the torso origin\n"
      "above 0.45 m, all held for 1 s; stood_up_s is the start of that second.\n"
      "With --after-fall getup a stand or walk episode does not end at a fall (fell,\n"
      "fall_time_s: trunk tilted past 60 deg or its origin below 0.25 m) but goes on\n"
      "through the get-up (30 s by default), and stood_up_s counts\n"
      "from the fall.\n"
      "Both also report get_up_attempts and get_up_script (the first get-up played).\n"
      "A walk that stood up walks its command again and reports walked_after_get_up_m:\n"
      "how far the torso went from the moment it stood up to the end (null if it did not).\n\n"
      "%s",
      args.help().c_str());
}

/// What the command line asks for, checked: the motion, its length and command, the world.
struct SimRequest {
  std::string motion;         ///< stand, walk, kick or getup
  bool getup = false;         ///< motion == "getup"
  std::string lying;          ///< getup: front or back
  bool watch_get_up = false;  ///< getup, or --after-fall getup
  std::string duration_text;  ///< --duration as given (or its default)
  double duration = 0.0, vx = 0.0, vy = 0.0, vth = 0.0, metrics_from = 0.25;
  std::vector<double> snapshot_times;
  sim::WorldOptions world;
  /// The parameter file loaded into the controller: --params, else with --world seed the seed
  /// world's walk (config/seed-walk.json), else none (the firmware's defaults).
  std::optional<std::filesystem::path> params_file;
};

/// Reads and checks the motion and every option but the firmware's; errors are bad input.
Status read_request(const stride::core::CliArgs& args, SimRequest& r) {
  if (args.positional().size() != 1)
    return Status::error("expected one motion: stand, walk, kick or getup");
  r.motion = args.positional()[0];
  const std::string& motion = r.motion;
  if (motion != "stand" && motion != "walk" && motion != "kick" && motion != "getup")
    return Status::error("unknown motion '" + motion + "' (expected stand, walk, kick or getup)");
  r.getup = motion == "getup";
  r.lying = args.get("lying");
  if (args.has("lying") && !r.getup)
    return Status::error("--lying: only with getup (stride sim getup --lying front|back), not " +
                         motion);
  if (r.getup && !args.has("lying"))
    return Status::error("--lying: getup needs a side, front or back");
  if (r.getup && r.lying != "front" && r.lying != "back")
    return Status::error("--lying: unknown side '" + r.lying + "' (expected front or back)");
  if (args.has("after-fall") && args.get("after-fall") != "getup")
    return Status::error("--after-fall: unknown value '" + args.get("after-fall") +
                         "' (expected getup)");
  if (args.has("after-fall") && motion != "stand" && motion != "walk")
    return Status::error("--after-fall: only with stand or walk, not " + motion +
                         (r.getup ? " (it starts lying and always gets up)" : ""));
  r.watch_get_up = r.getup || args.has("after-fall");
  // Default lengths: 10 s; lying, the 20 s the rules give a fallen robot; after a fall, 10 s
  // and those 20 s.
  const char* default_duration = r.getup ? "20" : r.watch_get_up ? "30" : "10";
  r.duration_text = args.has("duration") ? args.get("duration") : default_duration;
  r.duration = std::stod(default_duration);
  for (auto [name, out] : {std::pair{"duration", &r.duration},
                           {"vx", &r.vx},
                           {"vy", &r.vy},
                           {"vth", &r.vth},
                           {"metrics-from", &r.metrics_from}})
    if (Status s = args.get_double(name, *out); !s) return s;
  if (!(r.duration > 0.0) || r.duration > 3600.0)
    return Status::error("--duration: must be in (0, 3600] s, got " + args.get("duration"));
  if (args.has("metrics-from") && !(r.metrics_from >= 0.0 && r.metrics_from < r.duration))
    return Status::error("--metrics-from: must be in [0, " + r.duration_text + ") s, got " +
                         args.get("metrics-from"));
  if (Status s = parse_times(args.get("snapshot-times"), r.snapshot_times); !s) return s;
  // The pushes must fall within the episode (read_world_options takes them below).
  for (const std::string& text : args.get_all("push")) {
    sim::TorsoPush push;
    if (Status s = sim::parse_push(text, r.duration, push); !s) return s;
  }
  sim::WorldSpec spec;
  if (Status s = sim::read_world_spec(args, spec); !s) return s;
  r.world = spec.to_options();
  // --world seed is the thesis's world and its walk: the walk defaults of then, unless --params.
  if (args.has("params"))
    r.params_file = args.get("params");
  else if (spec.base == sim::WorldPreset::kSeed && !spec.file)
    r.params_file = stride::fw::data_dir() / "config" / "seed-walk.json";
  if (motion == "walk")
    for (double v : {r.vx, r.vy, r.vth})
      if (!(v >= -1.0 && v <= 1.0)) return Status::error("--vx/--vy/--vth: must be in [-1, 1]");
  return {};
}

/// stand, walk or getup: the firmware driving the simulated robot, a get-up followed tick by
/// tick when asked for, and the first tick the firmware predicted a fall.
Status run_controlled_episode(const SimRequest& r, stride::fw::Firmware& firmware,
                              sim::EpisodeOptions& episode, sim::EpisodeResult& result,
                              std::unique_ptr<sim::SimRobot>& robot_ptr, GetUpOutcome& get_up,
                              std::optional<double>& predicted_s) {
  const bool getup = r.getup, watch_get_up = r.watch_get_up;
  std::unique_ptr<sim::SimWorld> world;
  if (Status s = sim::SimWorld::create(r.world, world); !s) return s;
  // getup: lying still on the side asked for (the optimiser's get-up task starts there too).
  if (getup) {
    if (Status s = world->reset(sim::lying_reset_spec(r.lying == "front")); !s) return s;
  }
  robot_ptr = std::make_unique<sim::SimRobot>(std::move(world));
  sim::SimRobot& robot = *robot_ptr;

  stride::fw::Controller& controller = firmware.controller();
  if (r.motion == "walk") controller.request(stride::fw::MotionRequest::walk(r.vx, r.vy, r.vth));
  if (r.motion == "walk") {
    // The request is taken at the next step: a refusal means the walk engine is missing.
    stride::hal::SensorFrame probe;
    robot.read(probe);
    (void)controller.step(probe, 0);
    if (controller.motion().refused_requests() > 0)
      return Status::error("walk engine not available");
  }
  // A get-up is followed tick by tick (it only reads the world: the episode is the same).
  sim::StoodUpWatch stood_up(static_cast<double>(robot.period_ns()) * 1e-9);
  if (watch_get_up) episode.stop_on_fall = false;
  // A robot that may fall and go on lying: its landing is measured (impact in --json).
  episode.impact_metrics = watch_get_up && !getup;
  // The landing ends where the get-up begins: the get-up's own pushes are not the impact (the
  // get-up starts once the robot lies still, which can be inside the 0.8 s window).
  episode.impact_over = [&stood_up] { return stood_up.get_up().attempts() > 0; };
  // The first tick the firmware predicted a fall (FallPredictor), whether or not it protects.
  const double period_s = static_cast<double>(robot.period_ns()) * 1e-9;
  const stride::hal::Tick first_tick = robot.current_tick();
  // Back on its feet, back in the game (issue 54 point 4): a walk that fell and stood up walks
  // its command again; where the torso was when it stood up.
  const bool resume_walk = watch_get_up && r.motion == "walk";
  stride::fw::MotionState last_state = controller.motion().state();
  std::optional<Eigen::Vector2d> stood_at;
  const sim::StepFunction step = [&controller, &stood_up, &robot, watch_get_up, &predicted_s,
                                  period_s, first_tick, resume_walk, &last_state, &stood_at,
                                  &r](const stride::hal::SensorFrame& sensors,
                                      stride::hal::Tick tick) {
    stride::hal::CommandFrame commands = controller.step(sensors, tick);
    if (watch_get_up) stood_up.after_step(controller, robot.world(), tick);
    const stride::fw::MotionState state = controller.motion().state();
    if (resume_walk && state == stride::fw::MotionState::kStand &&
        last_state == stride::fw::MotionState::kGetUp)
      controller.request(stride::fw::MotionRequest::walk(r.vx, r.vy, r.vth));
    last_state = state;
    if (resume_walk && !stood_at && stood_up.stood_up_at_s())
      stood_at = robot.world().torso_pose().translation().head<2>();
    if (!predicted_s && controller.safety().report().predictions > 0)
      predicted_s = static_cast<double>(tick - first_tick) * period_s;
    return commands;
  };
  result = sim::run_episode(robot, step, episode);
  if (watch_get_up) {
    get_up.watched = true;
    get_up.lying = getup ? r.lying : "";
    get_up.attempts = stood_up.get_up().attempts();
    get_up.first_script = stood_up.get_up().first_script();
    // From lying still (t = 0) or from the episode's fall; without a fall there is nothing to
    // stand up from.
    if (stood_up.stood_up_at_s() && (getup || result.fell))
      get_up.stood_up_s = *stood_up.stood_up_at_s() - (getup ? 0.0 : result.fall_time_s);
    if (stood_at && result.fell)
      get_up.walked_after_m =
          (robot.world().torso_pose().translation().head<2>() - *stood_at).norm();
  }
  return {};
}

/// --record, --snapshot and --html.
Status write_outputs(const stride::core::CliArgs& args, const SimRequest& r,
                     const sim::TrajectoryRecorder& recorder, sim::SimRobot& robot,
                     const sim::EpisodeResult& result, const GetUpOutcome& get_up,
                     sim::EpisodeCapturer& capturer) {
  if (args.has("record")) {
    if (Status s = recorder.save(args.get("record")); !s) return s;
  }
  if (args.has("snapshot")) {
    const std::string svg = sim::render_pose_svg(
        robot.world().model(), result.snapshots, robot.world().ground().grass_thickness_m,
        r.world.ball.present ? r.world.ball.radius_m : 0.0);
    if (Status s = stride::core::write_file_atomically(args.get("snapshot"), svg); !s) return s;
  }
  if (args.has("html"))
    return write_html(args, r.params_file ? r.params_file->string() : "default parameters",
                      r.motion, r.duration_text, r.world, robot, result, get_up, capturer.finish());
  return {};
}

/// The result: one JSON object with --json, else two lines of text.
void print_result(bool json_output, const SimRequest& r, const sim::EpisodeResult& result,
                  const GetUpOutcome& get_up, const std::optional<double>& predicted_s) {
  if (json_output) {
    nlohmann::json json = sim::to_json(result);
    if (predicted_s) json["fall_predicted_s"] = *predicted_s;
    if (get_up.watched) {
      if (r.getup) json["lying"] = r.lying;
      json["stood_up_s"] = get_up.stood_up_s ? nlohmann::json(*get_up.stood_up_s) : nullptr;
      json["get_up_attempts"] = get_up.attempts;
      json["get_up_script"] = get_up.first_script;
      if (r.motion == "walk")
        json["walked_after_get_up_m"] =
            get_up.walked_after_m ? nlohmann::json(*get_up.walked_after_m) : nullptr;
    }
    std::printf("%s\n", json.dump().c_str());
  } else if (get_up.watched) {
    std::printf("%s%s: %s; %.2f s sim (%.2f s wall, %.1fx real time)\n", r.motion.c_str(),
                r.getup ? (" (lying on the " + r.lying + ")").c_str() : "",
                outcome_text(result, get_up).c_str(), result.sim_time_s, result.wall_time_s,
                result.rtf);
    std::printf("max |a| %.2f m/s^2, state %s\n", result.max_accel,
                sim::hash_hex(result.state_hash).c_str());
  } else {
    std::printf("%s: %s after %.2f s sim (%.2f s wall, %.1fx real time)\n", r.motion.c_str(),
                result.fell ? "FELL" : "standing", result.sim_time_s, result.wall_time_s,
                result.rtf);
    std::printf("distance %.3f m, max |a| %.2f m/s^2, max field-plane sway %.2f m/s^2, state %s\n",
                result.distance_m, result.max_accel, result.max_fps,
                sim::hash_hex(result.state_hash).c_str());
  }
}

}  // namespace

int run_sim_servo(int argc, char** argv);  // sim_servo.cpp

int run_sim(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "servo") return run_sim_servo(argc - 1, argv + 1);
  stride::core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(argc, argv); !s) return errors.bad_input(s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  SimRequest r;
  if (Status s = read_request(args, r); !s) return errors.bad_input(s.message());

  // The firmware exactly as stride-fw builds it (parameters, servo table, engines).
  stride::fw::FirmwareOptions fw_options;
  fw_options.params_file = r.params_file;
  std::unique_ptr<stride::fw::Firmware> firmware;
  if (Status s = stride::fw::Firmware::create(fw_options, firmware); !s)
    return errors.bad_input(s.message());
  r.world.control_period_ns = firmware->period_ns();
  if (Status s = sim::check_physics_step(r.world.physics_step_ns, firmware->period_ns(),
                                         "--physics-step-us");
      !s)
    return errors.bad_input(s.message());

  sim::TrajectoryRecorder recorder;
  sim::EpisodeOptions episode;
  episode.duration_s = r.duration;
  episode.metrics_start_s = r.metrics_from;
  episode.recorder = args.has("record") ? &recorder : nullptr;
  if (args.has("snapshot")) episode.snapshot_times_s = r.snapshot_times;
  sim::EpisodeCapturer capturer;
  if (args.has("html")) episode.on_tick = capturer.observer();
  std::unique_ptr<sim::SimRobot> robot_ptr;
  sim::EpisodeResult result;
  GetUpOutcome get_up;
  std::optional<double> predicted_s;  // stand and walk: when the firmware predicted a fall
  Status ran;
  if (r.motion == "kick") {
    // The seed's kick episode (script_episodes.hpp): ball in front of the kicking foot, the
    // kick requested at 1 s, played by the firmware's script engine once the stand is reached.
    sim::KickEpisodeOptions kick;
    kick.script = args.get("script");
    if (firmware->params().list("script." + kick.script + ".frame").empty())
      return errors.bad_input("--script: no script '" + kick.script +
                              "' in the firmware's scripts");
    kick.duration_s = r.duration;
    kick.ball_position = sim::kick_ball_position(kick.script);
    kick.firmware = fw_options;
    kick.episode = episode;
    ran = sim::run_kick_episode(r.world, kick, result, &robot_ptr);
  } else {
    ran = run_controlled_episode(r, *firmware, episode, result, robot_ptr, get_up, predicted_s);
  }
  if (!ran) return errors.failure(ran.message());
  if (Status s = write_outputs(args, r, recorder, *robot_ptr, result, get_up, capturer); !s)
    return errors.failure(s.message());
  print_result(args.has("json"), r, result, get_up, predicted_s);
  if (result.status != sim::WorldStatus::kRunning)
    return errors.failure("episode ended: " + result.failure_reason);
  return 0;
}

STRIDE_COMMAND(sim, "simulate the robot: stand, walk, kick or get up; one servo on a bench",
               run_sim);
