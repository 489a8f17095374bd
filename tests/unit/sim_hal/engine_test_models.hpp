// Small robots and episode models for the physics-engine tests: URDF strings with closed-form
// physics (a free box, a pendulum on a heavy base), and an EngineModel with neutral settings
// (no randomisation, no armature, no ball unless asked).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "stride/sim_hal/physics_engine.hpp"

namespace stride::sim::engine_test {

/// An engine under test (make_physics_engine's kind).
struct EngineCase {
  EngineKind kind;
};

/// A 1 kg, 0.1 m cube with a collision box.
inline const char* kBoxUrdf = R"(<robot name="box">
  <link name="box">
    <inertial><mass value="1"/><origin xyz="0 0 0"/>
      <inertia ixx="0.0016667" iyy="0.0016667" izz="0.0016667" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
</robot>)";

/// A 10 kg base (0.4 x 0.4 x 0.1 m box) with a pendulum hinged about y at 0.4 m above the
/// base centre: a 0.2 kg bob 0.25 m below the hinge (centroidal inertia 1e-5 kg m^2).
inline const char* kPendulumUrdf = R"(<robot name="pendulum">
  <link name="base">
    <inertial><mass value="10"/><origin xyz="0 0 0"/>
      <inertia ixx="0.14167" iyy="0.14167" izz="0.26667" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <inertial><mass value="0.2"/><origin xyz="0 0 -0.25"/>
      <inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>
  <joint name="hinge" type="continuous">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.4"/><axis xyz="0 1 0"/>
  </joint>
</robot>)";

inline constexpr double kPendulumMass = 0.2, kPendulumLength = 0.25;
inline constexpr double kPendulumInertia = 1e-5 + 0.2 * 0.25 * 0.25;  // about the hinge

inline std::shared_ptr<RobotModel> load_urdf(const std::string& urdf) {
  auto model = std::make_shared<RobotModel>();
  const Status s = RobotModel::load_string(urdf, "test urdf", *model);
  EXPECT_TRUE(s) << s.message();
  return model;
}

/// Unscaled masses, no armature, no ball, feet unset.
inline EngineModel neutral_model(const RobotModel& robot) {
  EngineModel m;
  m.robot = &robot;
  m.link_mass_scale.assign(robot.links().size(), 1.0);
  m.joint_armature.assign(robot.joints().size(), 0.0);
  m.ball.present = false;
  return m;
}

}  // namespace stride::sim::engine_test
