// MagnetometerModel: the 3-axis magnetometer of the CM730 with NimbRo's firmware (igus.md 6.5),
// as the controller reads it, from the torso's true pose (engine-agnostic).
//
// The field at the torso, in the world frame (x forward at the start, y left, z up):
//   B = B_earth + d(p),   B_earth = F (cos I cos a, cos I sin a, -sin I),
// with F the Earth's total field and I its inclination (northern hemisphere: the field points
// down), a the direction of magnetic north from the world's x axis (drawn per episode), and
// d(p) the floor's disturbance at the torso's horizontal position p: per axis
//   d_k(p) = A sin(2 pi (u_k . p) / L + phi_k)  (z: A/2),
// unit directions u_k and phases phi_k drawn per episode, amplitude A, wavelength L.
// The chip reads, in the torso frame, R^T B + h + n: h a constant hard-iron offset per episode
// (the robot's own magnetised parts after a calibration; drawn N(0, hard_iron_std) per axis),
// n white noise (noise_std per axis and sample); sampled and held at output_rate_hz, quantised
// to the chip's resolution within its range, then to the register's LSB.
// Figures (MagnetometerSpec's defaults, README "Magnetometer"):
//  - chip: NimbRo's scale 1/820 gauss per LSB is the Honeywell HMC5883L's gain at its +-1.9 Ga
//    setting (datasheet table "Configuration Register B": 820 LSb/Gauss, output -2048..2047),
//    so the chip is taken to be an HMC5883L (an assumption: the board's part list was not
//    found); its noise floor 2 milli-gauss (datasheet), its fastest continuous rate 75 Hz;
//  - Earth: F = 0.49 gauss, I = 66 deg (the World Magnetic Model near Bonn, where the igus
//    platform's NimbRo team plays: about 49 uT total, inclination 65-66 deg);
//  - hard iron after calibration 0.01 gauss per axis, floor disturbance A = 0.03 gauss over
//    L = 3 m (an assumption of the order indoor surveys report near reinforced floors: a few uT
//    over metres).
// Random draws come from the model's own generator (seeded by the world), so turning the
// magnetometer on changes no other draw of the world.
#pragma once

#include <array>

#include <Eigen/Core>

#include "stride/sim_hal/world_rng.hpp"

namespace stride::sim {

struct MagnetometerSpec {
  bool present = false;
  double output_rate_hz = 75.0;           ///< HMC5883L continuous mode, fastest rate
  double noise_std_gauss = 0.002;         ///< HMC5883L noise floor
  double resolution_gauss = 1.0 / 820.0;  ///< chip LSB at +-1.9 Ga
  double full_scale_gauss = 2048.0 / 820.0;
  double register_lsb_gauss = 1.0 / 820.0;  ///< NimbRo's MAG scale (igus.md 6.5)
  double earth_field_gauss = 0.49;
  double inclination_rad = 66.0 * 3.14159265358979323846 / 180.0;
  double hard_iron_std_gauss = 0.01;
  double disturbance_gauss = 0.03;
  double disturbance_wavelength_m = 3.0;
};

class MagnetometerModel {
 public:
  /// At a reset: draws this episode's north direction, hard-iron offset and disturbance from a
  /// generator seeded with `seed`, and takes a first sample of the torso at rest.
  void reset(const MagnetometerSpec& spec, std::uint64_t seed, const Eigen::Matrix3d& rotation,
             const Eigen::Vector3d& position, bool noise);
  /// The end of a control period of `dt` seconds: samples again when the chip's next sample is
  /// due (sample and hold at output_rate_hz).
  void sample(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position, double dt);
  /// The register's reading in the torso frame [gauss].
  const Eigen::Vector3d& reading() const { return reading_; }
  /// The field in the world frame at horizontal position `position` [gauss] (no noise).
  Eigen::Vector3d world_field(const Eigen::Vector3d& position) const;
  /// The Earth's field alone in the world frame this episode [gauss].
  const Eigen::Vector3d& earth_field() const { return earth_; }
  const Eigen::Vector3d& hard_iron() const { return hard_iron_; }

 private:
  void take_sample(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& position);

  MagnetometerSpec spec_;
  WorldRng rng_;
  bool noise_ = false;
  Eigen::Vector3d earth_ = Eigen::Vector3d::Zero(), hard_iron_ = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector2d, 3> wave_direction_{};
  std::array<double, 3> wave_phase_{};
  double time_s_ = 0.0, next_sample_s_ = 0.0;
  Eigen::Vector3d reading_ = Eigen::Vector3d::Zero();
};

}  // namespace stride::sim
