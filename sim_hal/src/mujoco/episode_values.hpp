// An episode's randomised values written straight into a compiled MuJoCo model (issue 42
// point 1, "build once"), so that a randomised reset does not compile MJCF again.
//
// The MuJoCo engine compiles the MJCF of the model's structure: EngineModel with the values
// SimWorld draws per reset at fixed nominal ones (nominal_model(): every link mass scale 1, no
// trunk centre-of-mass shift, friction 1, the seed's grass thickness). write_episode_values()
// then writes the episode's values into the fields the compiler would have filled from them,
// computed exactly as MuJoCo 2.2.2's compiler computes them from write_mjcf()'s text:
// - body_mass = s m (the number write_mjcf prints, read back exactly);
// - body_inertia and body_iquat: the principal moments and axes of s I from mju_eig3, the
//   function the compiler applies to <inertial fullinertia> (user_objects.cc, mjCAlternative);
// - body_ipos of the trunk: its centre of mass plus root_com_shift (the body frame is the
//   URDF link frame, so the shift adds to the position the text would hold);
// - geom_friction[0] of every geom but the solid ground (which keeps MuJoCo's default) and
//   pair_friction[0..1] of the solid ground's pairs (the ball's pairs have none in the text);
// - geom_pos z of the grass plane (grass_thickness_m, drawn with the ground's range);
// then mj_setConst (2.2.2: body_subtreemass, dof_M0, body/dof_invweight0, stat.meaninertia,
// extent, meanmass...) as the compiler's last step. The model is then the compiler's bit for
// bit (unit test MujocoEngine.APatchedModelIsTheCompilersBitForBit).
// The compiler's checks and its derived flags are repeated first: a value it would refuse (a
// mass or principal moment below mjMINVAL, moments breaking A + B >= C, anything non-finite) or
// one that would change body_sameframe or geom_sameframe (a centre of mass or grass plane at the
// frame's origin, principal axes along the frame) writes nothing and returns false; the engine
// then compiles that episode's own text (which reports the bad value in one line).
#pragma once

#include <mujoco/mujoco.h>

#include "stride/sim_hal/physics_engine.hpp"

namespace stride::sim::mujoco {

/// `model` with the values randomised per reset at their nominal ones (see above).
EngineModel nominal_model(const EngineModel& model);

/// Writes `model`'s episode values into `m`, compiled from write_mjcf(nominal_model(model)),
/// and recomputes its constants (mj_setConst, `d` an mjData of `m`'s sizes used as scratch).
/// False, `m` unchanged: a value the compiler would refuse or handle differently (see above).
bool write_episode_values(mjModel* m, mjData* d, const EngineModel& model);

}  // namespace stride::sim::mujoco
