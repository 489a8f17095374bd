// Robustness of the walk engine over the optimiser's parameter space (issue 5 point 7):
// every one of the 46 genome parameters at each of its bounds gives finite joint targets that
// the safety layer keeps inside the joint limits (clamping and reporting where the engine
// exceeds them); random genomes within the bounds never give NaN. The 10,000-genome run is
// the integration test walk_genome_property_test.cpp; here a few hundred run under ASan.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "stride/firmware/safety_layer.hpp"
#include "stride/firmware/walk/walk_engine.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;

struct Outcome {
  bool finite = true;
  std::uint32_t engine_limit_violations = 0;  // ticks x joints outside the table limits
  std::uint32_t safety_clamps = 0;            // what the safety layer reported
  bool safe_output_inside_limits = true;
};

/// Walks with a command sequence (forward, then sideways/turning, then stop) for `ticks`.
Outcome run_walk(const std::vector<ParamWrite>& genome, int ticks, double vx, double vy,
                 double vtheta) {
  ParameterStore store;
  const ServoTable& servos = ServoTable::defaults();
  AttitudeEstimator attitude(store, kPeriodNs * 1e-9);
  WalkEngine engine(store, servos, kPeriodNs, attitude);
  SafetyLayer safety(store, servos);
  Outcome outcome;
  if (!store.set_now(genome)) {
    ADD_FAILURE() << "genome rejected";
    return outcome;
  }
  const hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame commands;
  engine.set_velocity(vx, vy, vtheta);
  engine.start(sensors, commands, 0);
  for (hal::Tick t = 0; t < ticks; ++t) {
    if (t == ticks / 2) engine.set_velocity(-vx, -vy, -vtheta);
    if (t == ticks - 250) engine.request_stop();
    attitude.update(sensors.cm730);
    engine.step(sensors, t, commands);
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      const double q = commands.servos[i].position_rad;
      if (!std::isfinite(q)) outcome.finite = false;
      if (q < servos[i].min_rad || q > servos[i].max_rad) ++outcome.engine_limit_violations;
    }
    hal::CommandFrame safe = commands;
    safety.observe(sensors, attitude);
    safety.apply(sensors, safe);
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      const double q = safe.servos[i].position_rad;
      if (!std::isfinite(q) || q < servos[i].min_rad || q > servos[i].max_rad) {
        outcome.safe_output_inside_limits = false;
      }
    }
  }
  for (auto c : safety.report().limit_clamps) outcome.safety_clamps += c;
  return outcome;
}

TEST(WalkRobustness, EveryGenomeParameterAtEachBound) {
  int with_violations = 0;
  for (const auto& row : walk::walk_parameter_table()) {
    if (row.table_e_index == 0) continue;
    for (double value : {row.min, row.max}) {
      const std::vector<ParamWrite> genome{{std::string(row.name), value}};
      const Outcome o = run_walk(genome, 650, 1.0, 0.3, 0.3);
      EXPECT_TRUE(o.finite) << row.name << " = " << value;
      EXPECT_TRUE(o.safe_output_inside_limits) << row.name << " = " << value;
      // Whatever the engine asked beyond the limits, the safety layer clamped and counted.
      EXPECT_EQ(o.safety_clamps, o.engine_limit_violations) << row.name << " = " << value;
      if (o.engine_limit_violations > 0) {
        ++with_violations;
        std::printf("  %s = %g: %u target(s) clamped by the safety layer\n",
                    std::string(row.name).c_str(), value, o.engine_limit_violations);
      }
    }
  }
  std::printf("  %d of 92 bound settings needed safety clamping\n", with_violations);
}

TEST(WalkRobustness, DefaultsStayInsideTheJointLimits) {
  for (auto [vx, vy, vth] : {std::tuple{1.0, 0.0, 0.0},
                             {-1.0, 0.0, 0.0},
                             {0.0, 1.0, 0.0},
                             {0.0, 0.0, 1.0},
                             {1.0, 1.0, 1.0}}) {
    const Outcome o = run_walk({}, 650, vx, vy, vth);
    EXPECT_TRUE(o.finite);
    EXPECT_EQ(o.engine_limit_violations, 0u) << vx << " " << vy << " " << vth;
  }
}

TEST(WalkRobustness, RandomGenomesWithinBoundsNeverGiveNaN) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> unit(0.0, 1.0), command(-1.0, 1.0);
  for (int g = 0; g < 60; ++g) {
    std::vector<ParamWrite> genome;
    for (const auto& row : walk::walk_parameter_table()) {
      genome.emplace_back(std::string(row.name), row.min + unit(rng) * (row.max - row.min));
    }
    const Outcome o = run_walk(genome, 500, command(rng), command(rng), command(rng));
    ASSERT_TRUE(o.finite) << "genome " << g;
    ASSERT_TRUE(o.safe_output_inside_limits) << "genome " << g;
  }
}

}  // namespace
}  // namespace stride::fw
