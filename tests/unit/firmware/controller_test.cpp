// Controller: step() allocates nothing, requests cross threads, torque switch, safety last.
#include "stride/firmware/controller.hpp"

#include <thread>

#include <gtest/gtest.h>

#include "counting_allocator.hpp"
#include "firmware_fixture.hpp"

namespace stride::fw {
namespace {

TEST(Controller, StepAllocatesNothing) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  Controller& controller = firmware->controller();
  const auto upright = hal::ScriptedRobot::standing_frame();
  const auto lying = test::tilted_frame(1.5);
  controller.request(MotionRequest::walk(0.5, 0, 0));
  controller.request(MotionRequest::play("kick_right"));
  test::start_counting_allocations();
  for (hal::Tick t = 0; t < 300; ++t) {
    (void)controller.step(t < 200 ? upright : lying, t);  // stand, requests, then a fall
  }
  EXPECT_EQ(test::stop_counting_allocations(), 0u);
  // The counter works: an allocation in the counted window is seen.
  test::start_counting_allocations();
  static int* volatile probe = nullptr;  // volatile: the allocation cannot be elided
  probe = new int(3);
  const std::size_t seen = test::stop_counting_allocations();
  delete probe;
  EXPECT_EQ(seen, 1u);
}

TEST(Controller, TorqueOffReachesEveryServoAndOnComesBack) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  Controller& controller = firmware->controller();
  const auto sensors = hal::ScriptedRobot::standing_frame();
  auto c = controller.step(sensors, 0);
  EXPECT_TRUE(c.servos[0].torque_enable);
  std::thread console([&] { controller.set_torque(false); });
  console.join();
  c = controller.step(sensors, 1);
  for (const auto& s : c.servos) EXPECT_FALSE(s.torque_enable);
  EXPECT_FALSE(controller.status().torque_on);
  controller.set_torque(true);
  c = controller.step(sensors, 2);
  EXPECT_TRUE(c.servos[19].torque_enable);
}

TEST(Controller, SafetyIsAppliedLastAndStatusIsPublished) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  Controller& controller = firmware->controller();
  const auto& table = firmware->servos();
  const auto sensors = hal::ScriptedRobot::standing_frame();
  for (hal::Tick t = 0; t < 10; ++t) {
    const auto c = controller.step(sensors, t);
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      EXPECT_GE(c.servos[i].position_rad, table[i].min_rad);
      EXPECT_LE(c.servos[i].position_rad, table[i].max_rad);
    }
  }
  const auto status = controller.status();
  EXPECT_EQ(status.tick, 9);
  EXPECT_EQ(status.state, MotionState::kStand);
}

TEST(Controller, MailboxDropsAndCountsBeyondCapacity) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  Controller& controller = firmware->controller();
  for (int i = 0; i < 10; ++i) controller.request(MotionRequest::stand());
  (void)controller.step(hal::ScriptedRobot::standing_frame(), 0);
  EXPECT_EQ(controller.status().dropped_requests, 2u);
}

}  // namespace
}  // namespace stride::fw
