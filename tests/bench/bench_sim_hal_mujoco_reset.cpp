// The MuJoCo engine's speed over many short episodes, with its model compiled once per model
// structure (the engine keeps the compiled mjModel across resets and writes a randomised
// episode's masses, trunk centre of mass, friction and ground into it) against the old path, a
// compile of the episode's MJCF at every reset (mujoco_set_always_compile), side by side in one
// run. Each round runs `episodes` episodes (reset, then the Stand pose held for `length`
// seconds at P 32) on one world with each path, in alternating order, and the ratio of their
// times is taken per round, so that the host's drift cancels. Two worlds: no randomisation and
// the optimiser's default mass and friction randomisation with the trunk's centre of mass and
// the ground drawn too. Reported: episodes per second and real-time factor of each path
// (medians), and the median and quartiles of the per-round ratio old / new. Then one
// randomised 5 s walk (the firmware walking forward) on each path: the torso's end position,
// the time to walk 1 m and whether the state hashes are equal.
// Run: build/release/bench/bench_sim_hal_mujoco_reset [rounds, default 9] [episodes, default 20]
//      [length s, default 0.5]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "mujoco/mujoco_engine.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace {

namespace fw = stride::fw;
namespace hal = stride::hal;
namespace sim = stride::sim;
using Clock = std::chrono::steady_clock;

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

/// Seconds for `episodes` episodes of `periods` control periods on `world`, each after a reset.
double run(sim::SimWorld& world, int episodes, int periods, bool old_path) {
  sim::mujoco_set_always_compile(old_path);
  const auto t0 = Clock::now();
  for (int e = 0; e < episodes; ++e) {
    if (const stride::Status s = world.reset(sim::ResetSpec::standing()); !s) {
      std::fprintf(stderr, "reset: %s\n", s.message().c_str());
      std::exit(2);
    }
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      hal::ServoCommand c;
      c.position_rad = sim::igus_stand_pose()[i];
      c.p_gain = 32;
      c.torque_enable = true;
      world.set_servo_command(i, c);
    }
    for (int k = 0; k < periods; ++k)
      if (!world.advance_period()) break;
  }
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  sim::mujoco_set_always_compile(false);
  return s;
}

/// A world with every per-reset draw of the optimiser's randomisation (masses, friction) and
/// the trunk's centre of mass and the ground drawn too.
sim::WorldOptions randomised_options() {
  sim::WorldOptions options;
  options.engine = sim::EngineKind::kMujoco;
  options.randomise.mass_range = 0.05;
  options.randomise.friction_range = 0.2;
  options.randomise.com_range = 0.01;
  options.randomise.contact_range = 0.5;
  return options;
}

/// The end of one randomised walk.
struct Walk {
  Eigen::Vector3d torso = Eigen::Vector3d::Zero();
  double time_to_1m_s = -1.0;
  std::uint64_t hash = 0;
};

/// The firmware walking forward for 5 s on a world made on `old_path` and reset once more (the
/// new path then writes the episode's values into the model it kept).
Walk walk(bool old_path) {
  sim::mujoco_set_always_compile(old_path);
  std::unique_ptr<fw::Firmware> firmware;
  if (!fw::Firmware::create({}, firmware)) std::exit(2);
  sim::WorldOptions options = randomised_options();
  options.seed = 7;
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  if (!sim::SimWorld::create(options, world) || !world->reset(sim::ResetSpec::standing()))
    std::exit(2);
  sim::SimRobot robot(std::move(world));
  firmware->controller().request(fw::MotionRequest::walk(1.0, 0, 0));
  Walk out;
  const double x0 = robot.world().torso_pose().translation().x();
  const double period_s = static_cast<double>(options.control_period_ns) * 1e-9;
  for (hal::Tick tick = 0; static_cast<double>(tick) * period_s < 5.0;) {
    hal::SensorFrame sensors;
    robot.read(sensors);
    robot.write(firmware->controller().step(sensors, tick));
    robot.sleep_until(++tick);
    if (out.time_to_1m_s < 0 && robot.world().torso_pose().translation().x() - x0 >= 1.0)
      out.time_to_1m_s = static_cast<double>(tick) * period_s;
  }
  out.torso = robot.world().torso_pose().translation();
  out.hash = robot.world().state_hash();
  sim::mujoco_set_always_compile(false);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(3, std::atoi(argv[1])) : 9;
  const int episodes = argc > 2 ? std::max(1, std::atoi(argv[2])) : 20;
  const double length = argc > 3 ? std::atof(argv[3]) : 0.5;
  std::printf("%d rounds of %d episodes of %.2f s simulated, each path\n", rounds, episodes,
              length);
  std::printf("%-12s %9s %9s %9s %9s %9s %9s %9s %9s\n", "world", "compiles", "eps_old", "eps_new",
              "rtf_old", "rtf_new", "ratio_q1", "ratio_med", "ratio_q3");
  for (const bool randomised : {false, true}) {
    sim::WorldOptions options;
    options.engine = sim::EngineKind::kMujoco;
    if (randomised) options = randomised_options();
    std::unique_ptr<sim::SimWorld> world;
    if (const stride::Status s = sim::SimWorld::create(options, world); !s) {
      std::fprintf(stderr, "%s\n", s.message().c_str());
      return 2;
    }
    const int periods =
        static_cast<int>(length / (static_cast<double>(options.control_period_ns) * 1e-9) + 0.5);
    const double simulated =
        episodes * periods * static_cast<double>(options.control_period_ns) * 1e-9;
    std::vector<double> t_old, t_new, ratios;
    std::int64_t compiles_new = 0;
    for (int r = 0; r < rounds; ++r) {
      const bool old_first = r % 2 == 0;
      double a = 0, b = 0;
      if (old_first) a = run(*world, episodes, periods, true);
      const std::int64_t before = sim::mujoco_compile_count();
      b = run(*world, episodes, periods, false);
      compiles_new += sim::mujoco_compile_count() - before;
      if (!old_first) a = run(*world, episodes, periods, true);
      t_old.push_back(a);
      t_new.push_back(b);
      ratios.push_back(a / b);
    }
    const double to = quantile(t_old, 0.5), tn = quantile(t_new, 0.5);
    char compiles[32];
    std::snprintf(compiles, sizeof compiles, "%lld/%d", static_cast<long long>(compiles_new),
                  rounds * episodes);
    std::printf("%-12s %9s %9.1f %9.1f %9.1f %9.1f %9.2f %9.2f %9.2f\n",
                randomised ? "randomised" : "fixed", compiles, episodes / to, episodes / tn,
                simulated / to, simulated / tn, quantile(ratios, 0.25), quantile(ratios, 0.5),
                quantile(ratios, 0.75));
  }
  std::printf(
      "(compiles: MJCF compiles of the new path / its resets; eps: episodes per second; "
      "ratio: time old / time new per round)\n");
  const Walk a = walk(true), b = walk(false);
  std::printf(
      "randomised 5 s walk, old path / new path: torso (%.9f, %.9f, %.9f) / (%.9f, %.9f, %.9f) "
      "m, largest difference %.3g m; 1 m walked at %.2f / %.2f s; state hashes %s\n",
      a.torso.x(), a.torso.y(), a.torso.z(), b.torso.x(), b.torso.y(), b.torso.z(),
      (a.torso - b.torso).cwiseAbs().maxCoeff(), a.time_to_1m_s, b.time_to_1m_s,
      a.hash == b.hash ? "equal" : "differ");
  return 0;
}
