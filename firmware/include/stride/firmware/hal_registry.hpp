// HAL backends of stride-fw: each implementation of the HAL registers itself from a source
// file compiled into the stride-fw executable, so the firmware never depends on a backend:
//
//   STRIDE_HAL_BACKEND(serial, "Dynamixel bus on a serial port", declare_fn, check_fn, make_fn);
//
// declare_fn(CliArgs&) declares the backend's own options; check_fn (may be null) checks their
// values for the given loop period without touching a device, so that stride-fw names a bad
// option as bad input (exit 2) before it opens anything; make_fn builds the robot (its errors
// are the device's or the world's, exit 1). `paced_by_clock` tells stride-fw to wrap the robot in
// RealtimeRobot (true for hardware; a simulation sets it only with --realtime).
// `default_params` (may be null; set it with STRIDE_HAL_BACKEND_WITH_PARAMS) names the parameter
// file stride-fw loads when --params is not given, for a backend whose options choose a world
// with a walk of its own (the simulator's --world seed: config/seed-walk.json); "" for none.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/core/status.hpp"
#include "stride/hal/robot.hpp"

namespace stride::fw {

struct HalInstance {
  std::unique_ptr<hal::Robot> robot;
  bool paced_by_clock = true;
  /// Optional: adds backend-specific results to stride-fw's final report.
  std::function<void(nlohmann::json& report)> report;
};

struct HalBackend {
  std::string_view name;
  std::string_view help;
  void (*declare_options)(core::CliArgs& args);
  Status (*check_options)(const core::CliArgs& args, std::int64_t period_ns);
  Status (*make)(const core::CliArgs& args, std::int64_t period_ns, HalInstance& out);
  std::string (*default_params)(const core::CliArgs& args) = nullptr;
};

/// All registered backends, sorted by name.
const std::vector<HalBackend>& hal_backends();
bool register_hal_backend(HalBackend backend);

}  // namespace stride::fw

#define STRIDE_HAL_BACKEND(name, help, declare_fn, check_fn, make_fn)       \
  [[maybe_unused]] static const bool stride_hal_backend_registered_##name = \
      ::stride::fw::register_hal_backend(                                   \
          ::stride::fw::HalBackend{#name, help, declare_fn, check_fn, make_fn})

#define STRIDE_HAL_BACKEND_WITH_PARAMS(name, help, declare_fn, check_fn, make_fn, params_fn) \
  [[maybe_unused]] static const bool stride_hal_backend_registered_##name =                  \
      ::stride::fw::register_hal_backend(                                                    \
          ::stride::fw::HalBackend{#name, help, declare_fn, check_fn, make_fn, params_fn})
