// Integration tests (release build) of `stride sim getup --lying front|back` and
// `stride sim stand|walk --after-fall getup` (issue 43 point 1): the time from lying still to
// standing (stood_up_s) in the default world, judged over seeds (tests/README.md); a pushed
// robot's episode goes on past its fall through the get-up; the replay options record the same
// episode; bad input is one line naming the option, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "seeds.hpp"
#include "stride_sim_json.hpp"

namespace {

using stride::test::sim_json;
using stride::test::stood_up_s;

std::string seed_arg(std::uint64_t seed) {
  return " --seed " + std::to_string(seed);
}

// The default world (identified servo, CM730 IMU, turf, noise on), seeds 1-5, 5 s episodes: the
// default firmware's direct get-ups (issue 43) stand up from both sides on both engines at the
// first try, under issue 43's 3 s from lying still (0.2 s of it lying still before the script
// starts), with the script of the side it lies on. Counted with one to spare, and the median.
// Seed 1 measured 2.28 and 2.42 s (back, front) on Simbody and 2.32 and 2.46 s on MuJoCo. Before
// issue 43 the same episodes took 7.20 s from the back and 12.35 s (Simbody) or 12.07 s (MuJoCo)
// from the front, which rolled onto its back and got up from there.
// Measured 2026-11-28, seeds 1-20: stood up after 2.28 s (back) and 2.42 s (front) on Simbody, 2.32
// and 2.46 s on MuJoCo, IQR 0 to 0.01 s each, 20 of 20 at the first try under 3 s.
TEST(StrideSimGetUp, TheDefaultFirmwareStandsUpFromBothSidesOnBothEngines) {
  for (const char* args :
       {"getup --lying back", "getup --lying front", "getup --lying back --engine mujoco",
        "getup --lying front --engine mujoco"}) {
    SCOPED_TRACE(args);
    const bool back = std::string(args).find("back") != std::string::npos;
    int first_try = 0;
    const stride::test::Figures f =
        stride::test::Seeds(5).run("stood up after [s]", [&](std::uint64_t seed) {
          const nlohmann::json r = sim_json(std::string(args) + " --duration 5" + seed_arg(seed));
          EXPECT_EQ(r.at("lying"), back ? "back" : "front") << r.dump();
          EXPECT_EQ(r.at("get_up_script"), back ? "get_up_back" : "get_up_front") << r.dump();
          EXPECT_DOUBLE_EQ(r.at("sim_time_s").get<double>(), 5.0);  // the duration asked for
          EXPECT_EQ(r.at("status"), "running");
          first_try += r.at("get_up_attempts") == 1 && stood_up_s(r) < 3.0 ? 1 : 0;
          return stood_up_s(r);
        });
    EXPECT_GE(first_try, static_cast<int>(f.size()) - 1) << "under 3 s at the first try";
    EXPECT_LT(f.median(),
              2.8);  // issue 43's target is 3 s; medians 2.28-2.46 s, IQR <= 0.01 s (seeds 1-20)
  }
  // A duration that ends before the robot has stood for the held second: null.
  const nlohmann::json short_one = sim_json("getup --lying back --duration 2.5");
  EXPECT_TRUE(short_one.at("stood_up_s").is_null()) << short_one.dump();
}

// On the other grounds too, from both sides, at the first try under 3 s (Simbody and MuJoCo;
// before issue 43 the front stayed down on Simbody's soft ground and on MuJoCo's hard ground,
// and the back on MuJoCo's hard ground): 11 ground, engine and side pairs on seeds 1 and 2, 22
// episodes counted with one to spare. One exception, MuJoCo's seed grass from the back: seed 1
// fell back three times and stood at the fourth attempt, 8.94 s from lying still; the back
// script's mixed search stage traded it for the drawn worlds (optimiser/RESULTS.md, "Direct
// get-ups": with friction, masses and strength drawn it stands there in 18 of 20 seeds, the
// script before it in 12). It is judged on its own: standing within the 20 s the rules give a
// fallen robot, on seeds 1-5, with one to spare. Its attempts are a knife edge: measured
// 2026-11-28 on seeds 1-20 it stood after a median 7.91 s (IQR 2.07, 4.54-9.23), and with the
// MX torque constant 1e-5 larger (tests/README.md's check) after 6.67-14.66 s (3 to 6 attempts;
// this test asked for 10 s then and failed). The 11 other pairs: 220 of 220 at the first try
// under 3 s (seeds 1-20).
TEST(StrideSimGetUp, OnEveryGroundTheDefaultFirmwareStandsUpFromBothSides) {
  int first_try = 0, episodes = 0;
  for (const char* engine : {"simbody", "mujoco"}) {
    for (const char* contact : {"seed", "soft", "hard"}) {
      for (const char* side : {"front", "back"}) {
        const bool exception = std::string(engine) == "mujoco" && std::string(contact) == "seed" &&
                               std::string(side) == "back";
        if (exception) continue;
        for (std::uint64_t seed = 1; seed <= 2; ++seed) {
          const std::string args = std::string("getup --lying ") + side + " --engine " + engine +
                                   " --contact " + contact + " --duration 5" + seed_arg(seed);
          const nlohmann::json r = sim_json(args);
          const bool ok =
              r.at("get_up_attempts") == 1 && stood_up_s(r) > 2.0 && stood_up_s(r) < 3.0;
          std::printf("  %s: stood up after %.2f s, %d attempts%s\n", args.c_str(), stood_up_s(r),
                      r.at("get_up_attempts").get<int>(), ok ? "" : " (not at the first try)");
          first_try += ok ? 1 : 0;
          ++episodes;
        }
      }
    }
  }
  EXPECT_GE(first_try, episodes - 1);
  const stride::test::Count exception = stride::test::Seeds(5).count(
      "MuJoCo seed grass, back: standing within 20 s", [](std::uint64_t seed) {
        return stood_up_s(sim_json("getup --lying back --engine mujoco --contact seed "
                                   "--duration 20" +
                                   seed_arg(seed))) < 19.0;
      });
  EXPECT_GE(exception.k, exception.n - 1);
}

// The replay options record the same episode, and the page says when it stood up.
TEST(StrideSimGetUp, RecordAndHtmlReplayTheSameEpisode) {
  const std::string dir = ::testing::TempDir();
  const std::string record = dir + "/getup.jsonl", html = dir + "/getup.html";
  const nlohmann::json plain = sim_json("getup --lying back --duration 5");
  const nlohmann::json replayed =
      sim_json("getup --lying back --duration 5 --record " + record + " --html " + html);
  EXPECT_EQ(replayed.at("state_hash"), plain.at("state_hash"));
  std::ifstream record_file(record);
  std::string line;
  int lines = 0;
  while (std::getline(record_file, line)) ++lines;
  EXPECT_GE(lines, 501);  // every tick of the 5 s
  std::stringstream page;
  page << std::ifstream(html).rdbuf();
  ASSERT_FALSE(plain.at("stood_up_s").is_null()) << plain.dump();
  char expected[64];
  std::snprintf(expected, sizeof expected, "stood up after %.2f s", stood_up_s(plain));
  EXPECT_NE(page.str().find(expected), std::string::npos) << expected;
  EXPECT_NE(page.str().find("lying on the back"), std::string::npos);
}

// Without --after-fall a fallen robot's episode ends at the fall; with it the episode runs its
// duration and the robot stands up again. Standing, pushed backward at 1 s (4 N s), it falls on
// its back (seed 1 at 1.85 s) and stands up with the direct get-up (seed 1: 2.12 s after the
// fall; 7.17 s before issue 43). Walking, pushed forward (8 N s at 3 s), it falls (seed 1 at
// 3.30 s) and stands up (seed 1: 5.06 s after the fall, at the second attempt; 12.53 s before
// issue 43, the roll): the robot lands in the crouch of the fall protection, not the lying pose
// the get-up was designed from. Seeds 1-5, counted with one to spare, and the median.
// Measured 2026-11-28, seeds 1-20: stand median 2.15 s from the fall, IQR 0 (2.12-2.16 s); walking
// median 5.06 s, IQR 0.02 s (5.04-5.08 s); every seed stood up.
TEST(StrideSimGetUp, APushedRobotGoesOnThroughItsGetUpWithAfterFall) {
  const nlohmann::json ended = sim_json("stand --push 1,backward,12");
  ASSERT_TRUE(ended.at("fell").get<bool>()) << ended.dump();
  EXPECT_DOUBLE_EQ(ended.at("sim_time_s").get<double>(), ended.at("fall_time_s").get<double>());
  EXPECT_FALSE(ended.contains("stood_up_s"));
  const auto after_fall = [](const std::string& args, const char* script, double duration) {
    return [=](std::uint64_t seed) {
      const nlohmann::json r = sim_json(args + " --after-fall getup --duration " +
                                        std::to_string(duration) + seed_arg(seed));
      EXPECT_DOUBLE_EQ(r.at("sim_time_s").get<double>(), duration) << r.dump();
      EXPECT_FALSE(r.contains("lying"));
      if (!r.at("fell").get<bool>() || r.at("stood_up_s").is_null()) return 1e9;
      EXPECT_EQ(r.at("get_up_script"), script) << r.dump();
      return stood_up_s(r);
    };
  };
  const stride::test::Figures stand =
      stride::test::Seeds(5).run("stand pushed backward: up after the fall [s]",
                                 after_fall("stand --push 1,backward,4", "get_up_back", 7.0));
  EXPECT_GE(stand.count_at_most(4.0), static_cast<int>(stand.size()) - 1);
  EXPECT_LT(stand.median(), 3.0);  // median 2.15 s, IQR 0, 2.12-2.16 s (seeds 1-20)
  const stride::test::Figures walk = stride::test::Seeds(5).run(
      "walk pushed forward: up after the fall [s]",
      after_fall("walk --vx 1 --push 3,forward,8", "get_up_front", 12.0));
  EXPECT_GE(walk.count_at_most(7.5), static_cast<int>(walk.size()) - 1);
  EXPECT_LT(walk.median(), 6.5);  // median 5.06 s, IQR 0.02, 5.04-5.08 s (seeds 1-20)
}

TEST(StrideSimGetUp, BadInputIsOneLineNamingTheOptionAndExitTwo) {
  const std::pair<const char*, const char*> cases[] = {
      {"getup --lying sideways", "--lying"},
      {"getup", "--lying"},
      {"walk --lying back", "--lying"},
      {"stand --lying front", "--lying"},
      {"kick --lying back", "--lying"},
      {"stand --after-fall kick", "--after-fall"},
      {"walk --after-fall ''", "--after-fall"},
      {"getup --lying back --after-fall getup", "--after-fall"},
      {"kick --after-fall getup", "--after-fall"},
  };
  for (const auto& [args, option] : cases) {
    int code = -1;
    const std::string err = stride::test::run_command(
        std::string(STRIDE_BIN_DIR) + "/stride sim " + args + " --json 2>&1 >/dev/null", code);
    EXPECT_EQ(code, 2) << args << ": " << err;
    EXPECT_NE(err.find(option), std::string::npos) << args << ": " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << args << ": " << err;
  }
}

}  // namespace
