// Walk measures from the simulator's ground truth (issue 22): the walking frame, the forward
// walk's straightness, and the omnidirectional task's segments and scores.
//
// Walking frame: the midpoint of the two feet (ground truth; unlike the torso it does not rock
// sideways with every step) and the torso's yaw, unwrapped over the episode (YawTracker), so
// that turns of more than pi are measured in full.
//
// Straightness of a translation from frame a to frame b, commanded along the unit axis u of a's
// heading: along = d . u, off-axis = |d . u_perp|, heading change = |yaw_b - yaw_a|.
// Drift ratio = off-axis / max(|along|, kDriftDistanceFloor): a walk that hardly moves is not
// held to millimetres.
//
// walk-omni (OmniTiming, walk_omni_settings.hpp): after start_s, six segments forward, backward,
// left, right, turn left, turn right; each ramps the command from 0 to full (ramp_s), holds it
// (hold_s) and stops it (command 0, stop_s). Per segment, over the hold: the speed along the
// commanded axis [m/s or rad/s, positive = the commanded way], the off-axis drift, the heading
// change, and for the turns the translation. Objectives (minimised):
//   Obj1 = -(v_forward + v_backward + 2 (v_left + v_right)/2 + 0.2 (w_left + w_right)/2)
//          (the Hamburg Bit-Bots' score; sideways and turning averaged over both sides)
//   Obj2 = max |a| of the IMU over the episode (the seed's stability measure)
// Constraints (g >= 0 feasible; 0 when met), each term relative to its limit and at most 1:
//   c0 fell: -(1 + time lost / episode length)
//   c1 drift: sum over translation segments of max(-1, min(0, 1 - drift ratio / max_drift_ratio))
//   c2 heading: sum over translation segments of max(-1, min(0, 1 - |heading change| / limit))
//   c3 turn translation: sum over turns of max(-1, min(0, 1 - translation / limit))
// A segment the robot did not reach (it fell before) has speed 0 and adds -1 to each of its
// constraints, so that falling earlier never lowers the violation (in a first short run without
// this, the least-violating members were those that fell in the second segment).
#pragma once

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "stride/hal/types.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/walk_omni_settings.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::opt {

/// A planar pose in the world [m, m, rad].
struct PlanarPose {
  double x = 0.0, y = 0.0, yaw = 0.0;
};

/// The yaw of the torso about world z (rad, in (-pi, pi]).
double torso_yaw(const Eigen::Isometry3d& torso);

/// Unwraps the torso yaw tick by tick.
class YawTracker {
 public:
  void reset(double yaw);
  /// The unwrapped yaw after this sample.
  double update(double yaw);
  double yaw() const { return unwrapped_; }

 private:
  double last_ = 0.0, unwrapped_ = 0.0;
};

/// Feet midpoint and the given (unwrapped) yaw.
PlanarPose walking_frame(const sim::GroundTruth& truth, double yaw);

/// Distance below which the drift ratio is taken against this floor instead [m].
inline constexpr double kDriftDistanceFloor = 0.25;

struct Translation {
  double along_m = 0.0;             ///< displacement along the commanded axis
  double off_axis_m = 0.0;          ///< |displacement across it|
  double heading_change_rad = 0.0;  ///< |yaw_b - yaw_a|
  double distance_m = 0.0;          ///< |displacement|
  double drift_ratio() const;
};
/// The translation from a to b commanded along (ux, uy) of a's heading (a unit vector).
Translation measure_translation(const PlanarPose& a, const PlanarPose& b, double ux, double uy);

/// min(0, limit - value) scaled by `scale`, or 0 when the limit is off (negative).
double limit_violation(double value, double limit, double scale = 1.0);

enum class OmniDirection : int { kForward, kBackward, kLeft, kRight, kTurnLeft, kTurnRight };
inline constexpr int kOmniSegments = 6;
/// "forward", "backward", "left", "right", "turn_left", "turn_right".
const char* to_string(OmniDirection direction);
/// The normalised walk command of a direction (vx, vy, vtheta).
std::array<double, 3> omni_command(OmniDirection direction);
/// The reference speed of each direction, in OmniDirection order [m/s; rad/s turning]: the
/// Hamburg Bit-Bots' walk tuned for maximum speed per direction on NUgus (an igus-derived
/// robot) in simulation, 0.38 forward, 0.42 backward, 0.26 sideways, 1.97 rad/s turning (1,000
/// trials, 8-24 h on a 12-core machine; issue 22). The report's and the validation's reference
/// row and walk-command's speed objective read them here.
inline constexpr std::array<double, kOmniSegments> kReferenceSpeeds = {0.38, 0.42, 0.26,
                                                                       0.26, 1.97, 1.97};

struct OmniSegment {
  bool measured = false;            ///< the hold was completed
  double speed = 0.0;               ///< along the commanded axis [m/s or rad/s]
  double drift_ratio = 0.0;         ///< translations: off-axis / max(|along|, floor)
  double heading_change_rad = 0.0;  ///< translations: over the hold
  double translation_m = 0.0;       ///< turns: |displacement| over the hold
};
using OmniSegments = std::array<OmniSegment, kOmniSegments>;

/// The time line of a walk-omni episode and its measurement at the hold boundaries.
class OmniEpisode {
 public:
  OmniEpisode(const OmniTiming& timing, double period_s);
  double duration_s() const { return timing_.total_s(); }
  /// The normalised command for tick `tick` (0 before the first segment and while stopping).
  std::array<double, 3> command(hal::Tick tick) const;
  /// Called once per tick with the world in its state at `tick`: tracks the yaw and samples
  /// the walking frame at the start and end of every hold.
  void observe(hal::Tick tick, const sim::SimWorld& world);
  const OmniSegments& segments() const { return segments_; }

 private:
  OmniTiming timing_;
  double period_s_;
  YawTracker yaw_;
  bool started_ = false;
  std::array<PlanarPose, kOmniSegments> hold_start_{};
  OmniSegments segments_{};
};

/// Every segment (direction) was measured: the walk-omni and walk-ramp validation success.
bool every_segment_measured(const OmniSegments& segments);
/// Obj1 of the walk-omni task from the segments' speeds (see the header comment).
double omni_speed_objective(const OmniSegments& segments);
/// Constraints c1..c3 of the walk-omni task (c0, the fall, is the caller's).
std::array<double, 3> omni_constraints(const OmniSegments& segments,
                                       const StraightnessLimits& limits);

/// One segment's term of a straightness constraint, relative to its limit and at most 1:
/// max(-1, min(0, 1 - figure / limit)), or -1 for a segment not reached (`measured` false).
/// The caller adds it only when the limit is on (drift: >= 0; heading, turn translation: > 0).
double drift_term(bool measured, double drift_ratio, const StraightnessLimits& limits);
double heading_term(bool measured, double heading_change_rad, const StraightnessLimits& limits);
double turn_translation_term(bool measured, double translation_m, const StraightnessLimits& limits);

}  // namespace stride::opt
