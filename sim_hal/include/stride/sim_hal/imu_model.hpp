// ImuModel: the igus robot's IMU as the controller sees it through the CM730 (engine-agnostic:
// it takes the torso's true specific force and angular rate every physics step).
//
// Chain, per axis (figures from the chips' datasheets and the CM730 firmware of the igus
// software, humanoid_op_ros cm730/firmware gyro_acc.c, which configures both chips):
//  - gyro: STMicroelectronics L3G4200D at ODR 400 Hz, output of its fixed low-pass LPF1
//    (about 93 Hz), rate noise density 0.03 dps/sqrt(Hz), 16-bit;
//  - accelerometer: STMicroelectronics LIS331DLH at ODR 100 Hz, analog low-pass 74 Hz, +-4 g,
//    noise density 218 ug/sqrt(Hz), 12 bits (2 mg/digit at +-4 g);
//  - each chip is a first-order low-pass on the true signal, sampled and held at its output
//    data rate, with white noise of the density over the filter's noise bandwidth
//    (pi/2 x cut-off) and the chip's quantisation and range;
//  - the CM730 reads both chips at 259.3 Hz and reports the mean of its last 5 readings;
//  - the register the controller reads is quantised to the CM730 control table's unit: the
//    stock table that Stride's serial HAL reads (igus.md 6.4: 10 bits, 4 g / 512 per LSB,
//    1800 deg/s / 512 per LSB), clipped to its range.
// NimbRo's CM730 firmware (ImuChain::cm730_nimbro(), `--imu cm730-nimbro`, igus.md 6.5) reads
// the same chips but reports signed 16-bit registers: gyro (pi/180) 500/65536 rad/s per LSB,
// accelerometer 2*4*9.81/65536 m/s^2 per LSB, and adds a magnetometer (magnetometer_model.hpp).
// Its sampling and averaging are taken to be the stock firmware's (not documented otherwise).
// Bias: a fixed offset per episode (what remains after the robot's start-up calibration),
// drawn by the world. Noise draws: three per chip sample, so the random stream depends only on
// time, not on the options.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stride/sim_hal/magnetometer_model.hpp"
#include "stride/sim_hal/world_rng.hpp"

namespace stride::sim {

struct ImuChip {
  double output_rate_hz = 100.0;
  double cutoff_hz = 74.0;     ///< first-order low-pass before sampling
  double noise_density = 0.0;  ///< per sqrt(Hz), in the output unit
  double resolution = 0.0;     ///< chip LSB in the output unit (0: none)
  double full_scale = 0.0;     ///< +- range in the output unit (0: none)
};

struct ImuChain {
  ImuChip gyro{400.0, 93.0, 0.03 * 3.14159265358979323846 / 180.0,
               0.00875 * 3.14159265358979323846 / 180.0, 250.0 * 3.14159265358979323846 / 180.0};
  ImuChip accel{100.0, 74.0, 218e-6 * 9.80665, 0.002 * 9.80665, 4.0 * 9.80665};
  double cm730_read_rate_hz = 259.3;
  int cm730_average = 5;  ///< readings averaged (1..8)
  double gyro_register_lsb = 1800.0 * 3.14159265358979323846 / 180.0 / 512.0;  ///< [rad/s]
  double accel_register_lsb = 4.0 * 9.80665 / 512.0;                           ///< [m/s^2]
  double register_half_range = 512.0;  ///< LSBs either side of zero
  bool noise = false;                  ///< chip noise on (the draws happen either way)
  MagnetometerSpec magnetometer{};     ///< present only with NimbRo's firmware
  /// The chain with NimbRo's CM730 firmware: 16-bit registers at its scales, a magnetometer.
  static ImuChain cm730_nimbro();
  /// The ideal sensor: every stage off, the reading is the true value at the period's end
  /// (SimWorld then adds ImuOptions' white noise per period, the model before the chain).
  static ImuChain ideal();
  bool is_ideal() const;
};

class ImuModel {
 public:
  void configure(const ImuChain& chain) { chain_ = chain; }
  const ImuChain& chain() const { return chain_; }
  /// Starts at rest reading (accel, gyro) with the given per-episode biases.
  void reset(const Eigen::Vector3d& accel, const Eigen::Vector3d& gyro,
             const Eigen::Vector3d& accel_bias, const Eigen::Vector3d& gyro_bias);
  /// One physics step of length h [s] ending with the true torso-frame specific force
  /// [m/s^2] and angular rate [rad/s]; draws the chips' noise from `rng`.
  void step(const Eigen::Vector3d& accel, const Eigen::Vector3d& gyro, double h, WorldRng& rng);
  /// What the CM730's registers hold now, in SI units.
  Eigen::Vector3d accel() const { return register_accel_; }
  Eigen::Vector3d gyro() const { return register_gyro_; }

 private:
  struct ChipState {
    Eigen::Vector3d filtered = Eigen::Vector3d::Zero();
    Eigen::Vector3d output = Eigen::Vector3d::Zero();  ///< held sample
    double next_sample_s = 0.0;
  };
  void sample_chip(const ImuChip& chip, ChipState& state, const Eigen::Vector3d& bias,
                   WorldRng& rng) const;
  void read_chips();

  ImuChain chain_{};
  ChipState gyro_, accel_;
  Eigen::Vector3d gyro_bias_ = Eigen::Vector3d::Zero(), accel_bias_ = Eigen::Vector3d::Zero();
  double time_s_ = 0.0, next_read_s_ = 0.0;
  std::array<Eigen::Vector3d, 8> gyro_reads_{}, accel_reads_{};
  int reads_ = 0;  ///< readings taken so far (the ring holds the last cm730_average)
  Eigen::Vector3d register_accel_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d register_gyro_ = Eigen::Vector3d::Zero();
};

}  // namespace stride::sim
