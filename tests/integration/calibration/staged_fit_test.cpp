// The staged calibration on the arms' known loads (issue 56 points 1, 2 and 5): a robot whose
// MX-64s are weaker (x0.85), whose gears are stiffer (friction x1.3) and whose bus is two ticks
// late, and whose MX-106s (x1.1) and trunk centre of mass (8 mm forward) differ too, values the
// fit is not asked for and must not be pulled by. The routine is standing and identify_arms
// (arm holds approached from both sides, set-point steps; firmware/scripts/IDENTIFICATION.md);
// stride calibrate classifies the log's windows (window_parts.hpp) and fits the latency, the
// MX-64 torque and the friction on the arms' channels of the arms' windows (staged_fit.cpp).
// Before identify_arms and the stages, the study of drawn robots found the MX-64 torque on 1 of
// 18 robots and the friction on 0 of 18; with them, 13 of 20 each (tests/bench/RESULTS.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "seeds.hpp"
#include "stride/calibration/window_parts.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/sim_hal/world_file.hpp"
#include "temp_dir.hpp"

namespace stride::calibration {
namespace {

constexpr double kTrueMx64 = 0.85, kTrueFriction = 1.3;
constexpr int kTrueLatency = 2;

test::ChildRun stride(const test::TempDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), std::string(STRIDE_BIN_DIR) + "/stride");
  return test::run_child(args, dir.path());
}

struct Fit {
  bool ok = false;
  double mx64 = NAN, friction = NAN;
  int latency = -1;
  std::size_t arm_windows = 0, still_windows = 0, other_windows = 0;
};

Fit record_and_fit(std::uint64_t seed) {
  test::TempDir dir;
  const auto world = dir.write("robot.json", R"({"format": "stride-world", "robot": {
      "torque_scale": {"MX-64": 0.85, "MX-106": 1.1}, "friction_scale": 1.3,
      "latency_ticks": 2, "trunk_com_offset_m": [0.008, 0.0]}})");
  const auto log = dir.path() / "arms.flog";
  test::ChildRun run = stride(dir, {"identify", "--out", log.string(), "--world", world.string(),
                                    "--parts", "stand,identify_arms", "--stand-s", "5", "--noise",
                                    "on", "--seed", std::to_string(seed), "--json"});
  Fit fit;
  EXPECT_EQ(run.code, 0) << run.err;
  if (run.code != 0 || nlohmann::json::parse(run.out)["fell"].get<bool>()) return fit;
  fw::FlightLog flight;
  EXPECT_TRUE(fw::read_flight_log(log, flight));
  for (WindowPart part : classify_windows(flight, 5.0))
    ++(part == WindowPart::kArms    ? fit.arm_windows
       : part == WindowPart::kStill ? fit.still_windows
                                    : fit.other_windows);
  const auto out = dir.path() / "calibrated.json";
  run = stride(dir, {"calibrate", log.string(), "--fit", "torque_mx64,friction,latency", "--out",
                     out.string(), "--window", "5", "--subsets", "0", "--jobs", "2", "--no-check"});
  EXPECT_EQ(run.code, 0) << run.err;
  sim::WorldFile calibrated;
  if (run.code != 0 || !sim::load_world_file(out, calibrated)) return fit;
  fit.ok = true;
  fit.mx64 = calibrated.robot.torque_scale_mx64;
  fit.friction = calibrated.robot.friction_scale;
  fit.latency = calibrated.robot.latency_ticks;
  return fit;
}

// Measured 2026-11-28, seeds 1-5 (about 25 s each on 2 threads; 20 seeds not measured): MX-64
// error median 0.013 (IQR 0.015, 0.001-0.033), friction 0.018 (IQR 0.018, 0.003-0.052), latency
// exact on every seed; 4 of 5 within 20 % on both (seed 4: MX-64 0.033 off); 10 arm windows of
// 5 s and 1 still one. The two miss together (torque and friction trade on the arms: the drawn
// robots of tests/bench/RESULTS.md show the same), so the count is 4 of 5 less one to spare.
TEST(StagedFit, FindsTheArmServosTorqueFrictionAndTheLatencyUnpulledByTheLegsAndTrunk) {
  const test::Seeds seeds(5);
  std::vector<Fit> fits;
  const std::vector<test::Figures> f =
      seeds.run({"MX-64 error [x]", "friction error [x]", "latency error [ticks]", "arm windows",
                 "still windows"},
                [&](std::uint64_t seed) {
                  const Fit fit = record_and_fit(seed);
                  fits.push_back(fit);
                  return std::vector<double>{
                      std::abs(fit.mx64 - kTrueMx64), std::abs(fit.friction - kTrueFriction),
                      std::abs(static_cast<double>(fit.latency - kTrueLatency)),
                      static_cast<double>(fit.arm_windows), static_cast<double>(fit.still_windows)};
                });
  // Within 20 % of the perturbation (the study's measure): 0.03 and 0.06; latency exact.
  int within = 0;
  for (const Fit& fit : fits)
    within += fit.ok && std::abs(fit.mx64 - kTrueMx64) <= 0.03 &&
              std::abs(fit.friction - kTrueFriction) <= 0.06 && fit.latency == kTrueLatency;
  EXPECT_GE(within, test::count_limit(4.0 / 5.0, seeds.n()));
  EXPECT_LT(f[0].median(), 0.06);   // 0.013 + 3 IQR
  EXPECT_LT(f[1].median(), 0.075);  // 0.018 + 3 IQR
  EXPECT_EQ(f[2].median(), 0.0);
  // The window rules (window_parts.hpp) see the arms' part: 55 s of it in 5 s windows.
  EXPECT_GE(f[3].min(), 9.0);  // 10
  EXPECT_GE(f[4].min(), 1.0);  // 1: the first 5 s standing
}

}  // namespace
}  // namespace stride::calibration
