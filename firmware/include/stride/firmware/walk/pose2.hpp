// Pose2: a pose in the walk plane (x [m], y [m], theta [rad]) with the SE(2) operations the
// walk engine's footstep planner uses (UPenn/NUbots "uX" poses).
//   compose(a, b)  = a (+) b : b given in a's frame, returned in the world frame
//   relative(a, b) = a^-1 (+) b : b expressed in a's frame
//   interpolate(a, b, f)     : componentwise, the angle along the shorter arc
#pragma once

#include <cmath>
#include <numbers>

namespace stride::fw::walk {

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

/// Wraps an angle into (-pi, pi].
inline double wrap_angle(double angle) noexcept {
  const double two_pi = 2.0 * std::numbers::pi;
  double a = std::fmod(angle, two_pi);
  if (a > std::numbers::pi) a -= two_pi;
  if (a <= -std::numbers::pi) a += two_pi;
  return a;
}

inline Pose2 compose(const Pose2& a, const Pose2& b) noexcept {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, wrap_angle(a.theta + b.theta)};
}

inline Pose2 relative(const Pose2& a, const Pose2& b) noexcept {
  const double c = std::cos(a.theta);
  const double s = std::sin(a.theta);
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, wrap_angle(b.theta - a.theta)};
}

inline Pose2 interpolate(const Pose2& a, const Pose2& b, double f) noexcept {
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y),
          wrap_angle(a.theta + f * wrap_angle(b.theta - a.theta))};
}

}  // namespace stride::fw::walk
