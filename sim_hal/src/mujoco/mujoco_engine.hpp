// The MuJoCo 2.2 physics engine behind PhysicsEngine (private to sim_hal; the engine factory
// and the tests use it).
//
// build() compiles once per model structure: it writes the MJCF of the model with the values
// SimWorld draws per reset (link mass scales, trunk centre-of-mass shift, friction, grass
// thickness) at nominal ones, loads it through MuJoCo's virtual file system and allocates
// mjData; then it writes the episode's values into the compiled mjModel exactly as the compiler
// would have from the episode's own MJCF (episode_values.hpp: the same model bit for bit) and
// sets the soft-contact parameters (contact_params.hpp). A build() of the same structure (every
// reset of a world, randomised or not) compiles nothing: it keeps mjModel and mjData, writes
// the values and sets the contact parameters again; start() resets the data (mj_resetData
// clears its whole buffer, as mj_makeData does). Another structure compiles, keeping the mjData
// when the sizes are the same. A value the compiler would refuse or treat otherwise compiles
// the episode's own text (kept while that text repeats).
// step() puts the joint torques into qfrc_applied (and the ball's rolling damping), runs one
// mj_step (Euler: v' = v + h a, q' = q + h v', as Simbody's fixed-step loop), then recomputes
// the link poses for the new positions. Single-threaded and deterministic: the state hash
// covers time, qpos, qvel, qacc_warmstart (the solver's warm start, which shapes the next
// step) and act. torso_acceleration() is the change of the root origin's velocity over the
// last step divided by the step (MuJoCo's qacc of the free joint's translation, world frame).
// contacts() reads the contacts MuJoCo found at the start of the last step, with their forces
// (mj_contactForce, rotated to the world frame). MuJoCo's warnings (a bad qpos/qvel/qacc,
// after which it resets the state itself) and a full contact or constraint buffer (MuJoCo would
// drop contacts silently) end the step with a reason; build() silences
// MuJoCo's global warning handler, which would otherwise write MUJOCO_LOG.TXT.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>
#include <memory>

#include "stride/sim_hal/physics_engine.hpp"

namespace stride::sim {

std::unique_ptr<PhysicsEngine> make_mujoco_engine();

/// The compiled model of a built MuJoCo engine (null before build() or for another engine):
/// for tests that read masses, inertias and joint axes back.
const mjModel* mujoco_model_of(const PhysicsEngine& engine);

/// Test and benchmark hooks. The number of MJCF compiles (mj_loadXML) in this process so far,
/// over all MuJoCo engines and threads.
std::int64_t mujoco_compile_count();
/// On: every build() compiles the episode's own MJCF into a new mjModel and mjData, as before
/// the compiled model was kept (the old path, for the benchmark's side-by-side figure and the
/// tests' reference bits). Process-wide; off by default.
void mujoco_set_always_compile(bool on);
/// Called by every MuJoCo engine's step() just before mj_step, the step's joint torques in
/// d->qfrc_applied (bench_sim_hal_mujoco_bare records them). Process-wide; null: none (default).
using MujocoStepObserver = void (*)(const mjModel* m, const mjData* d, void* context);
void mujoco_set_step_observer(MujocoStepObserver observer, void* context);

}  // namespace stride::sim
