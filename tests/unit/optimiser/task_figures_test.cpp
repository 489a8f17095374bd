// TaskFigures: a task's own figures held by type in EpisodeScore (task_figures.hpp).
#include <gtest/gtest.h>

#include "stride/optimiser/tasks/episode_score.hpp"
#include "stride/optimiser/tasks/getup_figures.hpp"
#include "stride/optimiser/tasks/kick_figures.hpp"
#include "stride/optimiser/tasks/walk_figures.hpp"

namespace stride::opt {
namespace {

TEST(TaskFigures, HoldsOneTasksStructByType) {
  TaskFigures figures;
  EXPECT_TRUE(figures.empty());
  EXPECT_EQ(figures.get<WalkFigures>(), nullptr);
  figures.as<WalkFigures>().time_to_goal_s = 12.5;
  ASSERT_NE(figures.get<WalkFigures>(), nullptr);
  EXPECT_EQ(figures.get<WalkFigures>()->time_to_goal_s, 12.5);
  EXPECT_EQ(figures.get<KickFigures>(), nullptr);  // not another task's
  EXPECT_FALSE(figures.empty());
}

TEST(TaskFigures, ReadGivesTheDefaultsOfAnotherTasksFigures) {
  TaskFigures figures;
  EXPECT_EQ(figures.read<GetUpFigures>().stand_time_s, -1.0);
  figures.as<KickFigures>().ball_distance_m = 0.7;
  EXPECT_EQ(figures.read<KickFigures>().ball_distance_m, 0.7);
  EXPECT_EQ(figures.read<WalkFigures>().time_to_goal_s, -1.0);
  // as<T>() over another task's figures starts from T's defaults.
  EXPECT_EQ(figures.as<GetUpFigures>().stood, 0);
  EXPECT_EQ(figures.get<KickFigures>(), nullptr);
}

TEST(TaskFigures, CopiesWithTheScore) {
  EpisodeScore a;
  a.figures.as<GetUpFigures>().stood = 2;
  EpisodeScore b = a;
  a.figures.as<GetUpFigures>().stood = 1;
  EXPECT_EQ(b.figures.read<GetUpFigures>().stood, 2);
  EpisodeScore c = std::move(b);
  EXPECT_EQ(c.figures.read<GetUpFigures>().stood, 2);
}

}  // namespace
}  // namespace stride::opt
