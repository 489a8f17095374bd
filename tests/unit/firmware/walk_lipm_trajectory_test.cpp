// LIPM torso trajectory: boundary conditions, the pendulum equation x'' = (x - z)/tau^2, and
// the piecewise-linear ZMP with the correct slope pairing.
#include "stride/firmware/walk/lipm_trajectory.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace stride::fw::walk {
namespace {

struct Case {
  double p0, p1, s, step_time, tau, phi1, phi2;
};

class WalkLipm : public ::testing::TestWithParam<Case> {};

TEST_P(WalkLipm, MeetsBoundaryConditionsAndThePendulumEquation) {
  const Case c = GetParam();
  LipmAxis axis;
  axis.solve(c.p0, c.p1, c.s, c.step_time, c.tau, c.phi1, c.phi2);
  EXPECT_NEAR(axis.position(0.0), c.p0, 1e-12);
  EXPECT_NEAR(axis.position(c.step_time), c.p1, 1e-12);
  // ZMP: p0 -> s on [0, T1], s on [T1, T2], s -> p1 on [T2, T].
  EXPECT_NEAR(axis.zmp(0.0), c.p0, 1e-12);
  EXPECT_NEAR(axis.zmp(c.phi1 * c.step_time), c.s, 1e-12);
  EXPECT_NEAR(axis.zmp(0.5 * (c.phi1 + c.phi2) * c.step_time), c.s, 1e-12);
  EXPECT_NEAR(axis.zmp(c.step_time), c.p1, 1e-12);
  const double h = 1e-4;
  for (int i = 1; i < 200; ++i) {
    const double t = c.step_time * i / 200.0;
    const double lhs = axis.acceleration(t);
    const double rhs = (axis.position(t) - axis.zmp(t)) / (c.tau * c.tau);
    ASSERT_NEAR(lhs, rhs, 1e-9 * (1.0 + std::abs(rhs))) << "t " << t;
    const bool near_break = std::abs(t - c.phi1 * c.step_time) < 2 * h ||
                            std::abs(t - c.phi2 * c.step_time) < 2 * h;  // x''' jumps there
    if (t > h && t < c.step_time - h && !near_break) {
      const double fd_velocity = (axis.position(t + h) - axis.position(t - h)) / (2 * h);
      ASSERT_NEAR(axis.velocity(t), fd_velocity, 1e-6);
      const double fd_accel =
          (axis.position(t + h) - 2 * axis.position(t) + axis.position(t - h)) / (h * h);
      ASSERT_NEAR(lhs, fd_accel, 1e-4 * (1.0 + std::abs(lhs)));
    }
  }
  // Position and velocity are continuous at the ZMP breakpoints.
  for (double tb : {c.phi1 * c.step_time, c.phi2 * c.step_time}) {
    EXPECT_NEAR(axis.position(tb - 1e-9), axis.position(tb + 1e-9), 1e-8);
    EXPECT_NEAR(axis.velocity(tb - 1e-9), axis.velocity(tb + 1e-9), 1e-7);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, WalkLipm,
    ::testing::Values(Case{0.0, 0.0, 0.155, 0.85, 0.40, 0.12, 0.88},      // lateral sway, Ind_O
                      Case{0.072, 0.122, 0.122, 0.85, 0.40, 0.12, 0.88},  // forward
                      Case{-0.1, 0.3, 0.05, 0.425, 0.2, 0.06, 0.44},      // bound corner
                      Case{0.0, 0.05, -0.155, 1.275, 0.6, 0.18, 0.94},
                      Case{0.0, 0.0, 0.155, 1.275, 0.2, 0.3, 0.6}));

TEST(WalkLipmSlopes, EachRampUsesItsOwnAxisAndSegment) {
  // The historical NUbots bug fed the y axis m2x before T1; with correct pairing an axis
  // whose p0 == s (no first ramp) has a flat ZMP before T1 whatever the other slopes are.
  LipmAxis axis;
  axis.solve(0.1, 0.5, 0.1, 1.0, 0.3, 0.2, 0.7);
  EXPECT_DOUBLE_EQ(axis.zmp(0.1), 0.1);
  EXPECT_NEAR(axis.zmp(0.85), 0.1 + (0.5 - 0.1) * 0.5, 1e-12);
}

}  // namespace
}  // namespace stride::fw::walk
