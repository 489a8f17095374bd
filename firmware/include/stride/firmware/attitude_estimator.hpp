// AttitudeEstimator: the torso's attitude, one estimate for the whole firmware (in the manner of
// ArduPilot's AP_AHRS: one estimator that every user reads, not one filter per user).
//
// Updated once per control tick by the Controller, before anything reads it; read by the
// walk's balance feedback, capture step, heading hold and magnetic heading, by the fall
// predictor, and (host side) by the log replay, which runs the same estimator over a flight
// log's IMU readings.
//
// Theory. The estimate is the world's up direction u seen in the torso frame (unit vector;
// upright u = (0, 0, 1)). The torso frame is x forward, y left, z up; the gyro g [rad/s] reads
// the torso's angular velocity in it, and the accelerometer f [m/s^2] the specific force, which
// still and upright is (0, 0, +9.81) (hal/sensor_frame.hpp). A direction fixed in the world,
// seen from a frame turning at w, moves as du/dt = -w x u. The filter is Mahony's explicit
// complementary filter on the sphere (Mahony, Hamel & Pflimlin, IEEE TAC 53(5), 2008) reduced
// to the direction of gravity:
//     w = g - b - k_p (u x f/|f|),     u <- normalise(u - dt w x u),
//     b <- b + dt k_i (u x f/|f|)                       (only when the gyro bias is learnt)
// k_p = 1 / tau: for small errors u follows the accelerometer's direction with the first-order
// time constant tau [s] (walk.balance.tilt_filter_time) and the gyro's over shorter times, as a
// complementary filter with that time constant does. k_i = k_p^2 / 4 (critically damped).
// The accelerometer is a measure of gravity only while the torso does not accelerate much: it
// is ignored (gyro only) when |f| is outside [0.5 g, 1.5 g] (a step's impact, a fall, a push)
// or not finite. The bias b learns only what the error u x f sees, the gyro's bias about the
// horizontal axes (its yaw bias is not observable from gravity); the log replay learns it, the
// firmware does not (none of its estimates ever did).
//
// Outputs: roll = atan2(u_y, u_z) (positive about +x, leaning right), pitch =
// atan2(-u_x, hypot(u_y, u_z)) (positive about +y, nose down), both [rad]; the vertical rate
// u . (g - b) [rad/s], the rotation rate about the world's vertical (positive turning left),
// which is what a heading integrates. Before the first finite accelerometer reading within the
// window the estimate is not valid() and reads upright.
//
// Parameter: walk.balance.tilt_filter_time [s], 0.05-10, default 0.8442 (the name is the one
// the balance feedback's own filter had, kept because parameter files, genomes and optimiser
// configurations set it). It is the only time constant of the attitude.
// Real-time: update() does no I/O, reads no clock and allocates nothing.
#pragma once

#include <Eigen/Core>

#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw {

class AttitudeEstimator {
 public:
  /// Default of walk.balance.tilt_filter_time [s].
  static constexpr double kDefaultTimeConstantS = 0.8442;
  /// The accelerometer is used while its norm is within [kMinG, kMaxG] x 9.81 m/s^2.
  static constexpr double kMinG = 0.5, kMaxG = 1.5;

  /// The firmware's estimator: registers walk.balance.tilt_filter_time and reads it every tick
  /// (start-up only; throws on a name clash). No gyro bias learning.
  AttitudeEstimator(ParameterStore& store, double period_s);
  /// A host-side estimator with a fixed time constant [s] (the log replay).
  AttitudeEstimator(double period_s, double time_constant_s, bool learn_gyro_bias);

  /// Forgets the estimate (not valid until the next usable accelerometer reading).
  void reset() noexcept;
  /// Starts from the accelerometer alone (up along f), no bias; invalid f: upright.
  void start(const Eigen::Vector3d& accel) noexcept;
  /// One control tick.
  void update(const hal::Cm730State& imu) noexcept;
  void update(const Eigen::Vector3d& accel, const Eigen::Vector3d& gyro) noexcept;

  /// True once an accelerometer reading has set the estimate.
  bool valid() const noexcept { return valid_; }
  /// World up in the torso frame (unit).
  const Eigen::Vector3d& up() const noexcept { return up_; }
  double roll() const noexcept;
  double pitch() const noexcept;
  /// The tilt of this tick's accelerometer reading alone (no filter; 0 until a finite one)
  /// [rad], for a reference taken from one sample, as the balance feedback's start does.
  double measured_roll() const noexcept { return measured_roll_; }
  double measured_pitch() const noexcept { return measured_pitch_; }
  /// This tick's gyro reading [rad/s] (non-finite components read 0), before the bias.
  const Eigen::Vector3d& gyro() const noexcept { return gyro_; }
  /// Learnt gyro bias [rad/s] (zero unless learnt).
  const Eigen::Vector3d& gyro_bias() const noexcept { return bias_; }
  /// Rotation rate about the world's vertical, u . (g - b) [rad/s] (positive: turning left).
  double vertical_rate() const noexcept { return up_.dot(gyro_ - bias_); }
  /// The time constant in use [s].
  double time_constant() const noexcept;

 private:
  const ParameterStore* store_ = nullptr;
  ParamHandle time_constant_{};
  double period_s_;
  double fixed_time_constant_s_ = kDefaultTimeConstantS;
  bool learn_bias_ = false;
  bool valid_ = false;
  Eigen::Vector3d up_ = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_ = Eigen::Vector3d::Zero();
  double measured_roll_ = 0.0, measured_pitch_ = 0.0;
};

}  // namespace stride::fw
