// Quintic: a segment meets its six boundary conditions, holds its end states outside [0, T],
// and degenerates safely (zero duration, hold).
#include "stride/firmware/walk/quintic.hpp"

#include <gtest/gtest.h>

namespace stride::fw::walk {
namespace {

TEST(Quintic, MeetsPositionVelocityAndAccelerationAtBothEnds) {
  const AxisState from{0.1, -0.4, 2.0}, to{-0.3, 0.7, -1.5};
  const Quintic q = Quintic::between(from, to, 0.37);
  // Just inside each end (at() returns the stored end states exactly outside (0, T)).
  const AxisState a = q.at(1e-9), b = q.at(0.37 - 1e-9);
  EXPECT_NEAR(a.position, from.position, 1e-8);
  EXPECT_NEAR(a.velocity, from.velocity, 1e-6);
  EXPECT_NEAR(a.acceleration, from.acceleration, 1e-5);
  EXPECT_NEAR(b.position, to.position, 1e-8);
  EXPECT_NEAR(b.velocity, to.velocity, 1e-6);
  EXPECT_NEAR(b.acceleration, to.acceleration, 1e-5);
}

TEST(Quintic, VelocityAndAccelerationAreThePositionsDerivatives) {
  const Quintic q = Quintic::between({0.0, 1.0, 0.0}, {0.2, -0.5, 3.0}, 0.25);
  const double t = 0.11, h = 1e-6;
  const AxisState s = q.at(t);
  EXPECT_NEAR(s.velocity, (q.position(t + h) - q.position(t - h)) / (2 * h), 1e-6);
  EXPECT_NEAR(s.acceleration, (q.at(t + h).velocity - q.at(t - h).velocity) / (2 * h), 1e-5);
}

TEST(Quintic, RestToRestIsMonotonicAndSymmetric) {
  const Quintic q = Quintic::rest_to_rest(0.0, 1.0, 1.0);
  double previous = 0.0;
  for (int i = 1; i <= 100; ++i) {
    const double p = q.position(i / 100.0);
    EXPECT_GE(p, previous - 1e-12);
    previous = p;
  }
  EXPECT_NEAR(q.position(0.5), 0.5, 1e-12);
}

TEST(Quintic, HoldsItsEndStatesOutsideTheSegment) {
  const Quintic q = Quintic::between({1.0, 2.0, 0.0}, {3.0, 0.5, 0.0}, 0.5);
  EXPECT_EQ(q.at(-1.0).position, 1.0);
  EXPECT_EQ(q.at(-1.0).velocity, 2.0);
  EXPECT_EQ(q.at(7.0).position, 3.0);
  EXPECT_EQ(q.at(7.0).velocity, 0.5);
}

TEST(Quintic, ZeroDurationJumpsToTheEndAndHoldIsConstant) {
  const Quintic jump = Quintic::between({1.0, 0.0, 0.0}, {2.0, 0.0, 0.0}, 0.0);
  EXPECT_EQ(jump.position(0.0), 2.0);
  const Quintic hold = Quintic::hold(0.25);
  EXPECT_EQ(hold.position(-1.0), 0.25);
  EXPECT_EQ(hold.position(0.0), 0.25);
  EXPECT_EQ(hold.position(3.0), 0.25);
  EXPECT_EQ(hold.at(3.0).velocity, 0.0);
}

}  // namespace
}  // namespace stride::fw::walk
