// BalanceFeedback: optional gyro feedback to the support leg's ankles and hips, the way the
// UPenn walk (and NUbots' port, where it was disabled) stabilises an open-loop gait. Not part
// of the 46-parameter genome. Defaults: gains found by a random search in the simulator with
// the 46 at Ind_O (the open-loop walk fell in every simulated run; see the walk README);
// setting every gain to 0 gives the seed's open-loop walk.
//
//   g_f  <- g_f + alpha (g - g_f),  alpha = dt / (dt + walk.balance.filter_time)   [rad/s]
//   shift_j = clamp(k_j * deadband(g_f), -max_shift, +max_shift)                    [rad]
//   ankle_pitch += shift(k_ankle_pitch, g_y),  hip_pitch += shift(k_hip_pitch, g_y)
//   ankle_roll  += shift(k_ankle_roll, g_x),   hip_roll  += shift(k_hip_roll, g_x)
// g is the torso gyro (rad/s, torso frame). Signs: a torso pitching forward (g_y > 0) gets
// more toe-down ankle and more backward hip pitch on the support leg, both of which rotate the
// torso back; likewise for roll. Gains k_j are in seconds (rad of joint per rad/s of rate).
//
// Tilt term (walk.balance.{pitch,roll}_angle_gain, 1/s; 0 = rate feedback only): the torso's
// pitch and roll are the firmware's attitude estimate (attitude_estimator.hpp, time constant
// walk.balance.tilt_filter_time); its slow mean (walk.balance.tilt_reference_time)
// is the reference (0: the tilt measured when the walk starts), so the term reacts to a tilt
// away from the recent (or the starting) posture. The fed-back rate becomes
//   r = deadband(g_f) + angle_gain * (tilt - tilt_reference)                          [rad/s]
// Hand-over (walk.balance.double_support_weight, 0..1; 0 = support leg only): the share of the
// shift the swing leg also takes while both feet are down, ramped out over the first and in over
// the last tenth of the single-support phase, so the feedback does not jump between legs at the
// step change. Start sway (walk.balance.start_sway_steps, 0 = off): the lateral and sagittal ZMP
// excursion of step n after the start is scaled by min(1, n / start_sway_steps).
#pragma once

#include <string_view>

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/walk/leg_kinematics.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::walk {

struct BalanceShift {
  double ankle_pitch = 0.0, ankle_roll = 0.0, hip_pitch = 0.0, hip_roll = 0.0;  ///< [rad]
};

/// Adds `weight` of `shift` to a leg's hip and ankle joints [rad].
inline void add_balance_shift(LegJoints& q, const BalanceShift& shift, double weight) noexcept {
  q.hip_roll += weight * shift.hip_roll;
  q.hip_pitch += weight * shift.hip_pitch;
  q.ankle_pitch += weight * shift.ankle_pitch;
  q.ankle_roll += weight * shift.ankle_roll;
}

class BalanceFeedback {
 public:
  /// Registers PREFIX.balance.* (PREFIX: "walk", or "walk.spline" for the spline walk; start-up
  /// only; throws on a name clash).
  BalanceFeedback(ParameterStore& store, double period_s, std::string_view prefix = "walk");

  void reset() noexcept;
  /// Filters this tick's gyro (the attitude estimate's reading, updated this tick) and returns
  /// the joint shifts for the support leg. Real-time.
  BalanceShift update(const AttitudeEstimator& attitude) noexcept;
  /// Share of the shift the swing leg takes in double support (0..1).
  double double_support_weight() const noexcept;
  /// ZMP excursion scale of step `step_count` after the start (0..1].
  double start_sway_scale(int step_count) const noexcept;

 private:
  const ParameterStore& store_;
  double period_s_;
  ParamHandle ankle_pitch_gain_, ankle_roll_gain_, hip_pitch_gain_, hip_roll_gain_;
  ParamHandle filter_time_, deadband_, max_shift_;
  ParamHandle pitch_angle_gain_, roll_angle_gain_, tilt_reference_time_;
  ParamHandle double_support_weight_, start_sway_steps_;
  double gyro_x_ = 0.0, gyro_y_ = 0.0;
  bool tilt_valid_ = false;
  double roll_reference_ = 0.0, pitch_reference_ = 0.0;
};

}  // namespace stride::fw::walk
