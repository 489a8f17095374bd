// Integration tests (release build) of falling safely (issue 43 point 2) through `stride sim`:
// in pushed falls the firmware predicts the fall before any link but the feet touches the
// ground; with the protection the peak servo motor torque at impact is lower than without in the
// forward fall; the get-up still follows a protected fall; walking 10 s in each
// direction never predicts a fall. Default world (Simbody, turf), judged over seeds
// (tests/README.md); seed 1's figures are firmware/src/FALLING.md's table.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "seeds.hpp"
#include "stride_sim_json.hpp"

namespace {

using stride::test::sim_json;

const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/tests/integration/sim_hal/";

/// A stand pushed at 1 s with 12 N s, going on 1.5 s past the push (--after-fall keeps the
/// episode running through the landing); `protect` false loads fall-unprotected.json.
nlohmann::json pushed(const std::string& direction, bool protect, std::uint64_t seed) {
  return sim_json("stand --push 1," + direction + ",12 --after-fall getup --duration 2.5 --seed " +
                  std::to_string(seed) +
                  (protect ? std::string() : " --params " + kConfigs + "fall-unprotected.json"));
}

// Seed 1 measured (FALLING.md's table): fall predicted at 1.04, 1.12 and 1.05 s, the body's first
// contact at 1.33, 1.38 and 1.38 s (forward, backward, left); these were pinned to 1e-9 s.
// Seeds 1-5 per direction, counted with one to spare. Measured 2026-11-28, seeds 1-20: the fall
// predicted in 20 of 20 per direction, median lead before the body's contact 0.29 s forward (IQR
// 0), 0.28 s backward (IQR 0.013), 0.33 s left (IQR 0.01).
TEST(FallProtection, PredictsEachPushedFallBeforeTheBodyTouchesTheGround) {
  for (const char* direction : {"forward", "backward", "left"}) {
    SCOPED_TRACE(direction);
    const stride::test::Figures lead = stride::test::Seeds(5).run(
        std::string(direction) + ": contact - prediction [s]", [&](std::uint64_t seed) {
          const nlohmann::json on = pushed(direction, true, seed);
          if (!on.contains("fall_predicted_s") || !on.contains("impact") ||
              !on.at("impact").contains("body_contact_s") || !on.at("fell").get<bool>())
            return -1.0;
          const double predicted = on.at("fall_predicted_s").get<double>();
          if (predicted <= 1.0) return -1.0;  // after the push, not before
          return on.at("impact").at("body_contact_s").get<double>() - predicted;
        });
    EXPECT_GE(lead.count_above(0.0), static_cast<int>(lead.size()) - 1);
    EXPECT_GT(lead.median(), 0.15);  // medians 0.28-0.33 s, IQR <= 0.013 s (seeds 1-20)
  }
}

// The peak servo motor torque at impact, protected and not, in the forward fall: seeds 1-5,
// medians. Seed 1 measured forward 11.25 against 13.43 N m, backward 13.80 against 14.87, left
// 19.26 against 16.87 (pinned to 0.005 N m before, and the backward asserted lower). Measured
// 2026-11-28, seeds 1-20: forward protected median 11.25 N m (IQR 0), unprotected 13.43 (IQR 0,
// up to 14.02); backward protected 15.08 (IQR 1.32) against 14.87 (IQR 0.10), so the protection
// does not lower the backward fall's peak over seeds, which seed 1 said it did: a known limit,
// in tests/bench/RESULTS.md, not asserted.
TEST(FallProtection, LowersThePeakServoTorqueAtImpactForward) {
  const std::vector<stride::test::Figures> f =
      stride::test::Seeds(5).run({"protected [N m]", "unprotected [N m]"}, [&](std::uint64_t seed) {
        const auto torque = [](const nlohmann::json& r) {
          return r.at("impact").at("peak_servo_torque_nm").get<double>();
        };
        return std::vector<double>{torque(pushed("forward", true, seed)),
                                   torque(pushed("forward", false, seed))};
      });
  // 11.25 against 13.43 N m (seeds 1-20, IQR 0 each): the limit, 0.95 of the unprotected
  // median, is 13 % above the protected one.
  EXPECT_LT(f[0].median(), 0.95 * f[1].median());
}

// The default firmware (the direct get-ups of issue 43, fall.protect on): the robot lands
// protected, lies still, and stands up (seed 1: 2.49 s after the fall at the first try; 7.10 s
// with the get-up of issue 31). Seeds 1-5, counted with one to spare, and the median.
// Measured 2026-11-28, seeds 1-20: median 2.45 s from the fall, IQR 0.01 s, 2.44-2.51 s; predicted
// in 20 of 20.
TEST(FallProtection, TheGetUpFollowsAProtectedFall) {
  int predicted = 0;
  const stride::test::Figures up =
      stride::test::Seeds(5).run("stood up after the fall [s]", [&](std::uint64_t seed) {
        const nlohmann::json back =
            sim_json("stand --push 1,backward,12 --after-fall getup --duration 7 --seed " +
                     std::to_string(seed));
        predicted += back.contains("fall_predicted_s") && back.at("fell").get<bool>() ? 1 : 0;
        return back.at("stood_up_s").is_null() ? 1e9 : back.at("stood_up_s").get<double>();
      });
  EXPECT_GE(predicted, static_cast<int>(up.size()) - 1);
  EXPECT_GE(up.count_at_most(4.0), static_cast<int>(up.size()) - 1);
  EXPECT_LT(up.median(), 3.2);  // median 2.45 s, IQR 0.01 s (seeds 1-20)
}

// Walking 10 s in each direction never predicts a fall: seeds 1-5, 20 walks, counted with one
// to spare (seed 1 walked 20 s in each without a prediction). Measured 2026-11-28: 80 of 80 walks
// (seeds 1-20) without a prediction or a fall.
TEST(FallProtection, WalkingInEachDirectionNeverPredictsAFall) {
  int quiet = 0, walks = 0;
  for (const char* velocity : {"--vx 1", "--vx -1", "--vy 1", "--vy -1"}) {
    for (std::uint64_t seed = 1; seed <= static_cast<std::uint64_t>(stride::test::seed_count(5));
         ++seed) {
      const nlohmann::json walk = sim_json(std::string("walk ") + velocity +
                                           " --duration 10 --seed " + std::to_string(seed));
      const bool ok = !walk.at("fell").get<bool>() && !walk.contains("fall_predicted_s");
      if (!ok)
        std::printf("  %s seed %llu: %s\n", velocity, static_cast<unsigned long long>(seed),
                    walk.dump().c_str());
      quiet += ok ? 1 : 0;
      ++walks;
    }
  }
  std::printf("  %d of %d walks without a predicted fall\n", quiet, walks);
  EXPECT_GE(quiet, walks - 1);
}

}  // namespace
