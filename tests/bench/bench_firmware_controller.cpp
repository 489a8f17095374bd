// Benchmark: the cost of one Controller::step (stand engine + safety layer; walk and script
// engines are measured in their own benchmarks), and of building a firmware from files already
// loaded, as the optimiser does once per episode.
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

void BM_FirmwareCreateFromLoadedFiles(benchmark::State& state) {
  stride::fw::FirmwareFiles files;
  if (!stride::fw::FirmwareFiles::load({}, files)) {
    state.SkipWithError("firmware files did not load");
    return;
  }
  for (auto _ : state) {
    std::unique_ptr<stride::fw::Firmware> firmware;
    if (!stride::fw::Firmware::create({}, files, firmware)) {
      state.SkipWithError("firmware did not build");
      return;
    }
    benchmark::DoNotOptimize(firmware.get());
  }
}
BENCHMARK(BM_FirmwareCreateFromLoadedFiles)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
