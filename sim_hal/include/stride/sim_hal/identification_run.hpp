// The identification routine (firmware/scripts/IDENTIFICATION.md) played in the simulator as an
// operator plays it on the robot, and recorded with the flight recorder exactly as
// `stride-fw --record` does: standing still, the scripts identify_arms, identify_stand,
// identify_shift and identify_steps (each requested from the stand, the next one once the robot
// stands again), walking in place, a stop, a short forward walk and a stop. Its log is the input of
// `stride replay` and `stride calibrate`, and the test data of issue 30 point 5
// (`stride identify`).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

struct IdentificationRun {
  /// The parts in order: "stand", "identify_arms", "identify_stand", "identify_shift",
  /// "identify_steps", "walk".
  std::vector<std::string> parts = {"stand",          "identify_arms",  "identify_stand",
                                    "identify_shift", "identify_steps", "walk"};
  double stand_s = 20.0;  ///< part "stand": standing still, torque on
  double pause_s = 1.0;   ///< standing between parts
  double walk_in_place_s = 10.0;
  double walk_s = 10.0;  ///< the short walk forward at walk_vx
  double walk_vx = 0.5;  ///< normalised forward command (console `walk 0.5 0 0`)
  double stop_s = 4.0;   ///< after each `stop`: the walk finishes its step and stands
  double script_timeout_s = 60.0;
  fw::FirmwareOptions firmware;  ///< --params: the walk parameters the robot walks with
};

/// Known part names (for error messages).
const std::vector<std::string>& identification_parts();

struct IdentificationSummary {
  double period_s = 0.01;  ///< the firmware's control period
  std::int64_t ticks = 0;
  std::int64_t ticks_dropped = 0;
  bool fell = false;    ///< the firmware detected a fall (the log ends there)
  std::string failure;  ///< the world stopped (explosion) or a script did not end
  std::vector<std::pair<std::string, double>> part_start_s;  ///< each part's start [s]
  /// The IMU's fixed biases of the recorded episode (the world's plus the per-episode draw):
  /// the true values behind a calibration's accel_bias and gyro_bias.
  Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_rad_s = Eigen::Vector3d::Zero();
};

/// Plays `run` in `world` (its control period is the firmware's) and records it to `log`
/// (written whole, then renamed: a failure leaves no file). A fall or a world failure ends the
/// run early and is reported in `out`, the log kept. Errors: an unknown part, a bad firmware
/// option, a log that cannot be written.
Status record_identification(const IdentificationRun& run, WorldOptions world,
                             const std::filesystem::path& log, IdentificationSummary& out);

}  // namespace stride::sim
