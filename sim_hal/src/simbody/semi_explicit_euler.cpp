// Semi-explicit Euler on a Simbody state (see semi_explicit_euler.hpp).
#include "semi_explicit_euler.hpp"

#include <cmath>
#include <stdexcept>

namespace stride::sim::simbody {

using SimTK::Real;

void SemiExplicitEuler::configure(const SimTK::State& state, std::vector<int> quaternion_q) {
  u_next_.resize(state.getNU());
  qdot_.resize(state.getNQ());
  quaternion_q_ = std::move(quaternion_q);
}

void SemiExplicitEuler::step(const SimTK::SimbodyMatterSubsystem& matter, SimTK::State& state,
                             Real h, std::int64_t step_index) {
  // The loops run over the state's contiguous storage (Simbody's element access is a virtual
  // call per element, and `h * udot` a temporary vector); the arithmetic is the same, element
  // by element.
  const SimTK::Vector& udot = matter.getUDot(state);
  const SimTK::Vector& u = matter.getU(state);
  if (!udot.hasContiguousData() || !u.hasContiguousData() || !u_next_.hasContiguousData() ||
      !qdot_.hasContiguousData() || !matter.getQ(state).hasContiguousData())
    throw std::logic_error("state vectors are not contiguous");
  const Real* udot_data = udot.getContiguousScalarData();
  const Real* u_data = u.getContiguousScalarData();
  Real* u_next_data = u_next_.updContiguousScalarData();
  for (int i = 0; i < u_next_.size(); ++i) u_next_data[i] = u_data[i] + h * udot_data[i];
  matter.multiplyByN(state, false, u_next_, qdot_);
  Real* q = matter.updQ(state).updContiguousScalarData();
  const Real* qdot_data = qdot_.getContiguousScalarData();
  for (int i = 0; i < qdot_.size(); ++i) q[i] += h * qdot_data[i];
  for (int first : quaternion_q_) {  // keep the free bodies' quaternions unit length
    Real norm = 0.0;
    for (int k = 0; k < 4; ++k) norm += q[first + k] * q[first + k];
    norm = std::sqrt(norm);
    for (int k = 0; k < 4; ++k) q[first + k] /= norm;
  }
  matter.updU(state) = u_next_;
  state.updTime() = static_cast<Real>(step_index + 1) * h;
}

}  // namespace stride::sim::simbody
