// Firmware: the composition root. Owns the parameter store, the servo table, the motion
// engines and the Controller, built in the right order from files on disk:
//   1. every module registers its parameters (defaults);
//   2. an optional parameter file is validated and applied (all or nothing);
//   3. the loop period follows loop.rate_hz (needs a restart to change).
// stride-fw, `stride sim` and the optimiser's episodes all build the firmware through here,
// so they run the very same controller.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/firmware/controller.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/robot_description.hpp"
#include "stride/firmware/script/script.hpp"
#include "stride/firmware/servo_table.hpp"

namespace stride::fw {

struct FirmwareOptions {
  std::filesystem::path servo_table = ServoTable::default_path();
  /// Rigid-body model (stride describe); empty: the shipped one beside the servo table's data.
  std::filesystem::path robot_description;
  std::filesystem::path scripts_dir;                 ///< keyframe scripts; empty: the shipped ones
  std::optional<std::filesystem::path> params_file;  ///< applied after the defaults
};

/// The data files a firmware is built from, read and validated: the servo table and the
/// keyframe scripts. A host tool that builds many firmwares from the same files (the optimiser
/// builds one per evaluation) loads them once; the firmware built from them is the same.
struct FirmwareFiles {
  ServoTable servos;
  RobotDescription robot;  ///< checked against `servos`
  std::vector<Script> scripts;

  /// Reads options.servo_table, the robot description and the scripts folder; an error names
  /// the file and field.
  static Status load(const FirmwareOptions& options, FirmwareFiles& out);
};

class Firmware {
 public:
  /// Builds everything; an error names the file and field that was wrong.
  static Status create(const FirmwareOptions& options, std::unique_ptr<Firmware>& out);
  /// The same from files already loaded (options.servo_table and scripts_dir are not read).
  static Status create(const FirmwareOptions& options, const FirmwareFiles& files,
                       std::unique_ptr<Firmware>& out);
  ~Firmware();

  ParameterStore& params() noexcept { return params_; }
  const ParameterStore& params() const noexcept { return params_; }
  Controller& controller() noexcept { return *controller_; }
  const ServoTable& servos() const noexcept { return servos_; }
  const RobotDescription& robot() const noexcept { return robot_; }
  /// Loop period from loop.rate_hz at start-up [ns].
  std::int64_t period_ns() const noexcept { return period_ns_; }

 private:
  Firmware() = default;
  struct Engines;  // owned motion engines (walk, script), defined in firmware.cpp

  ParameterStore params_;
  ServoTable servos_;
  RobotDescription robot_;
  std::int64_t period_ns_ = 10'000'000;
  std::unique_ptr<Engines> engines_;
  std::unique_ptr<Controller> controller_;
};

/// The folder of the shipped data (config/, scripts/): $STRIDE_DATA_DIR if set, else the
/// installed or source-tree location compiled in.
std::filesystem::path data_dir();

}  // namespace stride::fw
