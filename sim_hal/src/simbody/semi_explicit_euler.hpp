// The Simbody engine's fixed-step integrator: semi-explicit (symplectic) Euler,
//   u' = u + h udot(q, u),   q' = q + h N(q) u',
// with the free bodies' quaternions renormalised after each step. One step costs exactly one
// realization to Stage::Acceleration (done by the caller), which Simbody's variable-step
// integrators cannot promise; the explicit terms are stable for the servo and contact
// stiffnesses at the default 2 ms step (sim_hal/models/README.md).
#pragma once

#include <Simbody.h>

#include <vector>

namespace stride::sim::simbody {

class SemiExplicitEuler {
 public:
  /// Sizes the work vectors for `state`; `quaternion_q` are the first q indices of the
  /// free bodies' quaternions.
  void configure(const SimTK::State& state, std::vector<int> quaternion_q);
  /// Advances `state` (realized to Stage::Acceleration) by h; the time becomes
  /// (step_index + 1) h exactly, so that it does not drift by round-off. Throws what Simbody
  /// throws; allocates nothing.
  void step(const SimTK::SimbodyMatterSubsystem& matter, SimTK::State& state, SimTK::Real h,
            std::int64_t step_index);

 private:
  SimTK::Vector u_next_, qdot_;
  std::vector<int> quaternion_q_;
};

}  // namespace stride::sim::simbody
