// Gyro and magnetometer heading fusion (equations in magnetic_heading.hpp).
#include "stride/firmware/walk/magnetic_heading.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace stride::fw::walk {
namespace {

constexpr double kPi = 3.14159265358979323846;

double wrap(double angle) {
  return angle - 2.0 * kPi * std::floor((angle + kPi) / (2.0 * kPi));
}

bool finite3(const std::array<double, 3>& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

}  // namespace

MagneticHeading::MagneticHeading(ParameterStore& store, double period_s, std::string_view prefix)
    : store_(store), period_s_(period_s) {
  const std::string p(prefix);
  time_ = store.add_real(p + ".balance.heading_mag_time", 10.0, 0.0, 60.0, "s",
                         "time constant over which the heading hold's heading follows the "
                         "magnetometer rather than the gyro (0: magnetometer unused)");
  bias_time_ = store.add_real(p + ".balance.heading_mag_bias_time", 0.0, 0.0, 300.0, "s",
                              "time constant of the gyro yaw bias learnt from the magnetometer "
                              "(0: not learnt, the default)");
}

void MagneticHeading::reset() noexcept {
  valid_ = false;
  heading_ = magnetic_ = 0.0;
  bias_ = bias_sum_ = 0.0;
  bias_samples_ = 0;
}

bool MagneticHeading::active(const hal::Cm730State& imu) const noexcept {
  return imu.has_magnetometer && store_.value(time_) > 0.0;
}

double MagneticHeading::tilt_compensated_heading(const std::array<double, 3>& m, double roll,
                                                 double pitch) noexcept {
  const double cr = std::cos(roll), sr = std::sin(roll);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  const double lx = m[0] * cp + (m[1] * sr + m[2] * cr) * sp;
  const double ly = m[1] * cr - m[2] * sr;
  return -std::atan2(ly, lx);
}

void MagneticHeading::update(const AttitudeEstimator& attitude, const hal::Cm730State& imu,
                             bool calibrating) noexcept {
  const bool mag_ok = finite3(imu.mag_gauss) &&
                      std::hypot(imu.mag_gauss[0], imu.mag_gauss[1], imu.mag_gauss[2]) > 1e-6;
  const double dt = period_s_;
  if (!attitude.valid()) return;
  const double roll = attitude.roll(), pitch = attitude.pitch();
  if (!valid_) {
    if (!mag_ok) return;
    magnetic_ = tilt_compensated_heading(imu.mag_gauss, roll, pitch);
    heading_ = magnetic_;
    valid_ = true;
    return;
  }
  const double yaw_rate = attitude.vertical_rate();
  if (calibrating) {
    bias_sum_ += yaw_rate;
    ++bias_samples_;
    bias_ = bias_sum_ / bias_samples_;
  }
  heading_ += (yaw_rate - bias_) * dt;
  if (!mag_ok) return;
  magnetic_ = tilt_compensated_heading(imu.mag_gauss, roll, pitch);
  const double innovation = wrap(magnetic_ - heading_);
  const double time = store_.value(time_);
  if (!(time > 0.0)) return;
  heading_ += innovation * dt / time;
  const double bias_time = store_.value(bias_time_);
  if (bias_time > 0.0 && !calibrating) bias_ -= innovation * dt / (time * bias_time);
}

}  // namespace stride::fw::walk
