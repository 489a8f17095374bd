// Cost of one WalkEngine::step (issue 5 point 5: target <= 10 us) while walking forward and
// turning with the default (Ind_O) parameters, and of one leg IK solve.
#include <benchmark/benchmark.h>

#include "stride/firmware/walk/walk_engine.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace {

using namespace stride;

void BM_WalkEngineStep(benchmark::State& state) {
  fw::ParameterStore store;
  fw::AttitudeEstimator attitude(store, 0.01);  // the controller's: updated before each step
  fw::WalkEngine engine(store, fw::ServoTable::defaults(), 10'000'000, attitude);
  const hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame commands;
  engine.set_velocity(1.0, 0.2, 0.2);
  engine.start(sensors, commands, 0);
  hal::Tick tick = 0;
  for (; tick < 200; ++tick) {  // past the start blend
    attitude.update(sensors.cm730);
    engine.step(sensors, tick, commands);
  }
  for (auto _ : state) {
    attitude.update(sensors.cm730);
    engine.step(sensors, tick++, commands);
    benchmark::DoNotOptimize(commands);
  }
  state.counters["ik_clamped_ticks"] = static_cast<double>(engine.ik_clamped_ticks());
}
BENCHMARK(BM_WalkEngineStep);

void BM_LegInverseKinematics(benchmark::State& state) {
  const fw::walk::LegKinematics leg(fw::walk::LegSide::kLeft);
  const fw::walk::Pose3 target = leg.forward({0.2, 0.1, -0.4, 0.7, -0.3, -0.1});
  for (auto _ : state) {
    auto result = leg.inverse(target);
    benchmark::DoNotOptimize(result);
  }
}
BENCHMARK(BM_LegInverseKinematics);

}  // namespace

BENCHMARK_MAIN();
