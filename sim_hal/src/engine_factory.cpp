// make_physics_engine: the engines this build has, by kind.
#include "mujoco/mujoco_engine.hpp"
#include "simbody/simbody_engine.hpp"
#include "stride/sim_hal/physics_engine.hpp"

namespace stride::sim {

std::unique_ptr<PhysicsEngine> make_physics_engine(EngineKind kind) {
  switch (kind) {
    case EngineKind::kSimbody:
      return simbody::make_simbody_engine();
    case EngineKind::kMujoco:
      return make_mujoco_engine();
  }
  return nullptr;
}

}  // namespace stride::sim
