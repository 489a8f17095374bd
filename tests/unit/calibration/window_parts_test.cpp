// The staged calibration's window rules (window_parts.hpp) on a made-up log: 3 s standing, 3 s
// of arm motion, 3 s of leg motion, 3 s walking, in windows of 1 s; a gap in the ticks moves
// the windows as the replay does.
#include "stride/calibration/window_parts.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/sim_hal/log_replay.hpp"

namespace stride::calibration {
namespace {

constexpr std::size_t kArm = 0, kOtherArm = 5, kKnee = 12, kOtherKnee = 13;

/// `lift`: the legs' part bends the right knee alone by up to `lift` [rad], else both knees.
fw::FlightLog made_up_log(double lift = 0.0) {
  fw::FlightLog log;
  nlohmann::json table = nlohmann::json::array();
  for (std::size_t i = 0; i < hal::kServoCount; ++i)
    table.push_back({{"name", i == kArm         ? "r_shoulder_pitch"
                              : i == kOtherArm  ? "l_elbow"
                              : i == kKnee      ? "r_knee"
                              : i == kOtherKnee ? "l_knee"
                                                : "servo " + std::to_string(i)}});
  log.header = {{"period_ns", 10000000}, {"servo_table", table}};
  for (int t = 0; t < 1200; ++t) {
    fw::FlightLogTick tick;
    tick.meta.tick = static_cast<hal::Tick>(t);
    tick.meta.motion = t >= 900 ? fw::MotionState::kWalk : fw::MotionState::kStand;
    for (auto& s : tick.commands.servos) s.position_rad = 0.1;
    // Standing: a balance feedback's few hundredths of a degree on the knee.
    tick.commands.servos[kKnee].position_rad += 3e-4 * std::sin(t * 0.1);
    if (t >= 300 && t < 600) tick.commands.servos[kArm].position_rad += 0.002 * (t - 300);
    if (t >= 600 && t < 900) {
      const double bend = lift > 0.0 ? lift * (t - 600) / 300.0 : 0.001 * (t - 600);
      tick.commands.servos[kKnee].position_rad += bend;
      if (lift == 0.0) tick.commands.servos[kOtherKnee].position_rad += bend;
    }
    log.ticks.push_back(tick);
  }
  return log;
}

std::vector<std::string> names(const std::vector<WindowPart>& parts) {
  std::vector<std::string> out;
  for (WindowPart p : parts) out.push_back(window_part_name(p));
  return out;
}

TEST(WindowParts, ClassifiesStillArmsLegsAndWalkWindowsFromTheCommands) {
  const fw::FlightLog log = made_up_log();
  EXPECT_EQ(arm_servo_mask(log), (1U << kArm) | (1U << kOtherArm));
  // Windows of 100 ticks start at 0, 100, ... and reach their start + 100: the arm's goal first
  // moves at 301 and jumps back at 600 (the window from 500 is still the arms'); the knee's moves
  // from 601 and jumps back at 900, where the walk starts (the window from 800 walks).
  const std::vector<std::string> expected = {"still", "still", "still", "arms", "arms", "arms",
                                             "legs",  "legs",  "walk",  "walk", "walk"};
  EXPECT_EQ(names(classify_windows(log, 1.0)), expected);
}

TEST(WindowParts, OneKneeBentFurtherThanTheOtherIsASingleSupportStep) {
  // The right knee alone bends to 0.45 rad over 3 s: its goal passes 0.2 rad from the left's at
  // tick 734, so the window from 700 steps; the one from 600 (0.15 rad apart) stands on both feet.
  const std::vector<WindowPart> parts = classify_windows(made_up_log(0.45), 1.0);
  ASSERT_EQ(parts.size(), 11U);
  EXPECT_EQ(parts[6], WindowPart::kLegs);
  EXPECT_EQ(parts[7], WindowPart::kSteps);
  EXPECT_STREQ(window_part_name(parts[7]), "steps");
  EXPECT_EQ(parts[8], WindowPart::kWalk);  // the walk wins over the steps
}

TEST(WindowParts, AGapStartsTheWindowsAgainAfterIt) {
  fw::FlightLog log = made_up_log();
  log.ticks[150].meta.dropped_before = 3;  // the recorder lost three ticks before tick 150
  const std::vector<WindowPart> parts = classify_windows(log, 1.0);
  const std::vector<std::size_t> firsts = sim::window_first_indices(log, 1.0);
  ASSERT_EQ(parts.size(), firsts.size());
  ASSERT_EQ(parts.size(), 11U);  // 0-100, then 150-250, 250-350, ..., 1050-1150
  EXPECT_EQ(firsts[1], 150U);
  EXPECT_EQ(parts[1], WindowPart::kStill);
  EXPECT_EQ(parts[2], WindowPart::kArms);  // 250-350
}

TEST(WindowParts, ALogWithoutAPeriodHasNoWindows) {
  fw::FlightLog log = made_up_log();
  log.header.erase("period_ns");
  EXPECT_TRUE(classify_windows(log, 1.0).empty());
}

}  // namespace
}  // namespace stride::calibration
