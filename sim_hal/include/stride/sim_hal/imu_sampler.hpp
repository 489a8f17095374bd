// ImuSampler: what the torso's IMU reports, from the torso's true motion, for any engine.
//
// Two kinds (ImuOptions::chain): ideal, the true specific force and rate in the torso frame
// at the end of each control period plus a fixed bias and white noise of the given standard
// deviations (six normal draws per sample, whatever the options, so that the random stream
// does not depend on them); or the robot's chain (imu_model.hpp: the chips' rates, filters,
// noise and quantisation, the CM730's sampling), fed at every physics step.
// With a magnetometer in the chain (NimbRo's CM730), the reading also holds its field
// (magnetometer_model.hpp), sampled at the end of each control period.
// Frames: world x forward, y left, z up; the reading is in the torso (root link) frame.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "stride/sim_hal/imu_model.hpp"
#include "stride/sim_hal/world_options.hpp"
#include "stride/sim_hal/world_rng.hpp"

namespace stride::sim {

/// IMU reading in the torso frame.
struct ImuReading {
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< specific force [m/s^2]
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< angular rate [rad/s]
  Eigen::Vector3d mag = Eigen::Vector3d::Zero();    ///< magnetic field [gauss]
  bool has_mag = false;                             ///< the chain has a magnetometer
};

/// The torso's true motion at one instant (world frame).
struct TorsoMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();         ///< torso to world
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();     ///< [rad/s]
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();  ///< of the origin [m/s^2]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();             ///< of the origin [m]
};

/// What the magnetometer needs at a reset: the torso's position, a seed for its own draws and
/// the control period it is sampled at.
struct MagnetometerStart {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::uint64_t seed = 0;
  double period_s = 0.01;
};

class ImuSampler {
 public:
  /// At a reset: the options, gravity, this episode's biases and the torso at rest.
  void reset(const ImuOptions& options, double gravity_mps2, const Eigen::Vector3d& accel_bias,
             const Eigen::Vector3d& gyro_bias, const Eigen::Matrix3d& torso_rotation,
             const MagnetometerStart& magnetometer = {});
  /// True when the chain wants every physics step (feed()).
  bool needs_steps() const { return chain_; }
  /// One physics step of length h into the chain (motion at the step's start, acceleration
  /// over the step).
  void feed(const TorsoMotion& motion, double h, WorldRng& rng);
  /// The reading at the end of a control period (motion at that instant).
  void sample(const TorsoMotion& motion, WorldRng& rng);
  /// Draws the ideal sampler's noise without a reading (an ended episode keeps the stream).
  void skip(WorldRng& rng);
  const ImuReading& reading() const { return reading_; }

 private:
  Eigen::Vector3d specific_force(const TorsoMotion& motion) const;

  ImuOptions options_;
  double gravity_ = 9.81;
  Eigen::Vector3d accel_bias_ = Eigen::Vector3d::Zero(), gyro_bias_ = Eigen::Vector3d::Zero();
  bool chain_ = false;
  ImuModel model_;
  MagnetometerModel magnetometer_;
  double period_s_ = 0.01;
  ImuReading reading_;
};

}  // namespace stride::sim
