// MuJoCo's soft-contact parameters for Stride's field: the same static stiffness per
// contact point as the grass of Stride's contact law (ContactOptions), so that the robot
// standing on MuJoCo sinks as deep as on Simbody, while MuJoCo's own solver (elliptic
// Coulomb cones, its constraint impedance) computes the forces.
//
// MuJoCo 2.2's soft constraint (engine_core_constraint.c; standard solref = (timeconst,
// dampratio), solimp flat at impedance d): a contact row's reference acceleration is
// aref = -b v - k d r with k = 1 / (d^2 timeconst^2 dampratio^2), b = 2 / (d timeconst), and
// its regulariser R = (1-d)/d A, with A the diagonal approximation of the inverse inertia,
// body_invweight0[2 body] summed over the two bodies (the field's is 0). At rest (v = 0, no
// constraint acceleration) the solver's force obeys R f = aref, so
//     f = r / (timeconst^2 dampratio^2 (1-d) A):
// a linear spring. Each geom's timeconst is set from its body's A so that this is K [N/m] per
// contact: K = grass_stiffness_n_m for robot and ball on the field, ball_robot_stiffness_n_m
// for the ball against the robot. The standing sink then equals Stride's (8 studs at
// 1500 N/m: about 5.3 mm) by construction, whatever the robot.
//
// d = kContactImpedance = 0.9 (MuJoCo's usual 0.9-0.95, flat so that the spring is linear),
// dampratio = kDampingRatio = 1 (MuJoCo's default, critically damped): the contact's dynamics
// are MuJoCo's (a constraint relaxing with timeconst), not a copy of Stride's spring-damper. A
// smaller d makes the bare spring but, with it, a huge friction-row damping b whose elliptic
// cone throws a sliding body off the ground (tried: d = 0.01 made a sliding ball hop). Friction
// rows have no spring and R1 = R0 / impratio: a sticking contact under a tangential force F
// creeps at (1-d) A F timeconst / (2 impratio); kImpRatio = 10 keeps that near 1 mm/s per N on
// a foot. The Coulomb bound of the elliptic cone is exact: |f_t| <= mu f_n.
//
// The field's damping (issue 41: the soft ground is more damped than turf): the robot and ball
// geoms' damping ratio against the field is MuJoCo's default 1 scaled by how much more damped
// the ground's layer is than the seed's grass in Stride's law, relative to its stiffness
// (c / sqrt(k): the damping ratio of a spring-damper carrying a fixed mass), never below 1:
// turf and the seed grass (40 N s/m at 1500 N/m) keep 1, the hard ground (100 at 2e4, 0.68 of
// that) keeps 1, the soft ground (80 at 2000) gets 1.73. A larger damping ratio keeps the
// static stiffness (timeconst shrinks with it) and raises the damping b = 2 / (d timeconst).
//
// The solid ground under the grass (Stride's second, stiffer spring) is modelled only when
// ContactOptions::mujoco_solid_ground (the turf contact): a second plane at z = 0, touched
// through explicit pairs whose static stiffness is ground_stiffness_n_m per contact (the grass
// spring continues below it, so a point on the ground has k_g d + k_s (d - T) where Stride's
// law has k_g T + k_s (d - T): 1500 N/m against 2e4). On the seed's 2 cm grass it is left out:
// reached only at impacts (standing sinks ~5 mm, single support ~11 mm).
#pragma once

#include <mujoco/mujoco.h>

#include "stride/sim_hal/physics_engine.hpp"

namespace stride::sim::mujoco {

/// Sets geom_solref/solimp of every robot and ball geom and pair_solref/solimp of the
/// ball-robot pairs in the compiled model `m` (written by write_mjcf for `model`).
void set_contact_params(mjModel* m, const EngineModel& model);

/// The damping ratio (solref[1]) of robot and ball contacts with the field for `contact`.
double field_damping_ratio(const ContactOptions& contact);

}  // namespace stride::sim::mujoco
