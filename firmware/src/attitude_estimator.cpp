// AttitudeEstimator (theory and units in the header).
#include "stride/firmware/attitude_estimator.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace stride::fw {
namespace {

constexpr double kGravity = 9.81;

}  // namespace

AttitudeEstimator::AttitudeEstimator(ParameterStore& store, double period_s)
    : store_(&store), period_s_(period_s) {
  time_constant_ =
      store.add_real("walk.balance.tilt_filter_time", kDefaultTimeConstantS, 0.05, 10.0, "s",
                     "time constant of the torso attitude estimate (the accelerometer's pull on "
                     "the integrated gyro) that every user of the attitude reads");
}

AttitudeEstimator::AttitudeEstimator(double period_s, double time_constant_s, bool learn_gyro_bias)
    : period_s_(period_s), fixed_time_constant_s_(time_constant_s), learn_bias_(learn_gyro_bias) {}

double AttitudeEstimator::time_constant() const noexcept {
  return store_ ? store_->value(time_constant_) : fixed_time_constant_s_;
}

void AttitudeEstimator::reset() noexcept {
  valid_ = false;
  up_ = Eigen::Vector3d::UnitZ();
  bias_.setZero();
  gyro_.setZero();
}

void AttitudeEstimator::start(const Eigen::Vector3d& accel) noexcept {
  const double n = accel.norm();
  valid_ = n > 1e-6 && accel.allFinite();
  up_ = valid_ ? Eigen::Vector3d(accel / n) : Eigen::Vector3d::UnitZ();
  bias_.setZero();
}

void AttitudeEstimator::update(const hal::Cm730State& imu) noexcept {
  update(Eigen::Vector3d(imu.accel_mps2[0], imu.accel_mps2[1], imu.accel_mps2[2]),
         Eigen::Vector3d(imu.gyro_rad_s[0], imu.gyro_rad_s[1], imu.gyro_rad_s[2]));
}

void AttitudeEstimator::update(const Eigen::Vector3d& accel, const Eigen::Vector3d& gyro) noexcept {
  for (int i = 0; i < 3; ++i) gyro_[i] = std::isfinite(gyro[i]) ? gyro[i] : 0.0;
  const double n = accel.norm();
  if (accel.allFinite() && accel.z() > 1.0) {
    measured_roll_ = std::atan2(accel.y(), accel.z());
    measured_pitch_ = std::atan2(-accel.x(), std::hypot(accel.y(), accel.z()));
  }
  const bool accel_ok = accel.allFinite() && n > kMinG * kGravity && n < kMaxG * kGravity;
  if (!valid_) {
    if (accel_ok) {
      up_ = accel / n;
      valid_ = true;
    }
    return;
  }
  const double kp = 1.0 / time_constant();
  const Eigen::Vector3d error =
      accel_ok ? Eigen::Vector3d(up_.cross(accel / n)) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d w = gyro_ - bias_ - kp * error;
  up_ = (up_ - period_s_ * w.cross(up_)).normalized();
  if (learn_bias_) bias_ += period_s_ * 0.25 * kp * kp * error;
}

double AttitudeEstimator::roll() const noexcept {
  return std::atan2(up_.y(), up_.z());
}

double AttitudeEstimator::pitch() const noexcept {
  return std::atan2(-up_.x(), std::hypot(up_.y(), up_.z()));
}

}  // namespace stride::fw
