// HeadingHold: keeps a walk that is commanded not to turn on its heading, by feeding the
// gyro's integrated yaw back into the turn velocity of each planned step. Without it the
// open-loop walk goes straight only as far as the contact model holds the feet (an independent
// MuJoCo model of the robot turns the stock walk by up to 1.5 rad over 2.5 m; issue 22).
// Parameters walk.balance.heading_* (not in the 46-parameter genome; heading_gain 0 = off).
//
// Per tick, the world yaw rate is the firmware's attitude estimate's vertical rate
// (attitude_estimator.hpp): with the world's up direction u seen in the torso frame and the
// torso gyro g [rad/s],
//   r = u . g                                                                            [rad/s]
// (upright u = (0, 0, 1) and r = g_z; the torso pitched forward by theta gives
// r = cos(theta) g_z - sin(theta) g_x).
// During the start blend (the robot stands) r is averaged into a bias b. Afterwards, while no
// turn is commanded, the heading error integrates e += (r - b) dt, and a low-pass
//   r_f += alpha (r - b - r_f), alpha = dt / (dt + heading_filter_time)
// follows the yaw rate. At each step start the step's turn velocity gets
//   correction = clamp(-heading_gain e2 - heading_rate_gain r_f, +-heading_max_correction)
// [rad/step], where e2 is the mean of e over the last two steps: the torso yaws to and fro by
// a few degrees once per step pair (measured in the simulator: about +-4 deg), and e sampled at
// the step start would catch the left steps at one end of that swing and the right steps at
// the other (the step limits let a left step turn only left and a right step only right, so
// the hold would rectify the swing into a turn). While a turn is commanded the reference follows
// the robot (e = 0): the hold keeps the heading the robot has when the turn command returns to 0.
// With a magnetometer (the CM730 with NimbRo's firmware) and walk.balance.heading_mag_time > 0,
// e is instead the fused heading's change since the hold's reference (magnetic_heading.hpp):
// the gyro's yaw corrected towards the magnetometer's, so a gyro bias does not turn the walk.
// Without one, every figure is the gyro-only one above, to the bit.
// Real-time: update() and correction() allocate nothing and do no I/O.
#pragma once

#include <string_view>

#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/walk/magnetic_heading.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::walk {

class HeadingHold {
 public:
  /// Registers PREFIX.balance.heading_* (walk.balance.* for the seed's engine,
  /// walk.spline.balance.* for the spline walk; start-up only; throws on a name clash).
  HeadingHold(ParameterStore& store, double period_s, std::string_view prefix = "walk");

  /// At the walk's start: clears the bias estimate, the heading error and the filter.
  void reset() noexcept;
  /// One tick. `calibrating`: the robot stands (start blend), the sample goes into the bias;
  /// `hold`: no turn is commanded, the error integrates (otherwise it is cleared).
  /// `attitude` is the firmware's estimate, already updated with `imu` (the magnetometer's
  /// reading is taken from `imu`).
  void update(const AttitudeEstimator& attitude, const hal::Cm730State& imu, bool calibrating,
              bool hold) noexcept;
  /// At a step start: closes the step's averaging window and returns the turn velocity to add
  /// to the new step [rad/step] (0 while a turn is commanded, during the start blend, and when
  /// heading_gain and heading_rate_gain are 0).
  double begin_step() noexcept;
  /// The two-step mean heading error the latest begin_step() used [rad].
  double step_pair_mean() const noexcept { return step_pair_mean_; }
  /// Integrated heading error since the hold's reference [rad] (positive: turned left).
  double heading_error() const noexcept { return error_; }
  /// Gyro yaw-rate bias estimated during the start blend [rad/s].
  double bias() const noexcept { return bias_samples_ > 0 ? bias_sum_ / bias_samples_ : 0.0; }
  /// The gyro and magnetometer heading (used when the CM730 has a magnetometer).
  const MagneticHeading& magnetic() const noexcept { return magnetic_; }
  /// True when the latest update() used the magnetometer.
  bool using_magnetometer() const noexcept { return using_magnetometer_; }

 private:
  const ParameterStore& store_;
  double period_s_;
  ParamHandle gain_, rate_gain_, filter_time_, max_correction_;
  double bias_sum_ = 0.0;
  int bias_samples_ = 0;
  double error_ = 0.0;
  double rate_ = 0.0;
  bool holding_ = false;
  double window_sum_ = 0.0;  // sum of e over the ticks of the current step
  int window_ticks_ = 0;
  double previous_mean_ = 0.0, step_pair_mean_ = 0.0;
  bool previous_mean_valid_ = false;
  MagneticHeading magnetic_;
  bool using_magnetometer_ = false;
  bool reference_valid_ = false;
  double reference_ = 0.0;  // fused heading when the hold began [rad]
};

}  // namespace stride::fw::walk
