// The IMU reading from the torso's true motion (see imu_sampler.hpp).
#include "stride/sim_hal/imu_sampler.hpp"

namespace stride::sim {

void ImuSampler::reset(const ImuOptions& options, double gravity_mps2,
                       const Eigen::Vector3d& accel_bias, const Eigen::Vector3d& gyro_bias,
                       const Eigen::Matrix3d& torso_rotation,
                       const MagnetometerStart& magnetometer) {
  options_ = options;
  gravity_ = gravity_mps2;
  accel_bias_ = accel_bias;
  gyro_bias_ = gyro_bias;
  chain_ = !options.chain.is_ideal();
  reading_ = {};
  if (chain_) {
    model_.configure(options.chain);
    model_.reset(torso_rotation.transpose() * Eigen::Vector3d(0, 0, gravity_mps2),
                 Eigen::Vector3d::Zero(), accel_bias, gyro_bias);
    if (options.chain.magnetometer.present) {
      period_s_ = magnetometer.period_s;
      magnetometer_.reset(options.chain.magnetometer, magnetometer.seed, torso_rotation,
                          magnetometer.position, options.chain.noise);
      reading_.mag = magnetometer_.reading();
      reading_.has_mag = true;
    }
  }
}

Eigen::Vector3d ImuSampler::specific_force(const TorsoMotion& motion) const {
  return motion.rotation.transpose() *
         (motion.linear_acceleration + Eigen::Vector3d(0, 0, gravity_));
}

void ImuSampler::feed(const TorsoMotion& motion, double h, WorldRng& rng) {
  model_.step(specific_force(motion), motion.rotation.transpose() * motion.angular_velocity, h,
              rng);
}

void ImuSampler::sample(const TorsoMotion& motion, WorldRng& rng) {
  if (chain_) {
    reading_.accel = model_.accel();
    reading_.gyro = model_.gyro();
    if (reading_.has_mag) {
      magnetometer_.sample(motion.rotation, motion.position, period_s_);
      reading_.mag = magnetometer_.reading();
    }
    return;
  }
  Eigen::Vector3d accel_noise, gyro_noise;
  for (int k = 0; k < 3; ++k) accel_noise[k] = rng.normal();
  for (int k = 0; k < 3; ++k) gyro_noise[k] = rng.normal();
  reading_.accel = specific_force(motion) + accel_bias_ + options_.accel_noise_std * accel_noise;
  reading_.gyro = motion.rotation.transpose() * motion.angular_velocity + gyro_bias_ +
                  options_.gyro_noise_std * gyro_noise;
}

void ImuSampler::skip(WorldRng& rng) {
  if (chain_) return;
  for (int k = 0; k < 6; ++k) rng.normal();
}

}  // namespace stride::sim
