// ImuModel: chip low-pass, output data rate, noise, quantisation; CM730 sampling and averaging.
#include "stride/sim_hal/imu_model.hpp"

#include <algorithm>
#include <cmath>

namespace stride::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

double quantise(double value, double lsb, double full_scale) {
  if (full_scale > 0.0) value = std::clamp(value, -full_scale, full_scale);
  return lsb > 0.0 ? std::round(value / lsb) * lsb : value;
}

}  // namespace

ImuChain ImuChain::ideal() {
  ImuChain c;
  c.gyro = {0.0, 0.0, 0.0, 0.0, 0.0};
  c.accel = {0.0, 0.0, 0.0, 0.0, 0.0};
  c.cm730_read_rate_hz = 0.0;
  c.cm730_average = 1;
  c.gyro_register_lsb = 0.0;
  c.accel_register_lsb = 0.0;
  c.register_half_range = 0.0;
  c.noise = false;
  return c;
}

ImuChain ImuChain::cm730_nimbro() {
  ImuChain c;
  c.gyro_register_lsb = kPi / 180.0 * 500.0 / 65536.0;
  c.accel_register_lsb = 2.0 * 4.0 * 9.81 / 65536.0;
  c.register_half_range = 32768.0;
  c.magnetometer.present = true;
  return c;
}

bool ImuChain::is_ideal() const {
  return gyro.output_rate_hz <= 0.0;
}

void ImuModel::reset(const Eigen::Vector3d& accel, const Eigen::Vector3d& gyro,
                     const Eigen::Vector3d& accel_bias, const Eigen::Vector3d& gyro_bias) {
  accel_bias_ = accel_bias;
  gyro_bias_ = gyro_bias;
  time_s_ = 0.0;
  next_read_s_ = 0.0;
  reads_ = 0;
  for (ChipState* s : {&gyro_, &accel_}) s->next_sample_s = 0.0;
  gyro_.filtered = gyro;
  accel_.filtered = accel;
  gyro_.output = gyro + gyro_bias;
  accel_.output = accel + accel_bias;
  register_accel_ = accel + accel_bias;
  register_gyro_ = gyro + gyro_bias;
  if (!chain_.is_ideal()) read_chips();
}

void ImuModel::sample_chip(const ImuChip& chip, ChipState& s, const Eigen::Vector3d& bias,
                           WorldRng& rng) const {
  const double noise_std = chip.noise_density * std::sqrt(0.5 * kPi * chip.cutoff_hz);
  for (int k = 0; k < 3; ++k) {
    const double noise = rng.normal();
    const double value = s.filtered[k] + bias[k] + (chain_.noise ? noise_std * noise : 0.0);
    s.output[k] = quantise(value, chip.resolution, chip.full_scale);
  }
}

void ImuModel::read_chips() {
  const int n = std::clamp(chain_.cm730_average, 1, 8);
  const auto slot = static_cast<std::size_t>(reads_ % n);
  gyro_reads_[slot] = gyro_.output;
  accel_reads_[slot] = accel_.output;
  ++reads_;
  const int count = std::min(reads_, n);
  Eigen::Vector3d gyro_sum = Eigen::Vector3d::Zero(), accel_sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < count; ++i) {
    gyro_sum += gyro_reads_[static_cast<std::size_t>(i)];
    accel_sum += accel_reads_[static_cast<std::size_t>(i)];
  }
  const double gyro_range = chain_.register_half_range * chain_.gyro_register_lsb;
  const double accel_range = chain_.register_half_range * chain_.accel_register_lsb;
  for (int k = 0; k < 3; ++k) {
    register_gyro_[k] = quantise(gyro_sum[k] / count, chain_.gyro_register_lsb, gyro_range);
    register_accel_[k] = quantise(accel_sum[k] / count, chain_.accel_register_lsb, accel_range);
  }
}

void ImuModel::step(const Eigen::Vector3d& accel, const Eigen::Vector3d& gyro, double h,
                    WorldRng& rng) {
  time_s_ += h;
  if (chain_.is_ideal()) {
    register_accel_ = accel + accel_bias_;
    register_gyro_ = gyro + gyro_bias_;
    return;
  }
  // Chip filters (exact first-order discretisation over h).
  gyro_.filtered +=
      (1.0 - std::exp(-2.0 * kPi * chain_.gyro.cutoff_hz * h)) * (gyro - gyro_.filtered);
  accel_.filtered +=
      (1.0 - std::exp(-2.0 * kPi * chain_.accel.cutoff_hz * h)) * (accel - accel_.filtered);
  // Chip samples and CM730 reads due by now (several per step when the step is long).
  const double eps = 1e-12;
  while (true) {
    const double next = std::min({gyro_.next_sample_s, accel_.next_sample_s, next_read_s_});
    if (next > time_s_ + eps) break;
    if (gyro_.next_sample_s <= next + eps) {
      sample_chip(chain_.gyro, gyro_, gyro_bias_, rng);
      gyro_.next_sample_s += 1.0 / chain_.gyro.output_rate_hz;
    }
    if (accel_.next_sample_s <= next + eps) {
      sample_chip(chain_.accel, accel_, accel_bias_, rng);
      accel_.next_sample_s += 1.0 / chain_.accel.output_rate_hz;
    }
    if (next_read_s_ <= next + eps) {
      read_chips();
      next_read_s_ += 1.0 / chain_.cm730_read_rate_hz;
    }
  }
}

}  // namespace stride::sim
