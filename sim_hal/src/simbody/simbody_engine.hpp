// The Simbody engine: the robot as a tree of Simbody mobilized bodies (a Free root, one Pin
// per revolute joint), the reflected rotor inertia added about each joint axis, gravity and
// Stride's contact law (contact_law.hpp) applied as body forces, a free ball, and the
// semi-explicit Euler step (semi_explicit_euler.hpp).
#pragma once

#include <memory>

#include "stride/sim_hal/physics_engine.hpp"

namespace stride::sim::simbody {

std::unique_ptr<PhysicsEngine> make_simbody_engine();

}  // namespace stride::sim::simbody
