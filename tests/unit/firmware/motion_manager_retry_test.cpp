// Each get-up attempt differs from the failed one before it (issue 54 point 1): after a failed
// attempt from the back the robot rolls onto its front (roll_to_front) and gets up from there;
// on the front after an odd number of failed attempts it plays get_up_front_retry, after an even
// number get_up_front again; from motion.get_up_slow_after
// failed attempts on the other get-ups play motion.get_up_slow_scale times slower; a successful
// get-up or a new fall starts the count again.
#include <gtest/gtest.h>

#include "motion_manager_rig.hpp"

namespace stride::fw {
namespace {

using test::Rig;

/// Plays get-ups that all leave the robot down; returns the ticks of each kGetUp and the script
/// each played.
struct Attempt {
  std::string script;
  hal::Tick ticks = 0;
};
Attempt fail_one(Rig& r) {
  EXPECT_LE(r.run_until(MotionState::kGetUp, 400), 400);
  Attempt a{std::string(r.manager->active_script()), 0};
  a.ticks = r.run_until(MotionState::kFallen, 4000);
  EXPECT_LE(a.ticks, 4000);
  return a;
}

hal::Tick script_ticks(const Rig& r, const char* name) {
  const auto& s = r.scripts.script(static_cast<std::size_t>(r.scripts.find(name)));
  return s.total_duration_ms() / 10;
}

TEST(MotionManagerRetry, AFailedAttemptFromTheBackRollsOntoTheFrontThenGetsUpFromThere) {
  Rig r;
  r.settle_stand();
  r.lie(9.81, 0, 0);  // on the back
  EXPECT_EQ(fail_one(r).script, "get_up_back");
  EXPECT_EQ(fail_one(r).script, "roll_to_front");
  r.lie(-9.81, 0, 0);  // the roll put it on its front
  EXPECT_EQ(fail_one(r).script, "get_up_front_retry");
  r.lie(9.81, 0, 0);  // and that attempt ended on the back again: the back's get-up first
  EXPECT_EQ(fail_one(r).script, "get_up_back");
  EXPECT_EQ(fail_one(r).script, "roll_to_front");
}

TEST(MotionManagerRetry, TheRollCanBeSwitchedOff) {
  Rig r;
  ASSERT_TRUE(r.params.set_now({{"motion.get_up_roll", 0.0}}));
  r.settle_stand();
  r.lie(9.81, 0, 0);
  EXPECT_EQ(fail_one(r).script, "get_up_back");
  EXPECT_EQ(fail_one(r).script, "get_up_back");
}

TEST(MotionManagerRetry, OnTheFrontTheRetryGetUpAndTheGentleOneAlternate) {
  Rig r;
  r.settle_stand();
  r.lie(-9.81, 0, 0);
  EXPECT_EQ(fail_one(r).script, "get_up_front");
  const Attempt second = fail_one(r);
  EXPECT_EQ(second.script, "get_up_front_retry");
  EXPECT_NEAR(second.ticks, script_ticks(r, "get_up_front_retry"), 2);
  // Then the two alternate, the gentle one slower from the second failure on.
  const Attempt third = fail_one(r);
  EXPECT_EQ(third.script, "get_up_front");
  EXPECT_NEAR(third.ticks, 1.5 * script_ticks(r, "get_up_front"), 3);
  const Attempt fourth = fail_one(r);
  EXPECT_EQ(fourth.script, "get_up_front_retry");
  EXPECT_NEAR(fourth.ticks, script_ticks(r, "get_up_front_retry"), 2);  // never slowed
  Rig off;
  ASSERT_TRUE(off.params.set_now({{"motion.get_up_retry", 0.0}}));
  off.settle_stand();
  off.lie(-9.81, 0, 0);
  EXPECT_EQ(fail_one(off).script, "get_up_front");
  EXPECT_EQ(fail_one(off).script, "get_up_front");
}

// The back with the roll off: its own get-up again and again, slower from the second failure.
TEST(MotionManagerRetry, FromTheSecondFailedAttemptOnTheGetUpPlaysSlower) {
  Rig r;
  ASSERT_TRUE(r.params.set_now({{"motion.get_up_roll", 0.0}}));
  r.settle_stand();
  r.lie(9.81, 0, 0);
  const hal::Tick normal = script_ticks(r, "get_up_back");
  const Attempt first = fail_one(r), second = fail_one(r), third = fail_one(r);
  EXPECT_NEAR(first.ticks, normal, 2);
  EXPECT_NEAR(second.ticks, normal, 2);
  EXPECT_NEAR(third.ticks, 1.5 * normal, 3);  // motion.get_up_slow_scale
  // Standing up starts the count again: the next fall's first attempt is at full speed.
  ASSERT_LE(r.run_until(MotionState::kGetUp, 400), 400);
  r.get_up_upright();
  ASSERT_LE(r.run_until(MotionState::kStand, 4000), 4000);
  r.run(test::kStandRampTicks + 2);
  r.lie(9.81, 0, 0);
  EXPECT_NEAR(fail_one(r).ticks, normal, 2);
}

TEST(MotionManagerRetry, TheSlowerVariantCanBeSwitchedOff) {
  Rig r;
  ASSERT_TRUE(r.params.set_now({{"motion.get_up_slow_after", 0.0}, {"motion.get_up_roll", 0.0}}));
  r.settle_stand();
  r.lie(9.81, 0, 0);
  const hal::Tick normal = script_ticks(r, "get_up_back");
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(fail_one(r).ticks, normal, 2) << "attempt " << i + 1;
}

}  // namespace
}  // namespace stride::fw
