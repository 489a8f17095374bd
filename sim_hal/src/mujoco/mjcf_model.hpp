// MJCF text of one episode's physics (EngineModel) for MuJoCo 2.2, generated in memory.
//
// MuJoCo 2.2 has no model-editing API, so the MuJoCo engine writes MJCF and loads it through
// the virtual file system. Element names are indices (links "l<i>", joints "j<i>", the root's
// free joint "root", the ball body "ball", the field "grass"), never the URDF's names, so that
// any URDF name is safe in XML.
//
// The model (figures from EngineModel, numbers written with %.17g so that nothing is rounded):
// - links[0] is a body with a free joint; every model joint a hinge about JointSpec::axis in
//   the joint frame, the child body placed at JointSpec::origin in its parent (the child link
//   frame equals the joint frame at angle 0); no damping, friction or range (the shared servo
//   models apply those torques, joint stops included), armature = EngineModel::joint_armature.
// - inertial at the link's centre of mass with its mass and full inertia, both times
//   EngineModel::link_mass_scale.
// - collision: the link's spheres and boxes; the field is the plane z = grass_thickness_m
//   (the top of the grass, as in Stride's contact law). Contact bits: robot geoms (contype 1,
//   conaffinity 2), the field (2, 1) and the ball (0, 2) collide robot-field and ball-field
//   but never robot-robot; ball-robot contacts are explicit frictionless <pair>s (their own
//   stiffness), as in Stride's contact law.
// - the ball a free body with a sphere of BallOptions' radius, mass and inertia.
// - Euler integrator at EngineModel::step_s, elliptic friction cones, Newton solver.
// The soft-contact parameters (solref/solimp) are set after compiling, per geom, by
// contact_params.hpp (they depend on the compiled model's body_invweight0).
#pragma once

#include <string>

#include "stride/sim_hal/physics_engine.hpp"

namespace stride::sim::mujoco {

/// The impedance d of every contact (solimp flat at d), the damping ratio of solref and the
/// friction impedance ratio.
/// Why these values: contact_params.hpp.
inline constexpr double kContactImpedance = 0.9;
inline constexpr double kDampingRatio = 1.0;
inline constexpr double kImpRatio = 10.0;
/// mjData's fixed buffers (MJCF <size>): contacts and constraint rows.
inline constexpr int kMaxContacts = 200;
inline constexpr int kMaxConstraintRows = 600;

/// The MJCF document for `model`. `model.robot` must be set and the per-link and per-joint
/// vectors sized to the robot (checked by the caller).
std::string write_mjcf(const EngineModel& model);

}  // namespace stride::sim::mujoco
