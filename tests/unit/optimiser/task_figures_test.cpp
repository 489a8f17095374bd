// TaskFigures: a task's own figures held by type in EpisodeScore (task_figures.hpp), merged over
// a world's episodes and shown (outcome notes, validation figures) by the task types.
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "stride/optimiser/tasks/direction_figures.hpp"
#include "stride/optimiser/tasks/episode_score.hpp"
#include "stride/optimiser/tasks/getup_figures.hpp"
#include "stride/optimiser/tasks/kick_figures.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/optimiser/tasks/walk_figures.hpp"

namespace stride::opt {
namespace {

TEST(TaskFigures, HoldsOneTasksStructByType) {
  TaskFigures figures;
  EXPECT_TRUE(figures.empty());
  EXPECT_EQ(figures.find<WalkFigures>(), nullptr);
  figures.as<WalkFigures>().time_to_goal_s = 12.5;
  ASSERT_NE(figures.find<WalkFigures>(), nullptr);
  EXPECT_EQ(figures.get<WalkFigures>().time_to_goal_s, 12.5);
  EXPECT_EQ(figures.find<KickFigures>(), nullptr);  // not another task's
  EXPECT_FALSE(figures.empty());
}

TEST(TaskFigures, ReadGivesTheDefaultsOfNoFigures) {
  TaskFigures figures;
  EXPECT_EQ(figures.read<GetUpFigures>().stand_time_s, -1.0);
  figures.as<KickFigures>().ball_distance_m = 0.7;
  EXPECT_EQ(figures.read<KickFigures>().ball_distance_m, 0.7);
  figures.set(GetUpFigures{});  // set replaces them whatever they were
  EXPECT_EQ(figures.get<GetUpFigures>().stood, 0);
  EXPECT_EQ(figures.find<KickFigures>(), nullptr);
}

TEST(TaskFigures, AnotherTasksFiguresAreAnErrorNamingBothTypes) {
  TaskFigures figures;
  try {
    (void)figures.get<WalkFigures>();
    ADD_FAILURE() << "get<T>() of no figures returned";
  } catch (const TaskValueTypeError& e) {
    EXPECT_STREQ(e.what(), "task figures: expected stride::opt::WalkFigures, holds none");
  }
  figures.as<KickFigures>().ball_distance_m = 0.7;
  for (const auto& wrong : std::vector<std::function<void()>>{
           [&] { (void)figures.get<WalkFigures>(); }, [&] { (void)figures.read<WalkFigures>(); },
           [&] { (void)figures.as<WalkFigures>(); }}) {
    try {
      wrong();
      ADD_FAILURE() << "another task's figures read as a WalkFigures";
    } catch (const TaskValueTypeError& e) {
      EXPECT_STREQ(e.what(),
                   "task figures: expected stride::opt::WalkFigures, holds "
                   "stride::opt::KickFigures");
    }
  }
  EXPECT_EQ(figures.get<KickFigures>().ball_distance_m, 0.7);  // unchanged
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

TEST(TaskFigures, TheGetUpMergesItsEpisodesIntoTheWorlds) {
  const TaskType& getup = *find_task_type("getup");
  TaskFigures total, next;
  total.as<GetUpFigures>() = {2.0, 1, 1};
  next.as<GetUpFigures>() = {3.0, 1, 2};
  getup.merge_figures(next, 2, total);
  EXPECT_EQ(total.read<GetUpFigures>().stand_time_s, 2.5);  // the mean of the two
  EXPECT_EQ(total.read<GetUpFigures>().stood, 2);
  EXPECT_EQ(total.read<GetUpFigures>().get_up_attempts, 3);
  next.as<GetUpFigures>() = {-1.0, 0, 4};  // one that did not stand: no mean time
  getup.merge_figures(next, 3, total);
  EXPECT_EQ(total.read<GetUpFigures>().stand_time_s, -1.0);
  EXPECT_EQ(total.read<GetUpFigures>().stood, 2);
  EXPECT_EQ(total.read<GetUpFigures>().get_up_attempts, 7);
}

TEST(TaskFigures, TheRampFillsEachDirectionFromItsOwnEpisode) {
  const TaskType& ramp = *find_task_type("walk-ramp");
  TaskFigures total, next;
  total.as<DirectionFigures>().segments[0] = {true, 0.2, 0.01, 0.0, 0.0};
  total.as<DirectionFigures>().distance_m = 1.5;
  next.as<DirectionFigures>().segments[1] = {true, 0.1, 0.02, 0.0, 0.0};
  next.as<DirectionFigures>().distance_m = -0.5;
  ramp.merge_figures(next, 2, total);
  const DirectionFigures merged = total.read<DirectionFigures>();
  EXPECT_EQ(merged.segments[0].speed, 0.2);  // the first episode's direction stays
  EXPECT_EQ(merged.segments[1].speed, 0.1);
  EXPECT_TRUE(merged.segments[1].measured);
  EXPECT_FALSE(merged.segments[2].measured);
  EXPECT_EQ(merged.distance_m, 1.5);  // the first episode's, for the report's note
}

TEST(TaskFigures, DirectionTasksGiveTheValidationTheMeanSpeedPerDirection) {
  EpisodeScore a, b;
  a.figures.as<DirectionFigures>().segments[0].speed = 0.2;
  b.figures.as<DirectionFigures>().segments[0].speed = 0.4;
  b.figures.as<DirectionFigures>().segments[5].speed = 1.0;
  for (const char* task : {"walk-omni", "walk-ramp"}) {
    const ValidationFigures v = find_task_type(task)->validation_figures({&a, &b});
    EXPECT_DOUBLE_EQ(v.cell["speeds"]["forward"].get<double>(), 0.3) << task;
    EXPECT_DOUBLE_EQ(v.cell["speeds"]["turn_right"].get<double>(), 0.5) << task;
    EXPECT_EQ(v.cell["speeds"].size(), 6u) << task;
    EXPECT_DOUBLE_EQ(v.table_row["forward"].get<double>(), 0.3) << task;
    EXPECT_EQ(v.table_row.size(), 6u) << task;
  }
  const ValidationFigures walk = find_task_type("walk")->validation_figures({&a, &b});
  EXPECT_TRUE(walk.cell.empty());
  EXPECT_TRUE(walk.table_row.empty());
}

TEST(TaskFigures, TheOutcomeNotesComeFromEachTasksFigures) {
  const TaskConfig config;
  EpisodeScore s;
  s.figures.as<DirectionFigures>().distance_m = 1.234;
  EXPECT_EQ(find_task_type("walk-omni")->outcome_note(config, s, 20.0),
            "1.23 m in 20 s, goal not reached");
  s.figures = {};
  s.figures.as<KickFigures>().ball_distance_m = 0.75;
  EXPECT_EQ(find_task_type("kick")->outcome_note(config, s, 3.0), "ball kicked 0.75 m");
  s.fell = true;
  EXPECT_EQ(find_task_type("kick")->outcome_note(config, s, 1.5), "fell at 1.50 s");
  s.figures.set(GetUpFigures{.stood = 1});
  EXPECT_EQ(find_task_type("getup")->outcome_note(config, s, 9.0), "stood up in 1 of 2 episodes");
}

}  // namespace
}  // namespace stride::opt
