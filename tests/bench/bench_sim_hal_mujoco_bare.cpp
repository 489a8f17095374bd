// Stride's MuJoCo engine step against MuJoCo's own bare mj_step on the same model (issue 42
// point 2, profiling): what share of a physics step is the work around mj_step (servo models,
// IMU model, SimWorld's bookkeeping, the engine's checks and link poses).
//
// A recording run: the firmware walks forward (Ind_O, 1 m/s, as bench_sim_hal_engines) on a
// MuJoCo SimWorld for `length` seconds; the engine's step observer (mujoco_engine.hpp) records
// the state before the first physics step, the compiled mjModel and each physics step's
// qfrc_applied (the joint torques of the servo models and the ball's rolling damping), and
// the firmware's command frames are kept. Then, per round, in alternating order:
// - Stride: a new world of the same seed replays the command frames (SimRobot read, write and
//   sleep_until: servo and IMU models, engine step, no firmware), timed;
// - bare: a fresh mjData of a copy of that mjModel, set to the recorded first state, steps
//   with mj_step, the recorded torques copied into qfrc_applied before each step, timed.
// The two runs compute the same trajectory (checked: the replayed world's state hash equals
// the recording's, the bare run's qpos the recording's last). Reported: microseconds per
// physics step of each (medians), the median and quartiles of the per-round ratio
// Stride / bare and the share of Stride's step spent outside mj_step (1 - bare / Stride),
// and MuJoCo's solver statistics of the episode per step (mean solver iterations, contacts,
// constraint rows).
// Run: build/release/bench/bench_sim_hal_mujoco_bare [rounds, default 9] [length s, default 4]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
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

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

/// What the recording run keeps.
struct Recording {
  ModelPtr model;
  DataPtr first;                            ///< the state before the first physics step
  std::vector<mjtNum> torques;              ///< nv per physics step
  std::vector<mjtNum> last_qpos;            ///< qpos before the last physics step
  std::vector<hal::CommandFrame> commands;  ///< per control period
  long steps = 0;
};

void observe(const mjModel* m, const mjData* d, void* context) {
  auto& r = *static_cast<Recording*>(context);
  if (!r.model) {
    r.model.reset(mj_copyModel(nullptr, m));
    r.first.reset(mj_makeData(m));
    mj_copyData(r.first.get(), m, d);
  }
  r.torques.insert(r.torques.end(), d->qfrc_applied, d->qfrc_applied + m->nv);
  r.last_qpos.assign(d->qpos, d->qpos + m->nq);
  ++r.steps;
}

sim::WorldOptions world_options(const fw::Firmware& firmware) {
  sim::WorldOptions options;
  options.engine = sim::EngineKind::kMujoco;
  options.control_period_ns = firmware.period_ns();
  return options;
}

std::unique_ptr<sim::SimRobot> make_robot(const sim::WorldOptions& options) {
  std::unique_ptr<sim::SimWorld> world;
  if (const stride::Status s = sim::SimWorld::create(options, world); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(2);
  }
  return std::make_unique<sim::SimRobot>(std::move(world));
}

/// Stride's loop: the recorded command frames replayed on `robot`; returns its state hash.
std::uint64_t replay(sim::SimRobot& robot, const std::vector<hal::CommandFrame>& commands) {
  hal::SensorFrame sensors;
  hal::Tick tick = 0;
  for (const hal::CommandFrame& c : commands) {
    robot.read(sensors);
    robot.write(c);
    robot.sleep_until(++tick);
  }
  return robot.world().state_hash();
}

/// The bare loop: the recorded torques on `d` (set to the first state) with mj_step.
void bare(const mjModel* m, mjData* d, const std::vector<mjtNum>& torques, long steps) {
  const int nv = m->nv;
  for (long k = 0; k < steps; ++k) {
    mju_copy(d->qfrc_applied, torques.data() + k * nv, nv);
    mj_step(m, d);
  }
}

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(3, std::atoi(argv[1])) : 9;
  const double length = argc > 2 ? std::atof(argv[2]) : 4.0;
  std::unique_ptr<fw::Firmware> firmware;
  if (!fw::Firmware::create({}, firmware)) return 2;
  const sim::WorldOptions options = world_options(*firmware);
  const int periods =
      static_cast<int>(length / (static_cast<double>(options.control_period_ns) * 1e-9) + 0.5);

  // The recording run: the firmware walking.
  Recording rec;
  std::uint64_t recorded_hash = 0;
  {
    std::unique_ptr<sim::SimRobot> robot = make_robot(options);
    firmware->controller().request(fw::MotionRequest::walk(1.0, 0, 0));
    sim::mujoco_set_step_observer(observe, &rec);
    hal::SensorFrame sensors;
    for (hal::Tick tick = 0; tick < static_cast<hal::Tick>(periods);) {
      robot->read(sensors);
      rec.commands.push_back(firmware->controller().step(sensors, tick));
      robot->write(rec.commands.back());
      robot->sleep_until(++tick);
    }
    sim::mujoco_set_step_observer(nullptr, nullptr);
    const sim::SimWorld& w = robot->world();
    recorded_hash = w.state_hash();
    if (w.status() != sim::WorldStatus::kRunning || w.torso_pose().linear()(2, 2) < 0.5)
      std::printf("note: the robot fell or the world failed during the recorded walk\n");
    std::printf("walk of %.2f s: %ld physics steps, torso at x = %.3f m\n", length, rec.steps,
                w.torso_pose().translation().x());
  }
  if (!rec.model || rec.steps == 0) return 2;
  const mjModel* m = rec.model.get();

  // Solver statistics and the check that the bare loop computes Stride's trajectory.
  {
    DataPtr d(mj_makeData(m));
    mj_copyData(d.get(), m, rec.first.get());
    double iterations = 0, contacts = 0, rows = 0, deviation = 0;
    const int nv = m->nv;
    for (long k = 0; k < rec.steps; ++k) {
      if (k == rec.steps - 1)
        for (int i = 0; i < m->nq; ++i)
          deviation = std::max(deviation, std::abs(d->qpos[i] - rec.last_qpos[i]));
      mju_copy(d->qfrc_applied, rec.torques.data() + k * nv, nv);
      mj_step(m, d.get());
      iterations += d->solver_iter;
      contacts += d->ncon;
      rows += d->nefc;
    }
    std::unique_ptr<sim::SimRobot> robot = make_robot(options);
    const bool same_world = replay(*robot, rec.commands) == recorded_hash;
    std::printf(
        "per step: %.2f solver iterations, %.2f contacts, %.2f constraint rows (mean); "
        "bare loop's last qpos off the recording's by %.3g; replayed world %s the recording\n",
        iterations / static_cast<double>(rec.steps), contacts / static_cast<double>(rec.steps),
        rows / static_cast<double>(rec.steps), deviation, same_world ? "equals" : "DIFFERS FROM");
  }

  std::vector<double> t_stride, t_bare, ratios;
  for (int r = 0; r < rounds; ++r) {
    std::unique_ptr<sim::SimRobot> robot = make_robot(options);
    DataPtr d(mj_makeData(m));
    mj_copyData(d.get(), m, rec.first.get());
    double a = 0, b = 0;
    for (int half = 0; half < 2; ++half) {
      if ((half == 0) == (r % 2 == 0)) {
        const auto t0 = Clock::now();
        replay(*robot, rec.commands);
        a = seconds(t0, Clock::now());
      } else {
        const auto t0 = Clock::now();
        bare(m, d.get(), rec.torques, rec.steps);
        b = seconds(t0, Clock::now());
      }
    }
    t_stride.push_back(a);
    t_bare.push_back(b);
    ratios.push_back(a / b);
  }
  const double steps = static_cast<double>(rec.steps);
  const double us_stride = 1e6 * quantile(t_stride, 0.5) / steps;
  const double us_bare = 1e6 * quantile(t_bare, 0.5) / steps;
  std::printf("%6s %12s %12s %9s %9s %9s %14s\n", "rounds", "us_stride", "us_bare", "ratio_q1",
              "ratio_med", "ratio_q3", "outside_mj_step");
  std::printf("%6d %12.1f %12.1f %9.3f %9.3f %9.3f %13.1f%%\n", rounds, us_stride, us_bare,
              quantile(ratios, 0.25), quantile(ratios, 0.5), quantile(ratios, 0.75),
              100.0 * (1.0 - 1.0 / quantile(ratios, 0.5)));
  std::printf("(us: microseconds per physics step, medians; ratio: Stride / bare per round)\n");
  return 0;
}
