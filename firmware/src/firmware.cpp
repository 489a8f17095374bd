// Firmware composition root: registration order, parameter file, loop period.
#include "stride/firmware/firmware.hpp"

#include "stride/core/data_dir.hpp"

#include <cmath>
#include <cstdlib>
#include <exception>

#include "stride/firmware/script/script_engine.hpp"
#include "stride/firmware/walk/spline_walk_engine.hpp"
#include "stride/firmware/walk/walk_engine.hpp"
#include "stride/firmware/walk/walk_selector.hpp"

#ifndef STRIDE_FIRMWARE_DATA_DIR
#define STRIDE_FIRMWARE_DATA_DIR "."
#endif

namespace stride::fw {

std::filesystem::path data_dir() {
  return core::data_dir("config/servo_table.json", STRIDE_FIRMWARE_DATA_DIR);
}

// The motion engines the controller drives. Each engine registers its parameters in its
// constructor, before the parameter file is applied.
struct Firmware::Engines {
  std::unique_ptr<AttitudeEstimator> attitude;           // the one attitude estimate
  std::unique_ptr<WalkEngine> walk_engine;               // the seed's ZMP walk (walk.*)
  std::unique_ptr<SplineWalkEngine> spline_walk_engine;  // the spline walk (walk.spline.*)
  std::unique_ptr<WalkSelector> walk_selector;           // walk.engine chooses one of them
  WalkControl* walk = nullptr;
  ScriptControl* script = nullptr;
  std::unique_ptr<ScriptEngine> script_engine;
};

Firmware::~Firmware() = default;

Status FirmwareFiles::load(const FirmwareOptions& options, FirmwareFiles& out) {
  FirmwareFiles files;
  if (Status s = ServoTable::load(options.servo_table, files.servos); !s) return s;
  const std::filesystem::path robot_path = options.robot_description.empty()
                                               ? RobotDescription::default_path()
                                               : options.robot_description;
  if (Status s = RobotDescription::load(robot_path, files.servos, files.robot); !s) return s;
  const std::filesystem::path scripts_dir =
      options.scripts_dir.empty() ? data_dir() / "scripts" : options.scripts_dir;
  if (Status s = load_script_folder(scripts_dir, files.servos, files.scripts); !s) return s;
  out = std::move(files);
  return {};
}

Status Firmware::create(const FirmwareOptions& options, std::unique_ptr<Firmware>& out) {
  FirmwareFiles files;
  if (Status s = FirmwareFiles::load(options, files); !s) return s;
  return create(options, files, out);
}

Status Firmware::create(const FirmwareOptions& options, const FirmwareFiles& files,
                        std::unique_ptr<Firmware>& out) {
  std::unique_ptr<Firmware> fw(new Firmware());
  fw->servos_ = files.servos;
  fw->robot_ = files.robot;

  ParamSpec rate{"loop.rate_hz",
                 ParamType::kInt,
                 100,
                 10,
                 1000,
                 "Hz",
                 "control loop rate (ticks per second)",
                 false,
                 true};
  const ParamHandle rate_handle = fw->params_.add(rate);
  // The period must be known before the engines are built, so the rate is read from the
  // parameter file first (validated again with everything else below).
  if (options.params_file) {
    std::vector<ParamWrite> early;
    if (Status s = fw->params_.parse_json_file(*options.params_file, early); !s) {
      // Unknown names are expected here (engines not registered yet); only a bad rate or a
      // broken file matters now, and the full check below reports everything else.
      if (s.message().find("unknown parameter") == std::string::npos) return s;
    }
    for (const auto& [name, value] : early) {
      if (name == "loop.rate_hz") (void)fw->params_.set_now({{name, value}});
    }
  }
  const double rate_hz = fw->params_.value(rate_handle);
  fw->period_ns_ = static_cast<std::int64_t>(std::llround(1e9 / rate_hz));

  fw->engines_ = std::make_unique<Engines>();
  // The motion engines register their parameters here, before the parameter file applies.
  try {
    auto& engines = *fw->engines_;
    engines.attitude = std::make_unique<AttitudeEstimator>(
        fw->params_, static_cast<double>(fw->period_ns_) * 1e-9);
    engines.walk_engine = std::make_unique<WalkEngine>(fw->params_, fw->servos_, fw->period_ns_,
                                                       *engines.attitude, fw->robot_);
    engines.spline_walk_engine = std::make_unique<SplineWalkEngine>(
        fw->params_, fw->servos_, fw->period_ns_, *engines.attitude, fw->robot_);
    engines.walk_selector = std::make_unique<WalkSelector>(fw->params_, *engines.walk_engine,
                                                           *engines.spline_walk_engine);
  } catch (const std::exception& e) {
    return Status::error(e.what());
  }
  fw->engines_->walk = fw->engines_->walk_selector.get();
  // Scripts are loaded before the controller: the motion manager resolves the get-up scripts.
  fw->engines_->script_engine = std::make_unique<ScriptEngine>(
      fw->period_ns_, fw->params_, fw->servos_, fw->engines_->attitude.get());
  for (const Script& script : files.scripts) {
    if (Status s = fw->engines_->script_engine->add_script(script); !s) return s;
  }
  fw->engines_->script = fw->engines_->script_engine.get();

  fw->controller_ = std::make_unique<Controller>(
      fw->params_, fw->servos_, fw->period_ns_, *fw->engines_->attitude,
      ControllerEngines{fw->engines_->walk, fw->engines_->script});

  if (options.params_file) {
    if (Status s = fw->params_.load_file_now(*options.params_file); !s) return s;
  }
  out = std::move(fw);
  return {};
}

}  // namespace stride::fw
