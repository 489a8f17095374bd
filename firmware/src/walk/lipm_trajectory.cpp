// Closed-form LIPM torso trajectory of one axis (equations in lipm_trajectory.hpp).
#include "stride/firmware/walk/lipm_trajectory.hpp"

#include <cmath>

namespace stride::fw::walk {

void LipmAxis::solve(double p0, double p1, double s, double step_time, double tau, double phi1,
                     double phi2) noexcept {
  tau_ = tau;
  s_ = s;
  p0_ = p0;
  t1_ = phi1 * step_time;
  t2_ = phi2 * step_time;
  m1_ = (s - p0) / t1_;
  m2_ = (p1 - s) / (step_time - t2_);
  const double c1 = -tau * m1_ * std::sinh(t1_ / tau);
  const double c2 = tau * m2_ * std::sinh((step_time - t2_) / tau);
  const double e = std::exp(step_time / tau);
  const double denominator = e - 1.0 / e;
  a_plus_ = (c2 - c1 / e) / denominator;
  a_minus_ = (c1 * e - c2) / denominator;
}

double LipmAxis::position(double t) const noexcept {
  double r = 0.0;
  if (t < t1_) {
    r = m1_ * ((t - t1_) - tau_ * std::sinh((t - t1_) / tau_));
  } else if (t > t2_) {
    r = m2_ * ((t - t2_) - tau_ * std::sinh((t - t2_) / tau_));
  }
  return s_ + a_plus_ * std::exp(t / tau_) + a_minus_ * std::exp(-t / tau_) + r;
}

double LipmAxis::velocity(double t) const noexcept {
  double r = 0.0;
  if (t < t1_) {
    r = m1_ * (1.0 - std::cosh((t - t1_) / tau_));
  } else if (t > t2_) {
    r = m2_ * (1.0 - std::cosh((t - t2_) / tau_));
  }
  return (a_plus_ * std::exp(t / tau_) - a_minus_ * std::exp(-t / tau_)) / tau_ + r;
}

double LipmAxis::acceleration(double t) const noexcept {
  double r = 0.0;
  if (t < t1_) {
    r = -m1_ * std::sinh((t - t1_) / tau_) / tau_;
  } else if (t > t2_) {
    r = -m2_ * std::sinh((t - t2_) / tau_) / tau_;
  }
  return (a_plus_ * std::exp(t / tau_) + a_minus_ * std::exp(-t / tau_)) / (tau_ * tau_) + r;
}

double LipmAxis::zmp(double t) const noexcept {
  if (t < t1_) return p0_ + m1_ * t;
  if (t > t2_) return s_ + m2_ * (t - t2_);
  return s_;
}

}  // namespace stride::fw::walk
