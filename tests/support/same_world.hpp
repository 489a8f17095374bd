// expect_same_world(a, b): every figure of two simulated worlds that the world options, the
// presets, the trial and the validation worlds set (engine, step, gravity, robot and how it
// differs from the model, the servo law and its options, IMU chain and noise, contact figure by
// figure, randomisation, each push), one EXPECT each, so that a test names the figure that
// differs.
#pragma once

#include <cstddef>
#include <string>

#include <gtest/gtest.h>

#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

inline void expect_same_world(const WorldOptions& a, const WorldOptions& b,
                              const std::string& where = "") {
  SCOPED_TRACE(where);
  EXPECT_EQ(a.engine, b.engine);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.physics_step_ns, b.physics_step_ns);
  EXPECT_EQ(a.control_period_ns, b.control_period_ns);
  EXPECT_EQ(a.urdf, b.urdf);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.ball.present, b.ball.present);
  EXPECT_EQ(a.gravity_mps2, b.gravity_mps2);
  EXPECT_EQ(a.battery_voltage_v, b.battery_voltage_v);
  EXPECT_EQ(a.servo_models, b.servo_models);
  EXPECT_EQ(a.servo_models_from_table, b.servo_models_from_table);
  // The servo law and its options.
  const ServoOptions &s = a.servo, &t = b.servo;
  EXPECT_EQ(s.law, t.law);
  EXPECT_EQ(s.friction_model, t.friction_model);
  EXPECT_EQ(s.backlash_rad, t.backlash_rad);
  EXPECT_EQ(s.driver_drop_v, t.driver_drop_v);
  EXPECT_EQ(s.kp_per_register, t.kp_per_register);
  EXPECT_EQ(s.viscous_friction, t.viscous_friction);
  EXPECT_EQ(s.coulomb_friction, t.coulomb_friction);
  EXPECT_EQ(s.rotor_inertia_kg_m2, t.rotor_inertia_kg_m2);
  // How the robot differs from the model.
  EXPECT_EQ(a.robot.latency_ticks, b.robot.latency_ticks);
  EXPECT_EQ(a.robot.torque_scale_mx64, b.robot.torque_scale_mx64);
  EXPECT_EQ(a.robot.torque_scale_mx106, b.robot.torque_scale_mx106);
  EXPECT_EQ(a.robot.friction_scale, b.robot.friction_scale);
  EXPECT_EQ(a.robot.trunk_mass_scale, b.robot.trunk_mass_scale);
  EXPECT_EQ(a.robot.trunk_com_offset_m, b.robot.trunk_com_offset_m);
  // The pushes, each by its contents.
  ASSERT_EQ(a.pushes.size(), b.pushes.size());
  for (std::size_t i = 0; i < a.pushes.size(); ++i) {
    SCOPED_TRACE("push " + std::to_string(i));
    EXPECT_EQ(a.pushes[i].time_s, b.pushes[i].time_s);
    EXPECT_EQ(a.pushes[i].direction_rad, b.pushes[i].direction_rad);
    EXPECT_EQ(a.pushes[i].impulse_n_s, b.pushes[i].impulse_n_s);
  }
  // Randomisation.
  EXPECT_EQ(a.randomise.friction_range, b.randomise.friction_range);
  EXPECT_EQ(a.randomise.mass_range, b.randomise.mass_range);
  EXPECT_EQ(a.randomise.strength_range, b.randomise.strength_range);
  EXPECT_EQ(a.randomise.latency_probability, b.randomise.latency_probability);
  EXPECT_EQ(a.randomise.contact_range, b.randomise.contact_range);
  EXPECT_EQ(a.randomise.com_range, b.randomise.com_range);
  // Contact, figure by figure.
  const ContactOptions &c = a.contact, &d = b.contact;
  EXPECT_EQ(c.grass_thickness_m, d.grass_thickness_m);
  EXPECT_EQ(c.grass_stiffness_n_m, d.grass_stiffness_n_m);
  EXPECT_EQ(c.grass_damping_n_s_m, d.grass_damping_n_s_m);
  EXPECT_EQ(c.ground_stiffness_n_m, d.ground_stiffness_n_m);
  EXPECT_EQ(c.ground_damping_n_s_m, d.ground_damping_n_s_m);
  EXPECT_EQ(c.friction, d.friction);
  EXPECT_EQ(c.tangential_stiffness_n_m, d.tangential_stiffness_n_m);
  EXPECT_EQ(c.tangential_damping_n_s_m, d.tangential_damping_n_s_m);
  EXPECT_EQ(c.ball_robot_stiffness_n_m, d.ball_robot_stiffness_n_m);
  EXPECT_EQ(c.ball_robot_damping_n_s_m, d.ball_robot_damping_n_s_m);
  EXPECT_EQ(c.mujoco_solid_ground, d.mujoco_solid_ground);
  // The IMU: its chain and its noise.
  EXPECT_EQ(a.imu_kind(), b.imu_kind());
  EXPECT_EQ(a.imu.chain.noise, b.imu.chain.noise);
  EXPECT_EQ(a.imu.accel_noise_std, b.imu.accel_noise_std);
  EXPECT_EQ(a.imu.gyro_noise_std, b.imu.gyro_noise_std);
  EXPECT_EQ(a.imu.accel_bias_std, b.imu.accel_bias_std);
  EXPECT_EQ(a.imu.gyro_bias_std, b.imu.gyro_bias_std);
  EXPECT_EQ(a.imu.chain.magnetometer.disturbance_gauss, b.imu.chain.magnetometer.disturbance_gauss);
}

}  // namespace stride::sim
