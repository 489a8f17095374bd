// WalkSelector: forwards to the walk engine walk.engine names (see the header).
#include "stride/firmware/walk/walk_selector.hpp"

namespace stride::fw {

WalkSelector::WalkSelector(ParameterStore& store, WalkControl& seed_zmp, WalkControl& spline)
    : store_(store), seed_zmp_(seed_zmp), spline_(spline), active_(&seed_zmp) {
  engine_ = store.add({"walk.engine", ParamType::kInt, kSeedZmp, kSeedZmp, kSpline, "1",
                       "walk engine: 0 the seed's ZMP walk (walk.*), 1 the spline walk "
                       "(walk.spline.*); taken when a walk starts",
                       false, false});
}

void WalkSelector::start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
                         hal::Tick tick) noexcept {
  active_ = static_cast<int>(store_.value(engine_)) == kSpline ? &spline_ : &seed_zmp_;
  active_->start(sensors, last_sent, tick);
}

void WalkSelector::step(const hal::SensorFrame& sensors, hal::Tick tick,
                        hal::CommandFrame& out) noexcept {
  active_->step(sensors, tick, out);
}

void WalkSelector::set_velocity(double vx, double vy, double vtheta) noexcept {
  // Both hear it: the command may come before the start that chooses the engine.
  seed_zmp_.set_velocity(vx, vy, vtheta);
  spline_.set_velocity(vx, vy, vtheta);
}

}  // namespace stride::fw
