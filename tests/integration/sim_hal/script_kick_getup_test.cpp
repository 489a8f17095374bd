// Issue 6 point 6 in the simulator: the firmware's KickRight from stand sends the ball at
// least 0.5 m without a fall on 10 seeds; the robot knocked over by a scripted impulse gets up
// in 10 trials on turf, with the get-up script of the side it lies on. Counted with one to
// spare (tests/README.md): issue 6 asked for 10 of 10, which every count here measured.
// Figures (ball distance, max field-plane sway) are printed for the report.
#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "seeds.hpp"
#include "stride/sim_hal/script_episodes.hpp"

namespace stride::sim {
namespace {

WorldOptions world_for_seed(std::uint64_t seed, bool randomise) {
  WorldOptions options;
  options.seed = seed;
  options.imu.set_noise(true);  // as `stride sim --noise on` (the default)
  if (randomise) {
    options.randomise.friction_range = 0.2;
    options.randomise.mass_range = 0.05;
    options.randomise.strength_range = 0.1;
    options.randomise.latency_probability = 0.05;
  }
  return options;
}

struct KickFigures {
  int kicks = 0, good = 0;
  double min_distance = 1e9, max_distance = 0, sum_distance = 0, max_sway = 0, sum_sway = 0;
  void add(const EpisodeResult& r) {
    ++kicks;
    if (!r.fell && r.ball_distance_m >= 0.5) ++good;
    min_distance = std::min(min_distance, r.ball_distance_m);
    max_distance = std::max(max_distance, r.ball_distance_m);
    sum_distance += r.ball_distance_m;
    max_sway = std::max(max_sway, r.max_fps);
    sum_sway += r.max_fps;
  }
  void print(const char* what) const {
    std::printf(
        "%s: %d/%d kicks >= 0.5 m without a fall; ball %.3f..%.3f m (mean %.3f); "
        "max field-plane sway mean %.2f, max %.2f m/s^2\n",
        what, good, kicks, min_distance, max_distance, sum_distance / kicks, sum_sway / kicks,
        max_sway);
  }
};

TEST(SimScripts, KickRightFromStandTenSeeds) {
  KickFigures figures;
  for (std::uint64_t seed = 1; seed <= static_cast<std::uint64_t>(test::seed_count(10)); ++seed) {
    KickEpisodeOptions kick;
    EpisodeResult result;
    const Status status = run_kick_episode(world_for_seed(seed, false), kick, result);
    ASSERT_TRUE(status) << status.message();
    EXPECT_EQ(result.status, WorldStatus::kRunning) << result.failure_reason;
    figures.add(result);
  }
  figures.print("kick_right, 10 seeds (IMU noise)");
  EXPECT_GE(figures.good, figures.kicks - 1);  // seeds 1-20: 20 of 20, ball 1.419 m
}

TEST(SimScripts, KickRightTenRandomisedWorldsAndBallPlacements) {
  // Harder than the seeds alone: friction +-20 %, masses +-5 %, servo strength +-10 %, 5 %
  // chance of one tick of command latency, ball placed +-1 cm / +-1.5 cm around its spot.
  KickFigures figures;
  for (std::uint64_t seed = 1; seed <= static_cast<std::uint64_t>(test::seed_count(10)); ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> dx(-0.01, 0.01), dy(-0.015, 0.015);
    KickEpisodeOptions kick;
    kick.ball_position.x() += dx(rng);
    kick.ball_position.y() += dy(rng);
    EpisodeResult result;
    const Status status = run_kick_episode(world_for_seed(seed, true), kick, result);
    ASSERT_TRUE(status) << status.message();
    figures.add(result);
  }
  figures.print("kick_right, 10 randomised worlds");
  EXPECT_GE(figures.good, figures.kicks - 1);  // worlds 1-20: 20 of 20, ball 1.23-1.59 m
}

// The left kick mirrors the right: seeds 1-5, counted with one to spare. Measured 2026-11-28,
// seeds 1-20: 20 of 20, ball 1.446 m.
TEST(SimScripts, KickLeftMirrorsTheKick) {
  KickFigures figures;
  for (std::uint64_t seed = 1; seed <= static_cast<std::uint64_t>(test::seed_count(5)); ++seed) {
    KickEpisodeOptions kick;
    kick.script = "kick_left";
    kick.ball_position.y() = -kick.ball_position.y();
    EpisodeResult result;
    ASSERT_TRUE(run_kick_episode(world_for_seed(seed, false), kick, result));
    figures.add(result);
  }
  figures.print("kick_left, 5 seeds (IMU noise)");
  EXPECT_GE(figures.good, figures.kicks - 1);
}

TEST(SimScripts, KickIsDeterministicAndAnUnknownScriptIsAnError) {
  EpisodeResult a, b;
  ASSERT_TRUE(run_kick_episode(world_for_seed(7, true), {}, a));
  ASSERT_TRUE(run_kick_episode(world_for_seed(7, true), {}, b));
  EXPECT_EQ(a.state_hash, b.state_hash);
  EXPECT_EQ(a.ball_distance_m, b.ball_distance_m);
  KickEpisodeOptions bad;
  bad.script = "kick_sideways";
  EpisodeResult c;
  const Status status = run_kick_episode(world_for_seed(1, false), bad, c);
  ASSERT_FALSE(status);
  EXPECT_NE(status.message().find("kick_sideways"), std::string::npos);
}

struct PushFigures {
  int trials = 0, knocked_over = 0, got_up = 0, right_script = 0, first_try = 0;
  double slowest_s = 0.0;        // the slowest stand-up of the trials, from the fall [s]
  std::vector<double> up_after;  // per trial: seconds from the fall to standing (1e9: stayed down)
};

/// Ten trials on `engine` in the default world (turf): the robot standing, knocked over by a
/// ball thrown at its chest at 10-14.5 m/s, from behind and from the front in turn, randomised
/// worlds, 20 s each (the time the rules give a fallen robot).
PushFigures push_trials(EngineKind engine) {
  PushFigures f;
  for (int trial = 0; trial < test::seed_count(10); ++trial) {
    PushEpisodeOptions push;
    push.from_behind = trial % 2 == 0;
    push.push_speed = 10.0 + 0.5 * static_cast<double>(trial % 10);
    push.duration_s = 20.0;
    PushEpisodeResult result;
    WorldOptions world = world_for_seed(static_cast<std::uint64_t>(100 + trial), true);
    world.contact = ContactOptions::turf();
    world.engine = engine;
    const Status status = run_push_episode(world, push, result);
    EXPECT_TRUE(status) << status.message();
    const char* expected = push.from_behind ? "get_up_front" : "get_up_back";
    const double from_fall = result.stand_again_s - result.episode.fall_time_s;
    std::printf(
        "%s push trial %d (%s, %.1f m/s): knocked over %d at %.2f s, first script %s, %d get-up "
        "attempts, standing again %.2f s after the fall, got up %d, final upright %.2f\n",
        to_string(engine), trial, push.from_behind ? "from behind" : "from the front",
        push.push_speed, result.episode.fell, result.episode.fall_time_s,
        result.get_up_script.c_str(), result.get_up_attempts, from_fall, result.got_up,
        result.final_upright);
    ++f.trials;
    f.up_after.push_back(result.got_up ? from_fall : 1e9);
    f.knocked_over += result.episode.fell ? 1 : 0;
    f.got_up += result.got_up ? 1 : 0;
    f.right_script += result.get_up_script == expected ? 1 : 0;
    f.first_try += result.got_up && result.get_up_attempts == 1 ? 1 : 0;
    f.slowest_s = std::max(f.slowest_s, result.got_up ? from_fall : 1e9);
  }
  std::printf(
      "%s push and get up: %d/%d knocked over, %d got up, %d chose the right side, %d at the first "
      "try, slowest %.2f s from the fall\n",
      to_string(engine), f.knocked_over, f.trials, f.got_up, f.right_script, f.first_try,
      f.slowest_s);
  std::printf("  %s\n",
              test::Figures("seconds from the fall to standing", {}, f.up_after).summary().c_str());
  return f;
}

// Knocked over in the default world, the default firmware gets up on both engines, with the
// script of the side it landed on, within 10 s of the fall (the landing, 0.2 s lying still, the
// script, and retries). Counted with one to spare below the share measured. How many
// stand at the first try is a figure, not asserted (it was pinned: Simbody 4 of 10, MuJoCo 3 of
// 10, slowest 6.79 and 9.82 s): the direct get-ups were designed from lying flat in the Stand
// pose, and a knocked-over robot lands in the crouch of the fall protection, often on a side; the
// retry starts from the flat pose the first attempt leaves. Before issue 43 only the seed's grass
// got 10 of 10 up within 40 s on Simbody, and on turf the front's roll took 12.5-35.8 s.
// Measured 2026-11-28, trials 0-19: Simbody 20 of 20 knocked over, on the right side and up within
// 10 s (8 at the first try), from the fall median 5.08 s (IQR 3.03, 2.11-7.92); MuJoCo 20 of 20
// knocked over and on the right side, 19 up within 10 s (trial 11: 17.06 s), 7 at the first try,
// median 4.74 s (IQR 5.29). The times are two groups (about 2.2 s at the first try, 4-10 s after a
// retry), so the count judges them, not the median.
void expect_gets_up(const PushFigures& f, double measured_within_10_s) {
  EXPECT_GE(f.knocked_over, f.trials - 1);
  EXPECT_GE(f.right_script, f.trials - 1);
  int within_10_s = 0;
  for (const double s : f.up_after) within_10_s += s < 10.0 ? 1 : 0;
  EXPECT_GE(within_10_s, test::count_limit(measured_within_10_s, f.trials));
}

TEST(SimScripts, PushedOverTheRobotGetsUpOnSimbody) {
  expect_gets_up(push_trials(EngineKind::kSimbody), 20.0 / 20.0);
}

TEST(SimScripts, PushedOverTheRobotGetsUpOnMujoco) {
  expect_gets_up(push_trials(EngineKind::kMujoco), 19.0 / 20.0);
}

std::string run_stride(const std::string& args, int& code) {
  const std::string command = std::string(STRIDE_BIN_DIR) + "/stride " + args;
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (pipe != nullptr && std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = pipe != nullptr ? pclose(pipe) : -1;
  code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

TEST(SimScripts, StrideSimKickJson) {
  int code = -1;
  const std::string out = run_stride("sim kick --seed 4 --json", code);
  ASSERT_EQ(code, 0) << out;
  // The command's figures (the kick itself is judged over seeds above).
  const nlohmann::json result = nlohmann::json::parse(out);
  EXPECT_TRUE(result.at("fell").is_boolean());
  EXPECT_GT(result.at("ball_distance_m").get<double>(), 0.05);  // the ball moved
  EXPECT_GT(result.at("max_fps").get<double>(), 0.0);
  const std::string left = run_stride("sim kick --script kick_left --json", code);
  ASSERT_EQ(code, 0) << left;
  EXPECT_GT(nlohmann::json::parse(left).at("ball_distance_m").get<double>(), 0.05);
  run_stride("sim kick --script kick_up --json 2>/dev/null", code);
  EXPECT_EQ(code, 2);
}

}  // namespace
}  // namespace stride::sim
