// Validation summaries from known episode scores: the median, what counts as reached per task,
// the gate (80 % reached, median within 25 % of the run's own value), gain kept only where
// Ind_O passes, a failed world as a fall with its reason, an unavailable world; the gain kept
// as the tables show it (two significant digits, hidden within the seeds' spread).
#include <gtest/gtest.h>

#include <cmath>

#include "stride/optimiser/report/html_tables.hpp"
#include "stride/optimiser/run/validation_summary.hpp"
#include "stride/optimiser/tasks/direction_figures.hpp"
#include "stride/optimiser/tasks/kick_figures.hpp"
#include "stride/optimiser/tasks/walk_figures.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

using nlohmann::json;

EpisodeOutcome walked(double time_s, double max_accel, bool reached) {
  EpisodeOutcome e;
  e.score.objectives = {time_s, max_accel};
  e.score.figures.as<WalkFigures>().time_to_goal_s = reached ? time_s : -1.0;
  e.score.fell = !reached;
  return e;
}

std::vector<EpisodeOutcome> seeds(int reached, double time_s, double accel, int fallen,
                                  double fall_time_s, double fall_accel) {
  std::vector<EpisodeOutcome> out;
  for (int i = 0; i < reached; ++i) out.push_back(walked(time_s, accel, true));
  for (int i = 0; i < fallen; ++i) out.push_back(walked(fall_time_s, fall_accel, false));
  return out;
}

TEST(ValidationSummary, MedianReachedAndGateObjective) {
  EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);
  EXPECT_TRUE(std::isnan(median({})));
  TaskConfig walk, kick, omni;
  walk.task = "walk";
  kick.task = "kick";
  omni.task = "walk-omni";
  EpisodeScore s;
  s.figures.as<WalkFigures>().time_to_goal_s = 12.0;
  EXPECT_TRUE(validation_reached(walk, s));
  s.world_failure = "exploding state";
  EXPECT_FALSE(validation_reached(walk, s));
  s = {};
  s.figures.as<KickFigures>().ball_distance_m = 0.49;
  EXPECT_FALSE(validation_reached(kick, s));
  s.figures.as<KickFigures>().ball_distance_m = 0.5;
  EXPECT_TRUE(validation_reached(kick, s));
  s = {};
  EXPECT_FALSE(validation_reached(omni, s));  // no segment measured
  for (auto& seg : s.figures.as<DirectionFigures>().segments) seg.measured = true;
  EXPECT_TRUE(validation_reached(omni, s));
  EXPECT_EQ(gate_objective(walk), 0);
  EXPECT_EQ(gate_objective(kick), 1);  // 1 / ball distance
}

TEST(ValidationSummary, GateAndGainKeptFollowTheMediansOfEachWorld) {
  TaskConfig config;
  config.task = "walk";
  std::vector<ValidationIndividual> individuals(2);
  individuals[0].name = "Ind_O";
  individuals[0].run_objectives = {20.0, 20.0};
  individuals[1].name = "fastest";
  individuals[1].file = "front/000.json";
  individuals[1].run_objectives = {10.0, 15.0};
  std::vector<ValidationWorld> worlds(3);
  worlds[0].name = "good";
  worlds[1].name = "hard";
  worlds[2].name = "engine mujoco";
  for (auto& w : worlds)
    for (std::uint64_t s = 0; s < 10; ++s) w.seeds.push_back(1001 + s);
  std::vector<std::vector<std::vector<EpisodeOutcome>>> outcomes(2);
  // good: Ind_O reaches 10/10 in 22 s (limit 25 s: pass); the pick 8/10 in 12 s, 2 falls
  // (limit 12.5 s: pass). hard: Ind_O reaches 7/10 (fails the gate): no gain kept.
  outcomes[0] = {seeds(10, 22.0, 21.0, 0, 0, 0), seeds(7, 24.0, 22.0, 3, 60.0, 30.0), {}};
  outcomes[1] = {seeds(8, 12.0, 14.0, 2, 50.0, 30.0), seeds(10, 11.0, 14.0, 0, 0, 0), {}};
  outcomes[1][0][9].score.world_failure = "exploding state: |u[3]| = 250 > 200";
  // The third world could not be built (an engine missing from this build).
  for (auto& ind : outcomes) {
    ind[2].resize(10);
    for (auto& e : ind[2]) e.setup_error = "MuJoCo is not in this build";
  }
  const json v = summarise_validation("run", config, individuals, worlds, outcomes);
  const json& ind_o = v["individuals"][0]["worlds"];
  const json& pick = v["individuals"][1]["worlds"];
  EXPECT_TRUE(ind_o[0]["gate"]["passed"].get<bool>());
  EXPECT_DOUBLE_EQ(ind_o[0]["gate"]["limit"].get<double>(), 25.0);
  EXPECT_TRUE(ind_o[0]["gain_kept"].is_null());  // Ind_O has no gain of its own
  EXPECT_EQ(pick[0]["reached"], 8);
  EXPECT_EQ(pick[0]["falls"], 2);
  EXPECT_DOUBLE_EQ(pick[0]["median_objectives"][0].get<double>(), 12.0);
  EXPECT_DOUBLE_EQ(pick[0]["gate"]["limit"].get<double>(), 12.5);
  EXPECT_TRUE(pick[0]["gate"]["passed"].get<bool>());
  // (22 - 12) / (20 - 10) and (21 - 14) / (20 - 15).
  EXPECT_DOUBLE_EQ(pick[0]["gain_kept"][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(pick[0]["gain_kept"][1].get<double>(), 1.4);
  ASSERT_EQ(pick[0]["failures"].size(), 1u);
  EXPECT_EQ(pick[0]["failures"][0]["seed"], 1010);
  EXPECT_EQ(pick[0]["failures"][0]["reason"], "exploding state: |u[3]| = 250 > 200");
  EXPECT_FALSE(ind_o[1]["gate"]["passed"].get<bool>());  // 7 of 10
  EXPECT_TRUE(pick[1]["gate"]["passed"].get<bool>());
  EXPECT_TRUE(pick[1]["gain_kept"].is_null());  // Ind_O failed the gate there
  EXPECT_EQ(pick[2]["unavailable"], "MuJoCo is not in this build");
  EXPECT_EQ(v["worlds"][2]["unavailable"], "MuJoCo is not in this build");
  EXPECT_FALSE(v["all_passed"].get<bool>());
  ASSERT_EQ(v["table"].size(), 6u);
  EXPECT_EQ(v["table"][3]["individual"], "fastest");
  EXPECT_EQ(v["table"][3]["gate"], "pass");
  EXPECT_DOUBLE_EQ(v["table"][3]["gain_kept_f2"].get<double>(), 1.4);
  EXPECT_EQ(v["table"][5]["gate"], "unavailable");
  const std::string text = validation_text(v);
  EXPECT_NE(text.find("UNAVAILABLE, MuJoCo is not in this build"), std::string::npos) << text;
  EXPECT_NE(text.find("fastest"), std::string::npos);
  // In words: where each holds, why Ind_O fails "hard", the untested world, the best pick.
  EXPECT_NE(text.find("  Ind_O: holds in good (reaches the goal in 10 of 10 seeds); fails in "
                      "hard (falls in 3 of 10 seeds); not tested on MuJoCo (MuJoCo is not in "
                      "this build)\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  fastest: holds in every world tested (reaches the goal in 18 of 20 "
                      "seeds); not tested on MuJoCo"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("the pick that holds in most worlds: fastest (2 of 2 worlds), "
                      "front/000.json\n"),
            std::string::npos)
      << text;
}

TEST(ValidationSummary, GainKeptHasTwoSignificantDigits) {
  EXPECT_EQ(two_significant_digits(json(7.5556)), "7.6");
  EXPECT_EQ(two_significant_digits(json(3.8889)), "3.9");
  EXPECT_EQ(two_significant_digits(json(-0.66667)), "-0.67");
  EXPECT_EQ(two_significant_digits(json(0.96)), "0.96");
  EXPECT_EQ(two_significant_digits(json(1.0)), "1.0");
  EXPECT_EQ(two_significant_digits(json(9.96)), "10");
  EXPECT_EQ(two_significant_digits(json(123.4)), "120");
  EXPECT_EQ(two_significant_digits(json(0.012345)), "0.012");
  EXPECT_EQ(two_significant_digits(json(0.0)), "0");
  EXPECT_EQ(two_significant_digits(json(nullptr)), "-");
}

// The demo's knee gained 0.5 % in peak |a| in the run; on fresh seeds that gain is far inside
// the seeds' spread, so its ratio (7.5556 in the old table) is noise and is not shown. The time
// gain is well outside the spread and is shown to two significant digits. validation.json
// keeps the ratios as numbers either way.
TEST(ValidationSummary, GainKeptIsShownOnlyWhereTheRunsGainExceedsTheSeedsSpread) {
  TaskConfig config;
  config.task = "walk";
  std::vector<ValidationIndividual> individuals(2);
  individuals[0].name = "Ind_O";
  individuals[0].run_objectives = {20.0, 20.0};
  individuals[1].name = "knee";
  individuals[1].file = "front/003.json";
  individuals[1].run_objectives = {10.0, 19.9};  // gains: 10 s and 0.1 m/s^2
  std::vector<ValidationWorld> worlds(1);
  worlds[0].name = "fresh seeds";
  worlds[0].seeds = {1001, 1002, 1003};
  std::vector<std::vector<std::vector<EpisodeOutcome>>> outcomes(2);
  // Ind_O: times 21, 22, 23 s (interquartile range 1 s), peaks 20, 21, 22 (range 1).
  outcomes[0] = {{walked(21.0, 20.0, true), walked(22.0, 21.0, true), walked(23.0, 22.0, true)}};
  // knee: 14.4 s and a peak of 19 on every seed (spread 0).
  outcomes[1] = {{walked(14.4, 19.0, true), walked(14.4, 19.0, true), walked(14.4, 19.0, true)}};
  const json v = summarise_validation("run", config, individuals, worlds, outcomes);
  const json& cell = v["individuals"][1]["worlds"][0];
  // The numbers stay in validation.json: (22 - 14.4) / 10 and (21 - 19) / 0.1.
  EXPECT_NEAR(cell["gain_kept"][0].get<double>(), 0.76, 1e-12);
  EXPECT_NEAR(cell["gain_kept"][1].get<double>(), 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(v["individuals"][0]["worlds"][0]["seed_spread"][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(cell["seed_spread"][1].get<double>(), 0.0);
  const json& row = v["table"][1];
  EXPECT_NEAR(row["run_gain_f1"].get<double>(), 10.0, 1e-12);
  EXPECT_DOUBLE_EQ(row["seed_spread_f1"].get<double>(), 1.0);  // the larger of the two
  EXPECT_DOUBLE_EQ(row["seed_spread_f2"].get<double>(), 1.0);
  EXPECT_EQ(gain_kept_text(row, 0), "0.76");
  EXPECT_EQ(gain_kept_text(row, 1), "-");            // 0.1 is within the spread of 1
  EXPECT_EQ(gain_kept_text(v["table"][0], 0), "-");  // Ind_O has no gain of its own
  // A row from before the spread was written shows its number, to two digits.
  EXPECT_EQ(gain_kept_text(json{{"gain_kept_f1", 7.5556}}, 0), "7.6");
  // The text table and the report's HTML table show the same.
  const std::string text = validation_text(v);
  EXPECT_NE(text.find("0.76        -\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("0.7600"), std::string::npos) << text;
  EXPECT_EQ(text.find("20.00"), std::string::npos) << text;
  test::TempDir tmp;
  const std::string html = report::validation_table_html(tmp.write("validation.json", v.dump()));
  EXPECT_NE(html.find("<td>0.76</td><td>-</td>"), std::string::npos) << html;
  EXPECT_EQ(html.find("seed_spread"), std::string::npos) << html;
  EXPECT_EQ(html.find(">20<"), std::string::npos) << html;
}

TEST(ValidationSummary, WordsSayWhereEachHoldsAndWhyItFailsAndWhatFailMeans) {
  TaskConfig config;
  config.task = "walk";
  std::vector<ValidationIndividual> individuals(3);
  individuals[0].name = "Ind_O";
  individuals[0].run_objectives = {20.0, 20.0};
  individuals[1].name = "fastest";
  individuals[1].file = "front/002.json";
  individuals[1].run_objectives = {10.0, 18.0};
  individuals[2].name = "knee";
  individuals[2].file = "front/005.json";
  individuals[2].run_objectives = {12.0, 16.0};
  std::vector<ValidationWorld> worlds(3);
  worlds[0].name = "engine mujoco";
  worlds[1].name = "fresh seeds";
  worlds[2].name = "half step";
  for (auto& w : worlds) w.seeds = {1001, 1002, 1003};
  auto ran_out_of_time = [] {
    EpisodeOutcome e;
    e.score.objectives = {30.0, 15.0};
    e.score.figures.as<WalkFigures>().time_to_goal_s = -1.0;
    return e;
  };
  std::vector<std::vector<std::vector<EpisodeOutcome>>> outcomes(3);
  // Ind_O: 26 s on MuJoCo (30 % slower than its 20 s: fails), holds on fresh seeds, falls in
  // all three at half the step.
  outcomes[0] = {seeds(3, 26.0, 20.0, 0, 0, 0), seeds(3, 20.0, 20.0, 0, 0, 0),
                 seeds(0, 0, 0, 3, 60.0, 30.0)};
  // fastest: runs out of time in 2 of 3 on MuJoCo, holds on fresh seeds, one fall and one
  // miss at half the step.
  outcomes[1] = {seeds(1, 10.0, 18.0, 0, 0, 0), seeds(3, 10.0, 18.0, 0, 0, 0),
                 seeds(1, 10.0, 18.0, 1, 60.0, 30.0)};
  outcomes[1][0].push_back(ran_out_of_time());
  outcomes[1][0].push_back(ran_out_of_time());
  outcomes[1][2].push_back(ran_out_of_time());
  // knee: holds on MuJoCo and on fresh seeds, falls at half the step.
  outcomes[2] = {seeds(3, 12.0, 16.0, 0, 0, 0), seeds(3, 12.0, 16.0, 0, 0, 0),
                 seeds(0, 0, 0, 3, 60.0, 30.0)};
  const json v = summarise_validation("run", config, individuals, worlds, outcomes);
  const std::string words = validation_words(v);
  EXPECT_NE(words.find("  Ind_O: holds on fresh seeds (reaches the goal in 3 of 3 seeds); fails "
                       "on MuJoCo (reaches the goal in 3 of 3 seeds but 30 % slower than in the "
                       "run) and at half the physics step (falls in 3 of 3 seeds)\n"),
            std::string::npos)
      << words;
  EXPECT_NE(words.find("  fastest: holds on fresh seeds (reaches the goal in 3 of 3 seeds); "
                       "fails on MuJoCo (does not reach the goal in time in 2 of 3 seeds) and at "
                       "half the physics step (falls in 1 and does not reach the goal in time in "
                       "1 of 3 seeds)\n"),
            std::string::npos)
      << words;
  EXPECT_NE(words.find("  knee: holds on MuJoCo and on fresh seeds (reaches the goal in 6 of 6 "
                       "seeds); fails at half the physics step (falls in 3 of 3 seeds)\n"),
            std::string::npos)
      << words;
  EXPECT_NE(words.find("  the pick that holds in most worlds: knee (2 of 3 worlds), "
                       "front/005.json\n"),
            std::string::npos)
      << words;
  EXPECT_NE(words.find("pass (holds): at least 80 % of the seeds reach the goal without a fall, "
                       "and the median time to the goal is at most 25 % worse"),
            std::string::npos)
      << words;
  EXPECT_NE(words.find("fail: "), std::string::npos) << words;
  EXPECT_NE(validation_text(v).find(words), std::string::npos);  // the table ends with them
}

TEST(ValidationSummary, WordsNameTheKicksGoalAndMeasure) {
  TaskConfig config;
  config.task = "kick";
  std::vector<ValidationIndividual> individuals(1);
  individuals[0].name = "Ind_O";
  individuals[0].run_objectives = {20.0, 0.5};  // a 2 m kick in the run
  std::vector<ValidationWorld> worlds(1);
  worlds[0].name = "fresh seeds";
  worlds[0].seeds = {1001, 1002, 1003};
  std::vector<std::vector<std::vector<EpisodeOutcome>>> outcomes(1);
  outcomes[0].resize(1);
  for (int s = 0; s < 3; ++s) {
    EpisodeOutcome e;
    e.score.figures.as<KickFigures>().ball_distance_m = 1.0;
    e.score.objectives = {20.0, 1.0};
    outcomes[0][0].push_back(e);
  }
  const std::string words =
      validation_words(summarise_validation("run", config, individuals, worlds, outcomes));
  EXPECT_NE(words.find("  Ind_O: fails on fresh seeds (kicks the ball at least 0.5 m in 3 of 3 "
                       "seeds but its median 1 / ball distance is 100 % worse than in the run)\n"),
            std::string::npos)
      << words;
  EXPECT_NE(words.find("  no pick holds in any world\n"), std::string::npos) << words;
  EXPECT_NE(words.find("the median 1 / ball distance is at most 25 % worse"), std::string::npos)
      << words;
  EXPECT_NE(words.find("the kick does not carry over to it"), std::string::npos) << words;
  EXPECT_EQ(words.find("walk"), std::string::npos) << words;  // a kick run's words
}

}  // namespace
}  // namespace stride::opt
