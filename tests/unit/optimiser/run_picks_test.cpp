// run_picks: which front rows a run's picks are and in what order they are chosen. A run
// without fresh-world scores picks by its own objectives; a resampling run picks only among
// the rows feasible on the fresh worlds and not dominated there, and by those fresh scores,
// so a row that was best in the run but is beaten or infeasible on fresh worlds is not picked.
#include "stride/optimiser/report/run_data.hpp"

#include <gtest/gtest.h>

namespace stride::opt::report {
namespace {

FrontMember row(std::vector<double> objectives, std::vector<double> rescored = {},
                bool feasible = false) {
  FrontMember m;
  m.objectives = std::move(objectives);
  m.genes = {0.0};
  m.rescored = std::move(rescored);
  m.rescored_feasible = feasible;
  return m;
}

RunData walk_run(std::vector<FrontMember> front) {
  RunData data;
  data.task = "walk";
  data.front = std::move(front);
  return data;
}

const RunPick* pick(const std::vector<RunPick>& picks, const std::string& key) {
  for (const RunPick& p : picks)
    for (const std::string& k : p.keys)
      if (k == key) return &p;
  return nullptr;
}

TEST(RunPicks, WithoutFreshScoresTheRunsObjectivesChoose) {
  const RunData data = walk_run({row({10, 20}), row({12, 15}), row({20, 11})});
  const auto picks = run_picks(data);
  ASSERT_NE(pick(picks, "fastest"), nullptr);
  EXPECT_EQ(pick(picks, "fastest")->front_index, 0u);
  EXPECT_EQ(pick(picks, "most_stable")->front_index, 2u);
  EXPECT_EQ(pick(picks, "knee")->front_index, 1u);
  EXPECT_EQ(pick(picks, "fastest")->file, "front/000.json");
}

TEST(RunPicks, FreshScoresChooseAndTheirOrderDecides) {
  // Row 0 was the fastest in the run but is the slowest of the feasible rows on fresh worlds;
  // row 1 is the fastest there; row 3 is fastest and steadiest there but infeasible; row 4 is
  // dominated on fresh worlds by row 2.
  const RunData data = walk_run({row({8, 20}, {14, 16}, true), row({9, 19}, {11, 18}, true),
                                 row({11, 12}, {12, 12}, true), row({7, 10}, {9, 9}, false),
                                 row({10, 13}, {13, 13}, true)});
  const auto picks = run_picks(data);
  ASSERT_NE(pick(picks, "fastest"), nullptr);
  EXPECT_EQ(pick(picks, "fastest")->front_index, 1u);
  EXPECT_EQ(pick(picks, "most_stable")->front_index, 2u);
  for (const RunPick& p : picks) {
    EXPECT_NE(p.front_index, 3u) << "infeasible on the fresh worlds";
    EXPECT_NE(p.front_index, 4u) << "dominated on the fresh worlds";
  }
  EXPECT_EQ(pick(picks, "fastest")->rescored, (std::vector<double>{11, 18}));
  EXPECT_EQ(pick(picks, "fastest")->objectives, (std::vector<double>{9, 19}));
}

TEST(RunPicks, WhenNoRowIsFeasibleOnFreshWorldsTheRunsScoresChoose) {
  const RunData data = walk_run({row({8, 20}, {30, 30}, false), row({12, 11}, {9, 9}, false)});
  const auto picks = run_picks(data);
  EXPECT_EQ(pick(picks, "fastest")->front_index, 0u);
  EXPECT_EQ(pick(picks, "most_stable")->front_index, 1u);
}

TEST(RunPicks, ARowPickedForSeveralReasonsAppearsOnceNamingEach) {
  const RunData data = walk_run({row({8, 9}), row({12, 15})});
  const auto picks = run_picks(data);
  ASSERT_EQ(picks.size(), 1u);
  EXPECT_EQ(picks[0].front_index, 0u);
  EXPECT_EQ(picks[0].label, "fastest, most stable, knee");
}

}  // namespace
}  // namespace stride::opt::report
