// Benchmark: the cost of one Controller::step (stand engine + safety layer; walk and script
// engines are measured in their own benchmarks).
#include <benchmark/benchmark.h>

#include <memory>

#include "stride/firmware/firmware.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace {

void BM_ControllerStepStanding(benchmark::State& state) {
  std::unique_ptr<stride::fw::Firmware> firmware;
  if (!stride::fw::Firmware::create({}, firmware)) {
    state.SkipWithError("firmware did not build");
    return;
  }
  auto& controller = firmware->controller();
  const auto sensors = stride::hal::ScriptedRobot::standing_frame();
  stride::hal::Tick tick = 0;
  for (auto _ : state) {
    auto commands = controller.step(sensors, tick++);
    benchmark::DoNotOptimize(commands);
  }
}
BENCHMARK(BM_ControllerStepStanding);

}  // namespace

BENCHMARK_MAIN();
