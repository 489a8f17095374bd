// LipmAxis: the closed-form torso (CoM) trajectory of one horizontal axis over one step, for
// the linear inverted pendulum x'' = (x - z(t)) / tau^2 driven by a piecewise-linear ZMP z(t)
// (igus.md 2.4, with the correct slope pairing).
//
// Over a step of duration T [s] with T1 = phi1*T, T2 = phi2*T:
//   z(t) ramps p0 -> s on [0, T1], holds s on [T1, T2], ramps s -> p1 on [T2, T];
//   slopes m1 = (s - p0)/T1, m2 = (p1 - s)/(T - T2)  [m/s].
//   x(t) = s + a+ e^(t/tau) + a- e^(-t/tau) + R(t),
//   R(t) = m1 [(t - T1) - tau sinh((t - T1)/tau)]  for t < T1,
//          0                                        for T1 <= t <= T2,
//          m2 [(t - T2) - tau sinh((t - T2)/tau)]  for t > T2,
//   c1 = -tau m1 sinh(T1/tau), c2 = tau m2 sinh((T - T2)/tau), E = e^(T/tau),
//   a+ = (c2 - c1/E)/(E - 1/E), a- = (c1 E - c2)/(E - 1/E),
// which meets x(0) = p0 and x(T) = p1 exactly. p0, p1, s, x, z in m; tau = walk.zmp_time [s].
#pragma once

namespace stride::fw::walk {

class LipmAxis {
 public:
  /// Solves one axis: p0 torso source, p1 torso destination, s support point [m]; T step
  /// duration, tau time constant [s]; 0 < phi1 < phi2 < 1. Inputs are assumed finite and
  /// valid (the walk parameters' bounds guarantee it).
  void solve(double p0, double p1, double s, double step_time, double tau, double phi1,
             double phi2) noexcept;

  /// Torso position x(t) [m], 0 <= t <= T [s].
  double position(double t) const noexcept;
  /// Torso velocity x'(t) [m/s].
  double velocity(double t) const noexcept;
  /// Torso acceleration x''(t) [m/s^2].
  double acceleration(double t) const noexcept;
  /// Reference ZMP z(t) [m].
  double zmp(double t) const noexcept;

  double time_constant() const noexcept { return tau_; }

 private:
  double s_ = 0.0, a_plus_ = 0.0, a_minus_ = 0.0;
  double m1_ = 0.0, m2_ = 0.0, t1_ = 0.0, t2_ = 0.0, tau_ = 1.0, p0_ = 0.0;
};

}  // namespace stride::fw::walk
