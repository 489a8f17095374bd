// Step independence (issue 20, point 4): the firmware's behaviour at physics steps of 2, 1,
// 0.5 and 0.25 ms, and how far a 10 s forward walk strays from the 0.25 ms reference.
// Per step: stand 10 s; forward walk to 2.5 m (40 s) on N seeds; backward, sideways left and
// right, turning left and right 20 s each (seed 1); KickRight (ball >= 0.5 m, no fall) on N
// seeds; push and get up, from behind and from the front, on N seeds; then the 10 s walk's
// largest torso height and sideways deviation from the finest step's, tick by tick (over the
// ticks both walks lasted). Every
// figure is deterministic (the world's seeds); the wall time per step is printed for the
// real-time factor only.
// Run: build/release/bench/bench_sim_hal_step_independence [--seeds N] [--steps-us 2000,1000]
//      [--servo-law identified] [--imu cm730] [--engine mujoco] [--noise off]
//      [--params FILE]   (a firmware parameter file, e.g. balance gains under test)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "stride/core/cli_args.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/script_episodes.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace {

namespace fw = stride::fw;
namespace core = stride::core;
namespace hal = stride::hal;
namespace sim = stride::sim;

struct Walk {
  sim::EpisodeResult result;
  std::vector<double> z, y;  ///< torso height and sideways position per tick
};

fw::FirmwareOptions g_firmware;  // the firmware every episode runs (--params)

Walk walk(sim::WorldOptions options, std::uint64_t seed, double vx, double vy, double vth,
          double duration_s) {
  Walk out;
  std::unique_ptr<fw::Firmware> firmware;
  if (const stride::Status s = fw::Firmware::create(g_firmware, firmware); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(2);
  }
  options.seed = seed;
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  if (const stride::Status s = sim::SimWorld::create(options, world); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(2);
  }
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  if (vx != 0.0 || vy != 0.0 || vth != 0.0)  // all zero: the firmware stands
    controller.request(fw::MotionRequest::walk(vx, vy, vth));
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    const Eigen::Vector3d p = robot.world().torso_pose().translation();
    out.z.push_back(p.z());
    out.y.push_back(p.y());
    return controller.step(sensors, tick);
  };
  sim::EpisodeOptions episode;
  episode.duration_s = duration_s;
  out.result = sim::run_episode(robot, step, episode);
  return out;
}

double max_deviation(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;  // over the common ticks (a walk that fell is shorter)
}

std::vector<std::int64_t> parse_steps(const std::string& text) {
  std::vector<std::int64_t> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stoll(item));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  core::CliArgs args;
  args.option("seeds", "seeds for the forward walk, the kick and the get-up", true, "3");
  args.option("steps-us", "physics steps [us], the finest last (the reference)", true,
              "2000,1000,500,250");
  args.option("params", "firmware parameter file (JSON) applied after the defaults", true);
  sim::declare_world_options(args);
  if (const stride::Status s = args.parse(argc, argv); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 2;
  }
  sim::WorldOptions base;
  if (const stride::Status s = sim::read_world_options(args, base); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 2;
  }
  if (args.has("params")) g_firmware.params_file = args.get("params");
  std::int64_t seeds = 3;
  if (!args.get_int("seeds", seeds) || seeds < 1) return 2;
  const std::vector<std::int64_t> steps = parse_steps(args.get("steps-us"));
  std::printf("%s, noise %s, %lld seeds, parameters %s\n", sim::describe_world(base).c_str(),
              args.get("noise").c_str(), static_cast<long long>(seeds),
              args.has("params") ? args.get("params").c_str() : "default");
  std::printf("%8s %6s %9s %9s %6s %6s %7s %7s %7s %8s %8s %8s %6s\n", "step_us", "stand",
              "fwd_goal", "fwd_t_med", "back", "left", "right", "turn_l", "turn_r", "kick", "getup",
              "dz_mm", "dy_mm");
  Walk reference;
  std::vector<std::string> lines;
  std::vector<Walk> ten_second;
  for (std::int64_t step_us : steps) {
    const auto t0 = std::chrono::steady_clock::now();
    sim::WorldOptions o = base;
    o.physics_step_ns = step_us * 1000;
    const bool stand = !walk(o, 1, 0, 0, 0, 10.0).result.fell;
    int reached = 0;
    std::vector<double> times;
    for (std::int64_t s = 1; s <= seeds; ++s) {
      const Walk w = walk(o, static_cast<std::uint64_t>(s), 1, 0, 0, 40.0);
      if (!w.result.fell && w.result.time_to_goal_s) {
        ++reached;
        times.push_back(*w.result.time_to_goal_s);
      }
    }
    std::sort(times.begin(), times.end());
    auto lasts = [&](double vx, double vy, double vth) {
      return !walk(o, 1, vx, vy, vth, 20.0).result.fell;
    };
    const bool back = lasts(-1, 0, 0), left = lasts(0, 1, 0), right = lasts(0, -1, 0);
    const bool turn_l = lasts(0, 0, 1), turn_r = lasts(0, 0, -1);
    int kicks = 0, got_up = 0;
    for (std::int64_t s = 1; s <= seeds; ++s) {
      sim::WorldOptions k = o;
      k.seed = static_cast<std::uint64_t>(s);
      sim::KickEpisodeOptions kick_options;
      kick_options.firmware = g_firmware;
      sim::EpisodeResult kick;
      if (sim::run_kick_episode(k, kick_options, kick) && !kick.fell && kick.ball_distance_m >= 0.5)
        ++kicks;
      for (bool from_behind : {true, false}) {
        sim::PushEpisodeOptions push;
        push.from_behind = from_behind;
        push.duration_s = 40.0;  // a front fall rolls onto the back first (as the tests)
        push.firmware = g_firmware;
        sim::PushEpisodeResult r;
        if (sim::run_push_episode(k, push, r) && r.got_up) ++got_up;
      }
    }
    ten_second.push_back(walk(o, 1, 1, 0, 0, 10.0));
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    char line[256];
    std::snprintf(
        line, sizeof line, "%8lld %6s %6d/%-2lld %9.2f %6s %6s %7s %7s %7s %5d/%-2lld %5d/%-2lld",
        static_cast<long long>(step_us), stand ? "ok" : "FELL", reached,
        static_cast<long long>(seeds), times.empty() ? std::nan("") : times[times.size() / 2],
        back ? "ok" : "FELL", left ? "ok" : "FELL", right ? "ok" : "FELL", turn_l ? "ok" : "FELL",
        turn_r ? "ok" : "FELL", kicks, static_cast<long long>(seeds), got_up,
        static_cast<long long>(2 * seeds));
    lines.push_back(line);
    std::fprintf(stderr, "%s   (%.0f s wall)\n", line, wall);
  }
  const Walk& finest = ten_second.back();
  for (std::size_t i = 0; i < lines.size(); ++i)
    std::printf("%s %8.1f %8.1f\n", lines[i].c_str(),
                1e3 * max_deviation(ten_second[i].z, finest.z),
                1e3 * max_deviation(ten_second[i].y, finest.y));
  return 0;
}
