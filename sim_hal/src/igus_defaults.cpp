// The igus robot's defaults for the simulator: servo-to-joint map, Stand pose, noisy IMU.
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

const std::array<std::string, hal::kServoCount>& igus_servo_joints() {
  static const std::array<std::string, hal::kServoCount> names = {"right_shoulder_pitch",
                                                                  "left_shoulder_pitch",
                                                                  "right_shoulder_roll",
                                                                  "left_shoulder_roll",
                                                                  "right_elbow_pitch",
                                                                  "left_elbow_pitch",
                                                                  "right_hip_yaw",
                                                                  "left_hip_yaw",
                                                                  "right_hip_roll",
                                                                  "left_hip_roll",
                                                                  "right_hip_pitch",
                                                                  "left_hip_pitch",
                                                                  "right_knee_pitch",
                                                                  "left_knee_pitch",
                                                                  "right_ankle_pitch",
                                                                  "left_ankle_pitch",
                                                                  "right_ankle_roll",
                                                                  "left_ankle_roll",
                                                                  "neck_yaw",
                                                                  "head_pitch"};
  return names;
}

const std::array<double, hal::kServoCount>& igus_stand_pose() {
  // igus.md 3.4 (NUbots angles); shoulder pitch 1.9635 - pi/2 = 0.3927 in URDF angles (1.5).
  static const std::array<double, hal::kServoCount> pose = {
      0.3927,  0.3927,  -0.1239, 0.1239, -2.4435, -2.4435, -0.0292, 0.0292,  -0.0626, 0.0626,
      -0.2041, -0.2071, 0.2561,  0.2945, -0.2394, -0.2624, 0.0691,  -0.0691, 0.0,     0.0};
  return pose;
}

ResetSpec ResetSpec::standing() {
  ResetSpec spec;
  spec.joint_angles = igus_stand_pose();
  return spec;
}

void ImuOptions::set_noise(bool on) {
  accel_noise_std = on ? 0.05 : 0.0;  // m/s^2 per sample
  gyro_noise_std = on ? 0.005 : 0.0;  // rad/s per sample
  accel_bias_std = on ? 0.1 : 0.0;    // m/s^2 per episode
  gyro_bias_std = on ? 0.01 : 0.0;    // rad/s per episode
  chain.noise = on;                   // used when the chain is not ideal
}

}  // namespace stride::sim
