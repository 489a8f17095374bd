// WalkSelector: the walk the motion manager drives, one of the firmware's walk engines chosen
// by the parameter walk.engine (0: the seed's ZMP walk, walk_engine.hpp; 1: the spline walk,
// spline_walk_engine.hpp). A parameter file carries the engine with its values, so stride-fw
// --params, stride sim --params, the console's `load` and an optimiser genome choose it the
// same way. The choice is latched when a walk starts: a change while walking takes effect at
// the next start. Real-time: every method only forwards (no allocation, no I/O).
#pragma once

#include "stride/firmware/motion_engine.hpp"
#include "stride/firmware/parameter_store.hpp"

namespace stride::fw {

class WalkSelector final : public WalkControl {
 public:
  /// Values of walk.engine.
  enum Engine : int { kSeedZmp = 0, kSpline = 1 };

  /// Registers walk.engine (start-up only; throws std::invalid_argument on a name clash).
  /// The engines must outlive the selector.
  WalkSelector(ParameterStore& store, WalkControl& seed_zmp, WalkControl& spline);

  std::string_view name() const noexcept override { return "walk"; }
  void start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
             hal::Tick tick) noexcept override;
  void step(const hal::SensorFrame& sensors, hal::Tick tick,
            hal::CommandFrame& out) noexcept override;
  bool done() const noexcept override { return active_->done(); }
  void set_velocity(double vx, double vy, double vtheta) noexcept override;
  void request_stop() noexcept override { active_->request_stop(); }

  /// The engine of the latest start() (the seed's before any).
  Engine active() const noexcept { return active_ == &spline_ ? kSpline : kSeedZmp; }

 private:
  const ParameterStore& store_;
  ParamHandle engine_;
  WalkControl& seed_zmp_;
  WalkControl& spline_;
  WalkControl* active_;
};

}  // namespace stride::fw
