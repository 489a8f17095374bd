// ComplianceCompensation: on by default (gain 1 since issue 29; seed-walk.json sets 0, off); the
// torques it predicts balance the robot's weight (a stance knee must extend, the robot's weight
// shared in double support); the goals move by torque / servo stiffness, bounded; it allocates
// nothing per tick.
#include "stride/firmware/walk/compliance_compensation.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "counting_allocator.hpp"
#include "stride/firmware/mx_motor.hpp"
#include "stride/firmware/stand_pose.hpp"

namespace stride::fw::walk {
namespace {

constexpr double kPeriod = 0.01;

struct Rig {
  ParameterStore store;
  ComplianceCompensation compensation{store, RobotDescription::defaults(), ServoTable::defaults(),
                                      kPeriod};
  std::array<double, hal::kServoCount> targets = kStandPoseRad;
  std::array<double, hal::kServoCount> gains{};
  hal::SensorFrame sensors;
  Rig() {
    gains.fill(38.0);
    for (auto& s : sensors.servos) s.voltage_v = 14.8;
  }
  void set(const char* name, double value) { ASSERT_TRUE(store.set_now({{name, value}}).is_ok()); }
};

std::size_t index(const char* name) {
  return *ServoTable::defaults().index_of(name);
}

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

TEST(WalkCompliance, OnByDefaultAndGainZeroLeavesTheGoalsAlone) {
  Rig rig;
  EXPECT_TRUE(rig.compensation.enabled());  // the faithful world's default (issue 29 point 6)
  rig.set("walk.compliance.gain", 0.0);
  EXPECT_FALSE(rig.compensation.enabled());
  const auto before = rig.targets;
  rig.compensation.apply(rig.targets, kGravity, {true, true}, rig.gains, rig.sensors);
  EXPECT_EQ(rig.targets, before);
}

TEST(WalkCompliance, AStanceLegCarriesTheRobotAndItsKneeIsCommandedStraighter) {
  Rig rig;
  rig.set("walk.compliance.gain", 1.0);
  const auto before = rig.targets;
  rig.compensation.apply(rig.targets, kGravity, {true, false}, rig.gains, rig.sensors);
  const auto& tau = rig.compensation.torques();
  // The left knee holds the robot above it (bent: positive URDF angle), so its servo must push
  // the shank to extend it, and the goal moves towards straight (negative).
  EXPECT_LT(tau[index("l_knee")], -1.0);
  EXPECT_LT(rig.targets[index("l_knee")], before[index("l_knee")]);
  // The swing leg holds only itself: its knee torque is a small fraction.
  EXPECT_LT(std::abs(tau[index("r_knee")]), 0.1 * std::abs(tau[index("l_knee")]));
  // Offsets are torque / stiffness: an MX-106 at P 38 and 14.8 V gives 0.158 P V kt / R with
  // the identified kt and R of the MX motor table (2.2098 N m/A, 2.0337 ohm): 96.6 N m/rad.
  const double stiffness =
      0.158 * 38.0 * 14.8 * fw::kMx106.m6.torque_constant / fw::kMx106.m6.resistance_ohm;
  EXPECT_NEAR(stiffness, 96.6, 0.05);
  EXPECT_NEAR(rig.compensation.offsets()[index("l_knee")], tau[index("l_knee")] / stiffness, 1e-12);
  // Arms are left alone.
  EXPECT_EQ(rig.targets[index("l_elbow")], before[index("l_elbow")]);
}

TEST(WalkCompliance, DoubleSupportSharesTheWeightBetweenTheLegs) {
  Rig rig;
  rig.set("walk.compliance.gain", 1.0);
  rig.compensation.apply(rig.targets, kGravity, {true, true}, rig.gains, rig.sensors);
  const double both = rig.compensation.torques()[index("l_knee")];
  Rig single;
  single.set("walk.compliance.gain", 1.0);
  single.compensation.apply(single.targets, kGravity, {true, false}, single.gains, single.sensors);
  const double one = single.compensation.torques()[index("l_knee")];
  EXPECT_LT(std::abs(both), 0.75 * std::abs(one));
  EXPECT_GT(std::abs(both), 0.25 * std::abs(one));
  // The stand pose is nearly symmetric: the knees share about evenly.
  EXPECT_NEAR(rig.compensation.torques()[index("r_knee")], both, 0.3 * std::abs(both));
}

TEST(WalkCompliance, OffsetsAreBoundedAndZeroGainIsIgnored) {
  Rig rig;
  rig.set("walk.compliance.gain", 1.5);
  rig.set("walk.compliance.max_offset", 0.01);
  rig.gains.fill(2.0);  // very soft: large predicted deflections
  rig.compensation.apply(rig.targets, kGravity, {true, false}, rig.gains, rig.sensors);
  for (double offset : rig.compensation.offsets()) EXPECT_LE(std::abs(offset), 0.01 + 1e-15);
  rig.gains.fill(0.0);  // P 0: no stiffness, nothing to compensate
  const auto before = rig.targets;
  rig.compensation.apply(rig.targets, kGravity, {true, false}, rig.gains, rig.sensors);
  EXPECT_EQ(rig.targets, before);
}

TEST(WalkCompliance, BackEmfFeedForwardFollowsTheGoalsSpeed) {
  Rig rig;
  rig.set("walk.compliance.gain", 0.0);  // the back-EMF term alone
  rig.set("walk.compliance.back_emf_gain", 1.0);
  rig.compensation.apply(rig.targets, kGravity, {true, true}, rig.gains, rig.sensors);
  auto moved = kStandPoseRad;
  moved[index("l_knee")] += 0.01;  // 1 rad/s at 100 Hz
  rig.targets = moved;
  rig.compensation.apply(rig.targets, kGravity, {true, true}, rig.gains, rig.sensors);
  const double expected = fw::kMx106.m6.torque_constant * 1.0 / (0.158 * 38.0 * 14.8);
  EXPECT_NEAR(rig.targets[index("l_knee")] - moved[index("l_knee")], expected, 1e-9);
}

TEST(WalkCompliance, ApplyAllocatesNothing) {
  Rig rig;
  rig.set("walk.compliance.gain", 1.0);
  rig.set("walk.compliance.back_emf_gain", 1.0);
  test::start_counting_allocations();
  for (int i = 0; i < 100; ++i) {
    rig.compensation.apply(rig.targets, kGravity, {i % 2 == 0, true}, rig.gains, rig.sensors);
  }
  EXPECT_EQ(test::stop_counting_allocations(), 0U);
}

}  // namespace
}  // namespace stride::fw::walk
