// MagnetometerModel: Earth field, floor disturbance, hard iron, noise, quantisation (see
// magnetometer_model.hpp for the model and its figures).
#include "stride/sim_hal/magnetometer_model.hpp"

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

void MagnetometerModel::reset(const MagnetometerSpec& spec, std::uint64_t seed,
                              const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position,
                              bool noise) {
  spec_ = spec;
  noise_ = noise;
  rng_.reseed(seed);
  const double north = rng_.uniform(-kPi, kPi);
  const double horizontal = spec.earth_field_gauss * std::cos(spec.inclination_rad);
  earth_ = {horizontal * std::cos(north), horizontal * std::sin(north),
            -spec.earth_field_gauss * std::sin(spec.inclination_rad)};
  for (int k = 0; k < 3; ++k) hard_iron_[k] = spec.hard_iron_std_gauss * rng_.normal();
  for (std::size_t k = 0; k < 3; ++k) {
    const double angle = rng_.uniform(-kPi, kPi);
    wave_direction_[k] = {std::cos(angle), std::sin(angle)};
    wave_phase_[k] = rng_.uniform(-kPi, kPi);
  }
  time_s_ = 0.0;
  next_sample_s_ = 0.0;
  take_sample(rotation, position);
}

Eigen::Vector3d MagnetometerModel::world_field(const Eigen::Vector3d& position) const {
  Eigen::Vector3d field = earth_;
  const double wavenumber = 2.0 * kPi / spec_.disturbance_wavelength_m;
  for (std::size_t k = 0; k < 3; ++k) {
    const double along = wave_direction_[k].dot(position.head<2>());
    const double amplitude = k == 2 ? 0.5 * spec_.disturbance_gauss : spec_.disturbance_gauss;
    field[static_cast<Eigen::Index>(k)] +=
        amplitude * std::sin(wavenumber * along + wave_phase_[k]);
  }
  return field;
}

void MagnetometerModel::take_sample(const Eigen::Matrix3d& rotation,
                                    const Eigen::Vector3d& position) {
  const Eigen::Vector3d body = rotation.transpose() * world_field(position) + hard_iron_;
  for (int k = 0; k < 3; ++k) {
    // The draw happens with the noise off too, so the stream depends only on time.
    const double n = rng_.normal();
    const double chip = quantise(body[k] + (noise_ ? spec_.noise_std_gauss * n : 0.0),
                                 spec_.resolution_gauss, spec_.full_scale_gauss);
    reading_[k] = quantise(chip, spec_.register_lsb_gauss, 0.0);
  }
  next_sample_s_ += 1.0 / spec_.output_rate_hz;
}

void MagnetometerModel::sample(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position,
                               double dt) {
  time_s_ += dt;
  if (next_sample_s_ <= time_s_ + 1e-12) {
    take_sample(rotation, position);
    // A period longer than the chip's interval skips the samples nobody reads.
    while (next_sample_s_ <= time_s_ + 1e-12) next_sample_s_ += 1.0 / spec_.output_rate_hz;
  }
}

}  // namespace stride::sim
