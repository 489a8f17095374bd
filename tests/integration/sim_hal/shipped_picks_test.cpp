// The optimised parameter files shipped in firmware/config (issue 32 point 4; where each comes
// from and its validation table: optimiser/RESULTS.md "Results in the faithful world") walk and
// kick in the default world as their runs found, through `stride sim --params` as a user would
// run them: walk-fast.json to 2.5 m in well under Ind_O's 19 s, walk-most-stable.json with a
// lower peak acceleration than Ind_O on the same seed, walk-fast-steady.json both at once (the
// seed's headline), walk-omnidirectional.json faster than Ind_O forward, backward and turning,
// kick-right-far.json at least twice
// Ind_O's distance with less sway. Noise on, seeds 1-3; deterministic, so the margins below
// are under the measured figures (in the comments).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

namespace stride {
namespace {

const std::string kConfig = STRIDE_SOURCE_DIR "/firmware/config/";

nlohmann::json stride_sim(const std::string& args) {
  const std::string command = std::string(STRIDE_BIN_DIR) + "/stride sim " + args + " --json";
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (pipe != nullptr && std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = pipe != nullptr ? pclose(pipe) : -1;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command << "\n" << out;
  return nlohmann::json::parse(out, nullptr, false);
}

double time_to_goal(const nlohmann::json& r) {
  return r.at("time_to_goal_s").is_number() ? r.at("time_to_goal_s").get<double>() : 1e9;
}

TEST(ShippedPicks, WalkFastReachesTheGoalInWellUnderIndOsTime) {
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string s = " --seed " + std::to_string(seed);
    const nlohmann::json r =
        stride_sim("walk --vx 1 --duration 20 --params " + kConfig + "walk-fast.json" + s);
    ASSERT_TRUE(r.is_object());
    EXPECT_FALSE(r.at("fell").get<bool>()) << "seed " << seed;
    EXPECT_LT(time_to_goal(r), 11.5) << "seed " << seed;  // 10.1-10.4 s; Ind_O 19.1-19.2 s
    const nlohmann::json mujoco = stride_sim("walk --vx 1 --duration 20 --engine mujoco --params " +
                                             kConfig + "walk-fast.json" + s);
    EXPECT_FALSE(mujoco.at("fell").get<bool>()) << "MuJoCo, seed " << seed;
    EXPECT_LT(time_to_goal(mujoco), 11.5) << "MuJoCo, seed " << seed;  // 8.6-8.7 s
  }
}

TEST(ShippedPicks, WalkMostStableShakesLessThanIndO) {
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string s = " --seed " + std::to_string(seed);
    const nlohmann::json ind_o = stride_sim("walk --vx 1 --duration 20" + s);
    const nlohmann::json r =
        stride_sim("walk --vx 1 --duration 20 --params " + kConfig + "walk-most-stable.json" + s);
    ASSERT_TRUE(r.is_object() && ind_o.is_object());
    EXPECT_FALSE(r.at("fell").get<bool>()) << "seed " << seed;
    EXPECT_LT(time_to_goal(r), time_to_goal(ind_o)) << "seed " << seed;  // 14.1-14.4 s; 19.1-19.2
    // Peak |a| over 20 s: 13.35-13.58 m/s^2 against Ind_O's 21.2-22.8.
    EXPECT_LT(r.at("max_accel").get<double>(), 0.7 * ind_o.at("max_accel").get<double>())
        << "seed " << seed;
  }
}

// The seed's headline on the faithful robot: at least 30 % faster and 40 % more stable than
// Ind_O in the run's world (noise off: 12.63 s against 19.11 s, peak |a| 12.54 against 21.52).
// With the noise on here: 12.7 s against 19.1-19.2 s, 12.9-14.1 m/s^2 against 21.2-22.8; on
// MuJoCo 11.35 s, 14.0 m/s^2 (seed 1).
TEST(ShippedPicks, WalkFastSteadyIsFasterAndSteadierThanIndO) {
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string s = " --seed " + std::to_string(seed);
    const nlohmann::json ind_o = stride_sim("walk --vx 1 --duration 20" + s);
    const nlohmann::json r =
        stride_sim("walk --vx 1 --duration 20 --params " + kConfig + "walk-fast-steady.json" + s);
    ASSERT_TRUE(r.is_object() && ind_o.is_object());
    EXPECT_FALSE(r.at("fell").get<bool>()) << "seed " << seed;
    EXPECT_LT(time_to_goal(r), 0.7 * time_to_goal(ind_o)) << "seed " << seed;
    EXPECT_LT(r.at("max_accel").get<double>(), 0.7 * ind_o.at("max_accel").get<double>())
        << "seed " << seed;
  }
  const nlohmann::json mujoco = stride_sim("walk --vx 1 --duration 20 --engine mujoco --params " +
                                           kConfig + "walk-fast-steady.json --seed 1");
  EXPECT_FALSE(mujoco.at("fell").get<bool>());
  EXPECT_LT(time_to_goal(mujoco), 12.5);  // 11.35 s
}

TEST(ShippedPicks, KickRightFarKicksTwiceAsFarAsIndOWithLessSway) {
  for (int seed = 1; seed <= 3; ++seed) {
    const std::string s = " --seed " + std::to_string(seed);
    const nlohmann::json ind_o = stride_sim("kick" + s);
    const nlohmann::json r = stride_sim("kick --params " + kConfig + "kick-right-far.json" + s);
    ASSERT_TRUE(r.is_object() && ind_o.is_object());
    EXPECT_FALSE(r.at("fell").get<bool>()) << "seed " << seed;
    // 4.9 m against 1.58 m; sway 2.84 against 3.92-3.98 m/s^2.
    EXPECT_GT(r.at("ball_distance_m").get<double>(),
              2.0 * ind_o.at("ball_distance_m").get<double>())
        << "seed " << seed;
    EXPECT_LT(r.at("max_fps").get<double>(), ind_o.at("max_fps").get<double>()) << "seed " << seed;
  }
}

// The speed-ramp run's knee (walk-ramp.json at the seed's budget, front/007; it holds a speed in
// every direction in every validation world): over 20 s from standing at full command it walks
// forward 0.32 m/s (Ind_O 0.13), backward 0.11 (0.024), turns 0.22-0.25 rad/s (0.15) and
// sideways 0.013 m/s as Ind_O (its sideways limit stayed at Ind_O's 0.01 m/step), without a
// fall in any direction (seeds 1-2 here).
TEST(ShippedPicks, WalkOmnidirectionalOutpacesIndOForwardBackwardAndTurning) {
  struct Direction {
    const char* args;
    const char* measure;  // the JSON field of the direction's displacement
    double sign;
    double times_ind_o;  // at least this multiple of Ind_O's
  };
  const Direction directions[] = {
      {"--vx 1", "distance_m", 1.0, 2.0},  {"--vx -1", "distance_m", -1.0, 3.0},
      {"--vy 1", "lateral_m", 1.0, 0.8},   {"--vy -1", "lateral_m", -1.0, 0.8},
      {"--vth 1", "turned_rad", 1.0, 1.3}, {"--vth -1", "turned_rad", -1.0, 1.3}};
  for (const Direction& d : directions) {
    const nlohmann::json ind_o = stride_sim(std::string("walk --duration 20 ") + d.args);
    ASSERT_TRUE(ind_o.is_object());
    const double ind_o_way = d.sign * ind_o.at(d.measure).get<double>();
    EXPECT_GT(ind_o_way, 0.0) << d.args;
    for (int seed = 1; seed <= 2; ++seed) {
      const nlohmann::json r =
          stride_sim(std::string("walk --duration 20 ") + d.args + " --seed " +
                     std::to_string(seed) + " --params " + kConfig + "walk-omnidirectional.json");
      ASSERT_TRUE(r.is_object());
      EXPECT_FALSE(r.at("fell").get<bool>()) << d.args << ", seed " << seed;
      EXPECT_GT(d.sign * r.at(d.measure).get<double>(), d.times_ind_o * ind_o_way)
          << d.args << ", seed " << seed;
    }
  }
}

// The resampled speed-ramp run's fastest (issue 41: walk-ramp.json with speed levels, 66 genes,
// resample, ground randomisation hard..soft; optimiser/RESULTS.md): on the soft ground, seed
// 1, it walks backward 0.21 m/s and turns 0.83 rad/s without a fall, where the hand-set
// stepping-turf-omni.json falls in both and walk-omnidirectional.json walks 0.12 m/s and turns
// 0.19 rad/s (tests/bench/RESULTS.md, "Every shipped walk file on each ground").
TEST(ShippedPicks, WalkOmniRobustWalksBackwardAndTurnsOnSoftGroundWhereTheHandSetFileFalls) {
  const std::string soft = "walk --duration 20 --contact soft --seed 1 --params " + kConfig;
  for (const char* args : {" --vx -1", " --vth 1"}) {
    const nlohmann::json robust = stride_sim(soft + "walk-omni-robust.json" + args);
    const nlohmann::json slow = stride_sim(soft + "walk-omnidirectional.json" + args);
    const nlohmann::json hand_set = stride_sim(soft + "stepping-turf-omni.json" + args);
    ASSERT_TRUE(robust.is_object() && slow.is_object() && hand_set.is_object());
    EXPECT_FALSE(robust.at("fell").get<bool>()) << args;
    EXPECT_TRUE(hand_set.at("fell").get<bool>()) << args;
    const bool turning = std::string(args) == " --vth 1";
    const char* measure = turning ? "turned_rad" : "distance_m";
    const double sign = turning ? 1.0 : -1.0;
    // Backward 1.7x, turning 4.4x walk-omnidirectional.json's (measured with 3 seeds).
    EXPECT_GT(sign * robust.at(measure).get<double>(),
              (turning ? 3.0 : 1.3) * sign * slow.at(measure).get<double>())
        << args;
  }
}

// Its sideways velocity limits (+-0.06 m/step, raised by hand from the run's +-0.01, which the
// ramp's first sideways level could not pass): it steps sideways on the soft ground without a
// fall, 1.62 m left and 1.63 m right in 20 s (seed 1), where walk-omnidirectional.json moves
// 0.19 and 0.11 m. At 0.09 m/step MuJoCo fell stepping right on two robot variants
// (tests/bench/RESULTS.md).
TEST(ShippedPicks, WalkOmniRobustStepsSidewaysOnSoftGround) {
  const std::string soft = "walk --duration 20 --contact soft --seed 1 --params " + kConfig;
  for (const double side : {1.0, -1.0}) {
    const std::string args = side > 0 ? " --vy 1" : " --vy -1";
    const nlohmann::json robust = stride_sim(soft + "walk-omni-robust.json" + args);
    const nlohmann::json slow = stride_sim(soft + "walk-omnidirectional.json" + args);
    ASSERT_TRUE(robust.is_object() && slow.is_object());
    EXPECT_FALSE(robust.at("fell").get<bool>()) << args;
    EXPECT_GT(side * robust.at("lateral_m").get<double>(), 1.4) << args;
    EXPECT_GT(side * robust.at("lateral_m").get<double>(),
              4.0 * side * slow.at("lateral_m").get<double>())
        << args;
  }
}

}  // namespace
}  // namespace stride
