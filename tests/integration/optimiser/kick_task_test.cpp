// The kick task's kicking foot (issue 44 point 1): a kick_left config places the ball before the
// left foot, as `stride sim kick --script kick_left` does, and a short kick_left episode of the
// optimiser moves the ball; kick_right keeps the ball before the right foot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "seeds.hpp"
#include "stride/optimiser/tasks/kick_figures.hpp"
#include "stride/optimiser/tasks/kick_settings.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "task_figures_of.hpp"

namespace stride::opt {
namespace {

const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

TaskConfig kick_config(const std::string& script) {
  TaskConfig c;
  EXPECT_TRUE(load_task_config(kConfigs + "kick.json", c));
  c.own_settings<KickSettings>().script = script;
  return c;
}

/// The world as the kick task's reset places it.
sim::GroundTruth start_of(const TaskConfig& c) {
  const TaskType* kick = find_task_type("kick");
  std::unique_ptr<sim::SimWorld> world;
  EXPECT_TRUE(sim::SimWorld::create(sim::WorldOptions{}, kick->reset_spec(c, 0), world));
  return world ? world->ground_truth() : sim::GroundTruth{};
}

TEST(KickTask, TheBallStartsBeforeTheKickingFoot) {
  for (const char* script : {"kick_right", "kick_left"}) {
    SCOPED_TRACE(script);
    const sim::GroundTruth g = start_of(kick_config(script));
    const bool left = std::string(script) == "kick_left";
    const Eigen::Vector3d foot = (left ? g.left_foot : g.right_foot).translation();
    const Eigen::Vector3d other = (left ? g.right_foot : g.left_foot).translation();
    EXPECT_LT(std::abs(g.ball_position.y() - foot.y()), std::abs(g.ball_position.y() - other.y()));
    EXPECT_GT(g.ball_position.x(), foot.x());    // in front of it
    EXPECT_EQ(g.ball_position.y() > 0.0, left);  // the robot's left is +y
  }
}

// A short kick_left episode moves the ball, in 5 of the config's drawn worlds (counted with one
// to spare); the objective is the episode's own ball distance.
TEST(KickTask, AShortLeftKickMovesTheBall) {
  TaskConfig c = kick_config("kick_left");
  c.duration_s = 5.0;
  c.trials = test::seed_count(5);
  const RobotTask task(c);
  ASSERT_TRUE(task.check());
  int moved = 0;
  for (int trial = 0; trial < c.trials; ++trial) {
    EpisodeScore s;
    ASSERT_TRUE(task.run_trial(task.start_genome(), trial, s));  // an error: the script was refused
    const double ball_distance_m = figures_of<KickFigures>(s).ball_distance_m;
    std::printf("  trial %d: fell %d, ball %.3f m\n", trial, s.fell ? 1 : 0, ball_distance_m);
    moved += !s.fell && ball_distance_m > 0.05 ? 1 : 0;
    if (!s.fell) {
      EXPECT_NEAR(s.objectives[1], 1.0 / std::clamp(ball_distance_m, 0.001, 10.0), 1e-12);
    }
  }
  EXPECT_GE(moved, c.trials - 1);
}

}  // namespace
}  // namespace stride::opt
