// Property test (issue 5 point 7): 10,000 random genomes, uniform within the optimiser bounds
// of the 46 walk parameters (and the body height), each walking with a random normalised
// command for 6 s including a stop; the walk engine never produces a non-finite target or
// throws, and after the safety layer every target is inside the joint limits.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "stride/firmware/safety_layer.hpp"
#include "stride/firmware/walk/walk_engine.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

TEST(WalkGenomeProperty, TenThousandRandomGenomesNeverGiveNaN) {
  const ServoTable& servos = ServoTable::defaults();
  ParameterStore store;
  AttitudeEstimator attitude(store, 0.01);
  WalkEngine engine(store, servos, 10'000'000, attitude);
  SafetyLayer safety(store, servos);
  const hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0), command(-1.0, 1.0);
  std::vector<ParamWrite> genome;
  std::uint64_t ticks = 0, outside_limits = 0, clamped_ik = 0;
  for (int g = 0; g < 10000; ++g) {
    genome.clear();
    for (const auto& row : walk::walk_parameter_table()) {
      genome.emplace_back(std::string(row.name), row.min + unit(rng) * (row.max - row.min));
    }
    ASSERT_TRUE(store.set_now(genome));
    hal::CommandFrame commands;
    engine.set_velocity(command(rng), command(rng), command(rng));
    const std::uint64_t clamped_before = engine.ik_clamped_ticks();
    engine.start(sensors, commands, 0);
    for (hal::Tick t = 0; t < 600; ++t) {
      if (t == 400) engine.request_stop();
      attitude.update(sensors.cm730);
      engine.step(sensors, t, commands);
      for (std::size_t i = 0; i < hal::kServoCount; ++i) {
        const double q = commands.servos[i].position_rad;
        ASSERT_TRUE(std::isfinite(q)) << "genome " << g << " tick " << t << " servo " << i;
        if (q < servos[i].min_rad || q > servos[i].max_rad) ++outside_limits;
      }
      hal::CommandFrame safe = commands;
      safety.apply(sensors, safe);
      for (std::size_t i = 0; i < hal::kServoCount; ++i) {
        const double q = safe.servos[i].position_rad;
        ASSERT_TRUE(q >= servos[i].min_rad && q <= servos[i].max_rad) << "genome " << g;
      }
      ++ticks;
    }
    clamped_ik += engine.ik_clamped_ticks() - clamped_before;
  }
  RecordProperty("ticks", std::to_string(ticks));
  std::printf(
      "  %llu ticks; %llu joint targets outside the limits (clamped by the safety "
      "layer); %llu ticks with a leg target out of reach (IK clamped)\n",
      static_cast<unsigned long long>(ticks), static_cast<unsigned long long>(outside_limits),
      static_cast<unsigned long long>(clamped_ik));
}

}  // namespace
}  // namespace stride::fw
