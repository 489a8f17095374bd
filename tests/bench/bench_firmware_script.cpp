// Script engine cost per control tick: ScriptEngine::step playing the stock kick_right, and the
// full Controller::step (motion manager + safety layer) during a kick. Counts heap allocations
// made inside the timed steps (must be 0: the control loop allocates nothing after start-up).
#include <atomic>
#include <cstdlib>
#include <new>

#include <benchmark/benchmark.h>

#include "stride/firmware/controller.hpp"
#include "stride/firmware/script/script_engine.hpp"
#include "stride/firmware/stand_pose.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// The replacement operator delete below frees what the replacement operator new malloc'ed;
// GCC cannot see that pairing when it inlines the library's calls.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace {

using namespace stride;
constexpr std::int64_t kPeriodNs = 10'000'000;

void BM_ScriptEngineStepKick(benchmark::State& state) {
  fw::ParameterStore params;
  fw::ScriptEngine engine(kPeriodNs, params);
  if (!engine.load_folder(fw::default_script_folder())) {
    state.SkipWithError("scripts");
    return;
  }
  engine.select(engine.find("kick_right"));
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame(fw::kStandPoseRad);
  hal::CommandFrame out{};
  hal::Tick tick = 0;
  engine.start(sensors, out, tick);
  const long before = g_allocations.load();
  for (auto _ : state) {
    if (engine.done()) engine.start(sensors, out, tick);
    engine.step(sensors, tick++, out);
    benchmark::DoNotOptimize(out);
  }
  state.counters["allocs_per_step"] = benchmark::Counter(
      static_cast<double>(g_allocations.load() - before), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_ScriptEngineStepKick);

void BM_ControllerStepDuringKicks(benchmark::State& state) {
  fw::ParameterStore params;
  fw::ScriptEngine engine(kPeriodNs, params);
  if (!engine.load_folder(fw::default_script_folder())) {
    state.SkipWithError("scripts");
    return;
  }
  fw::AttitudeEstimator attitude(params, kPeriodNs * 1e-9);
  fw::Controller controller(params, fw::ServoTable::defaults(), kPeriodNs, attitude,
                            {nullptr, &engine});
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame(fw::kStandPoseRad);
  hal::Tick tick = 0;
  for (; tick < 200; ++tick) benchmark::DoNotOptimize(controller.step(sensors, tick));
  long allocations = 0;
  for (auto _ : state) {
    if (controller.motion().state() == fw::MotionState::kStand) {
      state.PauseTiming();
      controller.request(fw::MotionRequest::play("kick_right"));  // off the timed path
      state.ResumeTiming();
    }
    const long before = g_allocations.load();
    benchmark::DoNotOptimize(controller.step(sensors, tick++));
    allocations += g_allocations.load() - before;
  }
  state.counters["allocs_per_step"] =
      benchmark::Counter(static_cast<double>(allocations), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_ControllerStepDuringKicks);

}  // namespace

BENCHMARK_MAIN();
