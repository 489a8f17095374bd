// MagneticHeading: the torso's heading from the gyro fused with the magnetometer's
// tilt-compensated heading, for the heading hold when the CM730 has a magnetometer (NimbRo's
// firmware, igus.md 6.5). Parameters walk.balance.heading_mag_* (not in the genome).
//
// Per tick, from the firmware's attitude estimate (attitude_estimator.hpp: the torso's roll phi
// and pitch theta, pitch positive nose down, and the rotation rate w about the world's
// vertical) and the magnetometer m in the torso frame:
//  - magnetic heading: the field m levelled by the tilt,
//      l_x = m_x cos theta + (m_y sin phi + m_z cos phi) sin theta,
//      l_y = m_y cos phi - m_z sin phi,
//    gives psi_m = -atan2(l_y, l_x) (anticlockwise positive, zero at magnetic north);
//  - fusion (a complementary filter, second order when the bias is learnt): with the
//    innovation e = wrap(psi_m - psi),
//      psi += (w - b) dt + e dt / heading_mag_time,
//      b -= e dt / (heading_mag_time heading_mag_bias_time)   (heading_mag_bias_time > 0 only),
//    psi continuous (not wrapped), b the gyro's yaw bias (its start: the mean of w while the
//    robot stands). The heading follows the gyro over times shorter than heading_mag_time and the
//    magnetometer over longer ones. A gyro bias the stand did not learn leaves an error of
//    b heading_mag_time (bounded, where the gyro alone drifts without bound); learning b
//    removes it. heading_mag_time 0 turns the magnetometer off.
// Defaults, measured in the simulator (tests/bench/RESULTS.md, forward walk 20 s, 6 seeds, floor
// disturbance 0.03 gauss; mean |heading change| in rad): heading_mag_time 10 s and no bias
// learning (0.07), against 2 s (0.23; 0.19 learning the bias over 10 s), 10 s learning it over
// 10 s (0.10) or 30 s (0.19), the magnetometer unused (0.11) and the stock table (0.20).
// NimbRo's 16-bit gyro learns its bias standing, so the magnetometer is needed only against slow
// drift, and a field that varies along the path looks like a turn: a short time constant
// follows the floor's field, a learnt bias takes its gradient for the gyro's.
// Real-time: update() allocates nothing and does no I/O.
#pragma once

#include <string_view>

#include <array>

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::walk {

class MagneticHeading {
 public:
  /// Registers PREFIX.balance.heading_mag_* (PREFIX: "walk", or "walk.spline" for the spline walk;
  /// start-up only; throws on a name clash).
  MagneticHeading(ParameterStore& store, double period_s, std::string_view prefix = "walk");

  /// At the walk's start: forgets the heading and the bias.
  void reset() noexcept;
  /// True when the heading hold should use this estimate: a magnetometer reading and
  /// heading_mag_time > 0.
  bool active(const hal::Cm730State& imu) const noexcept;
  /// One tick, after `attitude` was updated with `imu`. `calibrating`: the robot stands; the
  /// yaw rate's mean becomes the bias.
  void update(const AttitudeEstimator& attitude, const hal::Cm730State& imu,
              bool calibrating) noexcept;
  /// Fused heading [rad], continuous (not wrapped).
  double heading() const noexcept { return heading_; }
  /// Tilt-compensated magnetic heading of the latest tick [rad], in (-pi, pi].
  double magnetic_heading() const noexcept { return magnetic_; }
  /// Estimated gyro yaw-rate bias [rad/s].
  double bias() const noexcept { return bias_; }

  /// psi_m of a field `mag` [any unit] in the torso frame tilted by roll and pitch [rad].
  static double tilt_compensated_heading(const std::array<double, 3>& mag, double roll,
                                         double pitch) noexcept;

 private:
  const ParameterStore& store_;
  double period_s_;
  ParamHandle time_, bias_time_;
  bool valid_ = false;
  double heading_ = 0.0, magnetic_ = 0.0;
  double bias_ = 0.0, bias_sum_ = 0.0;
  int bias_samples_ = 0;
};

}  // namespace stride::fw::walk
