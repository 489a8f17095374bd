// Simulator speed: real-time factor of one world standing and stepping in place (a scripted
// motion that makes and breaks foot contact), throughput of worlds on 1 and 2 threads, and
// memory per world. Counters: rtf = simulated seconds per wall second, per thread;
// contact_changes = foot contact make/break events per simulated second (stepping).
// Run: build/release/bench/bench_sim_hal_rtf [--benchmark_filter=...]
//      (--physics-step-us N is read from the environment STRIDE_BENCH_STEP_US, default 2000)
#include <benchmark/benchmark.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <thread>
#include <vector>

#include "stride/sim_hal/sim_world.hpp"

namespace {

using stride::sim::SimWorld;
namespace hal = stride::hal;

std::int64_t physics_step_ns() {
  const char* env = std::getenv("STRIDE_BENCH_STEP_US");
  return (env ? std::atoll(env) : 2000) * 1000;
}

std::unique_ptr<SimWorld> make_world(
    std::int64_t step_ns = physics_step_ns(),
    stride::sim::ServoLaw law = stride::sim::WorldOptions{}.servo.law) {
  stride::sim::WorldOptions options;
  options.physics_step_ns = step_ns;
  options.servo.law = law;
  std::unique_ptr<SimWorld> world;
  const stride::Status s = SimWorld::create(options, world);
  if (!s) std::abort();
  return world;
}

/// Stepping in place, open loop: the hips roll the torso over one foot, the other leg lifts
/// (hip, knee, ankle pitch), then the other side; 0.8 s per step.
void command_stepping(SimWorld& world, double t) {
  constexpr double kCycle = 1.2;   // s per left+right step
  constexpr double kSway = -0.09;  // hip/ankle roll amplitude [rad] (torso over the stance foot)
  constexpr double kLift = 0.25;   // hip/ankle pitch of the lifted leg [rad], knee twice that
  std::array<double, hal::kServoCount> pose = stride::sim::igus_stand_pose();
  const double phase = std::fmod(t, kCycle) / kCycle;  // 0..1 over a left+right cycle
  const double s = std::sin(2 * M_PI * phase);
  const double sway = kSway * s;  // +: hips roll the torso over the left foot
  const double lift_r = std::max(0.0, s * s * s) * kLift;
  const double lift_l = std::max(0.0, -s * s * s) * kLift;
  for (std::size_t i : {8U, 9U}) pose[i] += sway;    // hip rolls
  for (std::size_t i : {16U, 17U}) pose[i] -= sway;  // ankle rolls
  pose[10] -= lift_r;
  pose[12] += 2 * lift_r;
  pose[14] -= lift_r;  // right leg
  pose[11] -= lift_l;
  pose[13] += 2 * lift_l;
  pose[15] -= lift_l;  // left leg
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand c;
    c.position_rad = pose[i];
    c.p_gain = 76;
    c.torque_enable = true;
    world.set_servo_command(i, c);
  }
}

void hold_stand(SimWorld& world) {
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand c;
    c.position_rad = stride::sim::igus_stand_pose()[i];
    c.p_gain = 76;
    c.torque_enable = true;
    world.set_servo_command(i, c);
  }
}

void BM_Stand(benchmark::State& state) {
  auto world = make_world();
  hold_stand(*world);
  double sim_seconds = 0;
  for (auto _ : state) {
    world->advance_period();
    sim_seconds += 0.01;
  }
  if (world->status() != stride::sim::WorldStatus::kRunning)
    state.SkipWithError(world->failure_reason().c_str());
  state.counters["rtf"] = benchmark::Counter(sim_seconds, benchmark::Counter::kIsRate);
}

void BM_SteppingInPlace(benchmark::State& state) {
  auto world = make_world();
  double sim_seconds = 0;
  int resets = 0, changes = 0;
  bool left_down = true, right_down = true;
  for (auto _ : state) {
    command_stepping(*world, world->time_s());
    world->advance_period();
    sim_seconds += 0.01;
    state.PauseTiming();
    const stride::sim::GroundTruth g = world->ground_truth();
    const bool l = g.left_contact.points_in_contact > 0, r = g.right_contact.points_in_contact > 0;
    changes += (l != left_down) + (r != right_down);
    left_down = l;
    right_down = r;
    if (g.torso.linear()(2, 2) < 0.5 || world->status() != stride::sim::WorldStatus::kRunning) {
      (void)world->reset(stride::sim::ResetSpec::standing());
      ++resets;
    }
    state.ResumeTiming();
  }
  state.counters["rtf"] = benchmark::Counter(sim_seconds, benchmark::Counter::kIsRate);
  state.counters["resets"] = resets;
  state.counters["contact_changes_per_s"] = changes / std::max(sim_seconds, 1e-9);
}

/// Steps a world through `periods` control periods of the stepping motion.
void step_periods(SimWorld& world, int periods) {
  for (int k = 0; k < periods; ++k) {
    command_stepping(world, world.time_s());
    if (!world.advance_period()) (void)world.reset(stride::sim::ResetSpec::standing());
  }
}

/// Throughput: every thread steps its own world (stepping in place).
void BM_SteppingThreads(benchmark::State& state) {
  auto world = make_world();
  double sim_seconds = 0;
  for (auto _ : state) {
    step_periods(*world, 1);
    sim_seconds += 0.01;
  }
  state.counters["rtf"] = benchmark::Counter(
      sim_seconds, benchmark::Counter::kIsRate | benchmark::Counter::kAvgThreads);
  state.counters["rtf_total"] = benchmark::Counter(sim_seconds, benchmark::Counter::kIsRate);
}

/// Accuracy: 10 s of stepping in place at the benchmark's physics step against a 0.25 ms
/// reference; the largest torso deviation in height (dz) and sideways (dy) [mm].
void BM_AccuracyAgainstFineStep(benchmark::State& state) {
  double dz = 0, dy = 0, dx = 0;
  for (auto _ : state) {
    auto coarse = make_world();
    auto fine = make_world(250'000);
    for (int k = 0; k < 1000; ++k) {
      command_stepping(*coarse, coarse->time_s());
      command_stepping(*fine, fine->time_s());
      coarse->advance_period();
      fine->advance_period();
      const Eigen::Vector3d d =
          coarse->torso_pose().translation() - fine->torso_pose().translation();
      dx = std::max(dx, std::abs(d.x()) * 1e3);
      dy = std::max(dy, std::abs(d.y()) * 1e3);
      dz = std::max(dz, std::abs(d.z()) * 1e3);
    }
  }
  state.counters["dx_max_mm"] = dx;
  state.counters["dy_max_mm"] = dy;
  state.counters["dz_max_mm"] = dz;
}

/// Two threads against one, measured in alternation: each round times one world stepping
/// `kPeriods` control periods alone, then two worlds doing the same on two threads, and
/// takes the ratio of their throughputs. Rounds a fraction of a second apart see the same host
/// speed, so the median ratio over the rounds cancels the drift that separate runs of
/// BM_SteppingThreads/threads:1 and :2 (seconds apart) pick up on a shared VM.
void BM_TwoThreadsAgainstOne(benchmark::State& state) {
  constexpr int kRounds = 21, kPeriods = 200;  // 2 s simulated per world and phase
  using Clock = std::chrono::steady_clock;
  std::vector<double> ratios;
  for (auto _ : state) {
    auto a = make_world();
    auto b = make_world();
    step_periods(*a, 20);  // warm up
    step_periods(*b, 20);
    for (int round = 0; round < kRounds; ++round) {
      const auto t0 = Clock::now();
      step_periods(*a, kPeriods);
      const auto t1 = Clock::now();
      std::thread other([&] { step_periods(*b, kPeriods); });
      step_periods(*a, kPeriods);
      other.join();
      const auto t2 = Clock::now();
      const double one = std::chrono::duration<double>(t1 - t0).count();
      const double two = std::chrono::duration<double>(t2 - t1).count();
      ratios.push_back(2.0 * one / two);  // (2 worlds / two) / (1 world / one)
    }
  }
  std::sort(ratios.begin(), ratios.end());
  state.counters["ratio_median"] = ratios[ratios.size() / 2];
  state.counters["ratio_q1"] = ratios[ratios.size() / 4];
  state.counters["ratio_q3"] = ratios[3 * ratios.size() / 4];
}

/// The identified MX servo law against the seed's, measured in alternation as above: each round
/// times a seed-law world and an identified-law world stepping in place for the same simulated
/// time; the counter is the median of (identified time / seed time), the cost of the law per
/// simulated second (issue 31: at most 1.1x).
void BM_IdentifiedAgainstSeedLaw(benchmark::State& state) {
  constexpr int kRounds = 21, kPeriods = 200;
  using Clock = std::chrono::steady_clock;
  using stride::sim::ServoLaw;
  std::vector<double> ratios;
  for (auto _ : state) {
    auto seed = make_world(physics_step_ns(), ServoLaw::kSeed);
    auto identified = make_world(physics_step_ns(), ServoLaw::kIdentified);
    const auto run = [](SimWorld& world) {
      for (int k = 0; k < kPeriods; ++k) {
        command_stepping(world, world.time_s());
        world.advance_period();
      }
    };
    for (int round = 0; round < kRounds; ++round) {
      const auto t0 = Clock::now();
      run(*seed);
      const auto t1 = Clock::now();
      run(*identified);
      const auto t2 = Clock::now();
      ratios.push_back(std::chrono::duration<double>(t2 - t1).count() /
                       std::chrono::duration<double>(t1 - t0).count());
    }
    if (seed->status() != stride::sim::WorldStatus::kRunning ||
        identified->status() != stride::sim::WorldStatus::kRunning)
      state.SkipWithError("a world failed");
    // Both still up (torso height [m]): a fallen robot's contacts would cost, not its law.
    state.counters["seed_torso_z"] = seed->torso_pose().translation().z();
    state.counters["identified_torso_z"] = identified->torso_pose().translation().z();
  }
  std::sort(ratios.begin(), ratios.end());
  state.counters["ratio_median"] = ratios[ratios.size() / 2];
  state.counters["ratio_q1"] = ratios[ratios.size() / 4];
  state.counters["ratio_q3"] = ratios[3 * ratios.size() / 4];
}

long resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

void BM_MemoryPerWorld(benchmark::State& state) {
  constexpr int kWorlds = 8;
  double per_world = 0;
  for (auto _ : state) {
    std::vector<std::unique_ptr<SimWorld>> worlds;
    make_world();  // warm caches (URDF parser, servo table)
    const long before = resident_bytes();
    for (int i = 0; i < kWorlds; ++i) {
      worlds.push_back(make_world());
      worlds.back()->advance_period();
    }
    per_world = static_cast<double>(resident_bytes() - before) / kWorlds;
  }
  state.counters["bytes_per_world"] = per_world;
}

}  // namespace

BENCHMARK(BM_Stand)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK(BM_SteppingInPlace)->Unit(benchmark::kMicrosecond)->MinTime(2.0);
BENCHMARK(BM_SteppingThreads)
    ->Unit(benchmark::kMicrosecond)
    ->MinTime(2.0)
    ->Threads(1)
    ->Threads(2)
    ->UseRealTime();
BENCHMARK(BM_TwoThreadsAgainstOne)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_IdentifiedAgainstSeedLaw)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MemoryPerWorld)->Iterations(1);
BENCHMARK(BM_AccuracyAgainstFineStep)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
