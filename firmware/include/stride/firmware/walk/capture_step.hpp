// CaptureStep: balance by stepping. From the IMU it estimates how far the robot's divergent
// component of motion (the capture point) has left the walk's own periodic motion, and moves
// the next footstep and changes the step timing to catch it, the way the capture-step gait of
// NimbRo-OP on the igus platform does (Missura & Behnke; fused-angle timing feedback of Allgeuer
// & Behnke, Humanoids 2016; ../shared/research/walk-anchors.md 1 and 5). Parameters
// walk.capture.* (not in the genome; every gain 0 = the seed's clock-driven walk).
//
// Tilt: the trunk's roll and pitch are the firmware's attitude estimate
// (attitude_estimator.hpp, time constant walk.balance.tilt_filter_time).
// Expected tilt: the walk rocks the trunk once per step pair, so the expected tilt is learned
// per phase of the step pair (kBins bins, each an exponential mean over learn_steps step pairs,
// started at the standing tilt), and the deviation is d = tilt - expected(phase). With the
// trunk as an inverted pendulum of height h = com_height over the stance foot, the capture
// point's deviation in the walk frame (x forward, y left) is
//   xi_x = h (d_pitch + d_pitch' / w),  xi_y = -h (d_roll + d_roll' / w),  w = sqrt(g / h)
// (d' low-passed over rate_filter_time). Englsberger et al. (IROS 2011): the point where the
// robot can stop moves with the deviation, so the next foot goes there:
//   footstep += clamp(step_gain * xi, +-max_step)                       (at each step start)
// Timing (NimbRo's df law on the lateral capture point): while the capture point leaves towards
// the swing side the swing foot must land sooner; away from it, later:
//   phase rate = clamp(1 + timing_gain * s xi_y, 1 - max_timing, 1 + max_timing),
// s = +1 while the left foot swings, -1 while the right does.
// Support exchange at touchdown (Bit-Bots' phase reset): late in a step (phase >= touchdown_phase)
// the step ends as soon as the swing leg's knee servo reports a load of touchdown_load or more
// (a fraction of its stall torque: the foot has taken weight), instead of when the clock says.
// Real-time: no allocation, no I/O.
#pragma once

#include <string_view>

#include <array>

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::walk {

class CaptureStep {
 public:
  /// Phase bins per step pair of the learned expected tilt.
  static constexpr std::size_t kBins = 40;

  /// Registers PREFIX.capture.* (PREFIX: "walk", or "walk.spline" for the spline walk; start-up
  /// only; throws on a name clash).
  CaptureStep(ParameterStore& store, double period_s, std::string_view prefix = "walk");

  void reset() noexcept;
  /// True if any gain is set.
  bool footstep_enabled() const noexcept;
  bool timing_enabled() const noexcept;
  /// One tick. `pair_phase` in [0, 1): the phase within the current step pair (left step then
  /// right step); `walking`: steps are being taken (the expected tilt learns only then);
  /// `standing`: the robot stands (the standing tilt is averaged into the expectation).
  /// `step_time` [s] paces the learning.
  void update(const AttitudeEstimator& attitude, double pair_phase, double step_time, bool walking,
              bool standing) noexcept;
  /// Footstep offset for the step that starts now [m] (walk frame: x forward, y left).
  double step_offset_x() const noexcept;
  double step_offset_y() const noexcept;
  /// Phase rate for this tick while `left_swings` (1 = the clock's pace).
  double phase_rate(bool left_swings) const noexcept;
  /// True if the swing foot has landed: `phase` (0..1) is late enough and the swing knee's
  /// present load (fraction of stall torque) reaches walk.capture.touchdown_load (> 0).
  bool touchdown(double phase, double swing_knee_load) const noexcept;
  /// The capture point deviation [m] (walk frame) of the latest update().
  double deviation_x() const noexcept { return xi_x_; }
  double deviation_y() const noexcept { return xi_y_; }

 private:
  const ParameterStore& store_;
  double period_s_;
  ParamHandle step_gain_x_, step_gain_y_, max_step_x_, max_step_y_;
  ParamHandle timing_gain_, max_timing_, com_height_, learn_steps_, rate_filter_time_,
      touchdown_load_, touchdown_phase_;
  bool tilt_valid_ = false;
  double roll_ = 0.0, pitch_ = 0.0;
  std::array<double, kBins> expected_roll_{}, expected_pitch_{};
  double previous_roll_dev_ = 0.0, previous_pitch_dev_ = 0.0;
  double roll_rate_ = 0.0, pitch_rate_ = 0.0;
  double xi_x_ = 0.0, xi_y_ = 0.0;
};

}  // namespace stride::fw::walk
