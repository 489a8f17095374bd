// The walk's planned speed along a direction and the command for a speed (ramp_command.hpp,
// issue 41 point 3): the closed forms of its header against the footstep planner's steady walk,
// each step limit's cap, the walk's parameters read back from a firmware's store, and the speeds
// the walk-ramp genome's ranges can plan.
#include "stride/optimiser/tasks/ramp_command.hpp"

#include <gtest/gtest.h>

#include <string>

#include "stride/firmware/walk/walk_parameters.hpp"
#include "stride/optimiser/tasks/task_config.hpp"

namespace stride::opt {
namespace {

using fw::walk::WalkParameters;

constexpr std::array<double, 3> kForward = {1.0, 0.0, 0.0}, kBackward = {-1.0, 0.0, 0.0},
                                kLeft = {0.0, 1.0, 0.0}, kRight = {0.0, -1.0, 0.0},
                                kTurnLeft = {0.0, 0.0, 1.0}, kTurnRight = {0.0, 0.0, -1.0};

TEST(RampCommand, WithNoStepLimitBindingATranslationGoesCommandTimesLimitPerStep) {
  const WalkParameters ind_o = fw::walk::default_walk_parameters();  // T = 0.85 s
  EXPECT_NEAR(planned_speed(ind_o, kForward, 0.2), 0.2 * 0.30 / 0.85, 1e-12);
  EXPECT_NEAR(planned_speed(ind_o, kBackward, 0.5), 0.5 * 0.027 / 0.85, 1e-12);
  EXPECT_NEAR(planned_speed(ind_o, kLeft, 0.5), 0.5 * 0.010 / 0.85, 1e-12);
  EXPECT_NEAR(planned_speed(ind_o, kRight, 1.0), 0.010 / 0.85, 1e-12);
  EXPECT_EQ(planned_speed(ind_o, kForward, 0.0), 0.0);
  // A shorter step is faster at the same command.
  WalkParameters quick = ind_o;
  quick.step_time = 0.5;
  EXPECT_NEAR(planned_speed(quick, kForward, 0.2), 0.2 * 0.30 / 0.5, 1e-12);
}

TEST(RampCommand, TheStepLimitsCapTheTranslations) {
  WalkParameters p = fw::walk::default_walk_parameters();
  // Forward: 0.3 m/step asked, step.limits.x_max 0.1 m lets 0.1 m/step.
  EXPECT_NEAR(planned_speed(p, kForward, 1.0), 0.10 / 0.85, 1e-12);
  p.velocity_limits.x_min = -0.2;
  EXPECT_NEAR(planned_speed(p, kBackward, 0.25), 0.05 / 0.85, 1e-12);
  EXPECT_NEAR(planned_speed(p, kBackward, 1.0), 0.10 / 0.85, 1e-12);  // step.limits.x_min
  // Sideways: half width h = 0.055 + 0.05 = 0.105 m, the feet kept C = 0.11 + 0.05 = 0.16 m
  // apart. Up to v = 2 h - C = 0.05 m/step the walk goes v per step; beyond, the inner foot
  // stops at C and a step pair gains h - C / 2 + 1.5 v; the outer foot stops at step y_max.
  p.velocity_limits.y_max = 0.1;
  EXPECT_NEAR(planned_speed(p, kLeft, 0.4), 0.04 / 0.85, 1e-12);
  EXPECT_NEAR(planned_speed(p, kLeft, 0.6), (0.105 - 0.08 + 1.5 * 0.06) / 1.7, 1e-12);
  // At 0.1 m/step the outer foot would land 0.08 + 0.105 + 0.15 = 0.335 m out, y_max is 0.3:
  // a pair gains y_max - C.
  EXPECT_NEAR(planned_speed(p, kLeft, 1.0), (0.30 - 0.16) / 1.7, 1e-12);
  // The planar part is capped at velocity.limits.x_max.
  p.velocity_limits.y_max = 0.25;
  p.velocity_limits.x_max = 0.02;
  EXPECT_NEAR(planned_speed(p, kLeft, 1.0), 0.02 / 0.85, 1e-12);
}

TEST(RampCommand, ATurnTurnsThreeQuartersOfItsVelocityUpToTheStepLimitPerPair) {
  WalkParameters p = fw::walk::default_walk_parameters();
  // The outer foot turns 1.5 w past the inner one, the inner one closes up: 1.5 w per pair.
  EXPECT_NEAR(planned_speed(p, kTurnLeft, 0.1), 0.75 * 0.08 / 0.85, 1e-12);
  EXPECT_NEAR(planned_speed(p, kTurnRight, 0.1), 0.75 * 0.08 / 0.85, 1e-12);
  // A pair turns at most step.limits.angle_max (0.262 rad).
  EXPECT_NEAR(planned_speed(p, kTurnLeft, 1.0), 0.262 / 1.7, 1e-12);
  // With angle_min > 0 the inner foot stays that far out: a pair turns 1.5 w - angle_min / 2.
  p.step_limits.angle_min = 0.05;
  EXPECT_NEAR(planned_speed(p, kTurnLeft, 0.1), (1.5 * 0.08 - 0.025) / 1.7, 1e-12);
  // Walking forward the splayed feet do not turn the walk.
  EXPECT_NEAR(planned_speed(p, kTurnLeft, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(planned_speed(p, kForward, 0.2), 0.2 * 0.30 / 0.85, 1e-12);
}

TEST(RampCommand, TheCommandForASpeedPlansItOrThereIsNone) {
  const WalkParameters ind_o = fw::walk::default_walk_parameters();
  const std::optional<double> c = command_for_speed(ind_o, kForward, 0.05);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(*c, 0.05 * 0.85 / 0.30, 1e-11);
  EXPECT_NEAR(planned_speed(ind_o, kForward, *c), 0.05, 1e-11);
  // Where the step limit caps, the smallest command that reaches the cap.
  const std::optional<double> top = command_for_speed(ind_o, kForward, 0.10 / 0.85);
  ASSERT_TRUE(top.has_value());
  EXPECT_NEAR(*top, 0.10 / 0.30, 1e-11);
  EXPECT_FALSE(command_for_speed(ind_o, kForward, 0.10 / 0.85 + 1e-6).has_value());
  // Ind_O's sideways and turning limits: 0.0118 m/s and 0.154 rad/s at most.
  EXPECT_FALSE(command_for_speed(ind_o, kLeft, 0.05).has_value());
  EXPECT_FALSE(command_for_speed(ind_o, kTurnLeft, 0.2).has_value());
  EXPECT_TRUE(command_for_speed(ind_o, kTurnLeft, 0.15).has_value());
  EXPECT_EQ(command_for_speed(ind_o, kRight, 0.0), 0.0);
}

TEST(RampCommand, TheWalksParametersAreReadFromTheFirmwaresStore) {
  fw::ParameterStore store;
  WalkParameters p;
  Status s = read_walk_parameters(store, p);
  ASSERT_FALSE(s);  // no walk registered
  EXPECT_NE(s.message().find("walk.stance.body_height"), std::string::npos) << s.message();
  const fw::walk::WalkParameterSet walk(store);
  ASSERT_TRUE(store.set_now(
      {{"walk.walk_cycle.step_time", 0.5}, {"walk.walk_cycle.velocity.limits.y_max", 0.06}}));
  ASSERT_TRUE(read_walk_parameters(store, p));
  EXPECT_EQ(p.step_time, 0.5);
  EXPECT_EQ(p.velocity_limits.y_max, 0.06);
  EXPECT_EQ(p.velocity_limits.y_min, -0.01);  // Ind_O
  EXPECT_EQ(p.step_limits.angle_max, 0.262);
}

/// A gene's bound in walk-ramp.json (`upper`: its max).
double gene_bound(const TaskConfig& config, const std::string& name, bool upper) {
  for (const TaskGene& g : config.genes)
    if (g.parameter == name) return upper ? g.max : g.min;
  ADD_FAILURE() << name << " is not a gene of walk-ramp.json";
  return 0.0;
}

// Issue 41 point 3: the walk-ramp genome's ranges plan the NUgus's speeds in simulation (0.38 m/s
// forward, 0.42 backward, 0.26 sideways, 1.97 rad/s turning) and beyond: at its fastest corner
// (shortest step, widest limits, widest stance, closest feet allowed), and stepping-turf-omni's
// 0.5 s steps with the limits at their ranges' ends still plan the translations.
TEST(RampCommand, TheWalkRampGenomeReachesThePublishedSpeeds) {
  TaskConfig config;
  ASSERT_TRUE(load_task_config(std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/walk-ramp.json",
                               config));
  const std::string cycle = "walk.walk_cycle.";
  auto max = [&](const std::string& name) { return gene_bound(config, cycle + name, true); };
  auto min = [&](const std::string& name) { return gene_bound(config, cycle + name, false); };
  WalkParameters p = fw::walk::default_walk_parameters();
  p.step_time = min("step_time");
  p.step_limits = {
      min("step.limits.x_min"),    max("step.limits.x_max"), 0.0, max("step.limits.y_max"), 0.0,
      max("step.limits.angle_max")};
  p.velocity_limits = {min("velocity.limits.x_min"),     max("velocity.limits.x_max"),
                       min("velocity.limits.y_min"),     max("velocity.limits.y_max"),
                       min("velocity.limits.angle_min"), max("velocity.limits.angle_max")};
  p.foot_offset_y = gene_bound(config, "walk.stance.foot_offset.y", false);
  p.limit_margin_y = gene_bound(config, "walk.stance.limit_margin_y", true);
  EXPECT_EQ(p.step_time, 0.35);
  EXPECT_EQ(p.step_limits.angle_max, 1.6);
  EXPECT_GE(planned_speed(p, kForward, 1.0), 0.38 * 1.5);
  EXPECT_GE(planned_speed(p, kBackward, 1.0), 0.42 * 1.5);
  EXPECT_GE(planned_speed(p, kLeft, 1.0), 0.26 * 1.5);
  EXPECT_GE(planned_speed(p, kRight, 1.0), 0.26 * 1.5);
  EXPECT_GE(planned_speed(p, kTurnLeft, 1.0), 1.97 * 1.1);
  EXPECT_GE(planned_speed(p, kTurnRight, 1.0), 1.97 * 1.1);
  // With the issue-22 ranges (0.425 s steps, 0.8 rad per pair) turning stopped at 0.94 rad/s.
  WalkParameters old = p;
  old.step_time = 0.425;
  old.step_limits.angle_max = 0.8;
  EXPECT_LT(planned_speed(old, kTurnLeft, 1.0), 0.95);
  // At stepping-turf-omni.json's 0.5 s the translations still plan beyond the NUgus's.
  p.step_time = 0.5;
  EXPECT_GE(planned_speed(p, kForward, 1.0), 0.38);
  EXPECT_GE(planned_speed(p, kBackward, 1.0), 0.42);
  EXPECT_GE(planned_speed(p, kLeft, 1.0), 0.26);
}

}  // namespace
}  // namespace stride::opt
