// Spline-walk trajectories of one step: the quintic segments of the swing foot, the support
// foot's settling and the hips, built once at the step's start and sampled every tick
// (spline_walk_engine.hpp has the design, ../shared/research/spline-walk.md its lineage).
// Walk-plane coordinates: x forward, y left [m], yaw [rad]; foot heights are the ankle's
// height above its standing height [m] (negative: pressed into the ground). Real-time: no
// allocation; build() and sample() are plain arithmetic.
#pragma once

#include "stride/firmware/walk/footstep_planner.hpp"
#include "stride/firmware/walk/pose2.hpp"
#include "stride/firmware/walk/quintic.hpp"
#include "stride/firmware/walk/spline_footsteps.hpp"
#include "stride/firmware/walk/spline_walk_parameters.hpp"

namespace stride::fw::walk {

/// One foot at one instant.
struct FootSample {
  Pose2 pose;
  double lift = 0.0;  ///< ankle above its standing height [m]
};

/// The hips (midpoint of the hip roll/pitch crossings) at one instant, per coordinate.
struct HipsSample {
  AxisState x, y, yaw;  ///< walk plane [m, m, rad] with their rates
  AxisState pitch;      ///< trunk pitch, forward positive [rad]
};

/// Everything a tick needs from the plan.
struct StepSample {
  FootSample left, right;
  HipsSample hips;
  bool left_down = true, right_down = true;  ///< the foot is planned on the ground
  double phase = 0.0;                        ///< share of the step elapsed [0, 1]
};

/// Where a step starts from: the feet and the hips as the previous step left them.
struct StepStart {
  Foot swing = Foot::kLeft;
  FootSample support, swing_foot;
  HipsSample hips;
};

/// Where the step is to end.
struct StepGoal {
  Pose2 swing_target;
  double duration = 0.5;  ///< T [s]
  double rise = 0.0;      ///< foot rise of this step [m] (0: the foot slides)
  HipsSample hips_end;    ///< the hips' state at the step's end
};

/// The hips' end state of a step: the midpoint of the support foot and the swing target,
/// trunk_x_offset ahead, swayed by `sway` [m] (towards +y of the heading at phase 0.25 of a
/// cycle), moving at `v` (walk frame of the end heading); `cycle_phase_end` is the cycle phase
/// at the step's end (0.5 after a left-support step, 1.0 after a right-support step).
HipsSample nominal_hips_end(const Pose2& support, const Pose2& swing_target, const WalkVelocity& v,
                            double sway, double cycle_phase_end, const SplineWalkParameters& p,
                            double pitch) noexcept;

class StepPlan {
 public:
  /// Builds the segments of one step.
  void build(const StepStart& from, const StepGoal& goal, const SplineWalkParameters& p) noexcept;
  /// The plan at time t [s] after the step's start (held at the end after the duration).
  StepSample sample(double t) const noexcept;
  double duration() const noexcept { return duration_; }
  Foot swing() const noexcept { return swing_; }

 private:
  Foot swing_ = Foot::kLeft;
  double duration_ = 0.5;
  double swing_begin_ = 0.0;     // end of the double support [s]
  double overshoot_time_ = 0.0;  // peak of the overshoot [s] (= duration_ without one)
  double apex_time_ = 0.0;
  Pose2 support_;
  Quintic support_lift_;  // the support foot settling onto the ground in double support
  Quintic swing_x_[2], swing_y_[2], swing_yaw_[2];  // to the overshoot, then back
  Quintic swing_lift_[3];  // settle in double support, rise to the apex, put down
  Quintic hips_x_, hips_y_, hips_yaw_, hips_pitch_;
};

}  // namespace stride::fw::walk
