// StandEngine: ramps every servo from where it is to the stand pose over a configurable time,
// then holds it. The ramp uses a smoothstep profile so velocity is zero at both ends.
//
// Parameters (registered in the ParameterStore):
//   stand.ramp_time  [s]    time to reach the stand pose from the start pose (default 1.5)
//   stand.gain       [0-100] servo gain while standing (default 30, P register 76)
#pragma once

#include <array>

#include "stride/firmware/motion_engine.hpp"
#include "stride/firmware/parameter_store.hpp"

namespace stride::fw {

class StandEngine final : public MotionEngine {
 public:
  StandEngine(ParameterStore& params, double period_s);

  std::string_view name() const noexcept override { return "stand"; }
  void start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
             hal::Tick tick) noexcept override;
  void step(const hal::SensorFrame& sensors, hal::Tick tick,
            hal::CommandFrame& out) noexcept override;
  /// True once the ramp has finished and the pose is held.
  bool done() const noexcept override { return settled_; }

  const std::array<double, hal::kServoCount>& pose() const { return pose_; }

 private:
  ParameterStore* params_ = nullptr;
  double period_s_;
  ParamHandle ramp_time_;
  ParamHandle gain_;
  std::array<double, hal::kServoCount> pose_;
  std::array<double, hal::kServoCount> from_{};
  hal::Tick start_tick_ = 0;
  bool settled_ = false;
};

}  // namespace stride::fw
