// SplineWalkParameters: the tunable values of the spline walk (walk.spline.*), each with a
// physical meaning, a unit and the range the store accepts; their registration and real-time
// read-back. The engine's closed-loop parts keep their own parameters under the same prefix
// (walk.spline.balance.*, walk.spline.capture.*, walk.spline.compliance.*).
//
// Defaults: a conservative walk found by hand in the simulator's default world (3 steps a second,
// docs in firmware/src/walk/SPLINE_WALK.md); ranges: the values of the fast small-humanoid walks
// of ../shared/research/walk-mechanisms.md (Bit-Bots' optimised sets: 2-3 Hz full cycles,
// double support 0.02-0.3, foot rise 0.03-0.12 m) widened to what this robot's legs reach (the
// trunk height: a leg of 0.2 + 0.2 m and an ankle 0.0565 m above the stud tips).
// The frequency's upper bound, 3.5 Hz (7 steps a second), is above what the identified MX-106
// follows at full foot rise (docs: the servo tracking error at each frequency).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "stride/firmware/parameter_store.hpp"

namespace stride::fw::walk {

/// One consistent snapshot of the spline walk's parameters (SI units).
struct SplineWalkParameters {
  // --- timing ---
  double frequency = 1.5;             ///< full cycles (two steps) per second [Hz]
  double double_support_ratio = 0.2;  ///< share of each step with both feet down [1]
  // --- swing foot ---
  double foot_distance = 0.20;        ///< lateral distance of the ankles standing [m]
  double foot_rise = 0.035;           ///< swing ankle's highest lift [m]
  double foot_apex_phase = 0.5;       ///< share of the swing at which the foot is highest [1]
  double foot_overshoot = 0.0;        ///< horizontal overshoot of the swing target [share of step]
  double foot_overshoot_phase = 0.8;  ///< share of the swing at which the overshoot peaks [1]
  double foot_put_down = 0.0;         ///< the swing foot aims this far below the ground [m]
  double foot_clearance = 0.02;       ///< least gap between the soles' inner edges [m]
  // --- trunk ---
  double trunk_height = 0.40;     ///< hip roll/pitch crossings above the ground [m]
  double trunk_pitch = 0.15;      ///< trunk pitched forward [rad]
  double trunk_pitch_vx = 0.0;    ///< extra pitch per m/s of forward speed [rad s/m]
  double trunk_x_offset = 0.0;    ///< hips ahead of the feet's midpoint [m]
  double trunk_sway = 0.025;      ///< lateral sway amplitude of the hips [m]
  double trunk_sway_phase = 0.0;  ///< sway delayed by this share of a cycle [1]
  double trunk_sway_vy = 0.0;     ///< sway change per m/s of sideways speed [s]
  double start_steps = 2.0;       ///< steps in place (sway ramping in) before moving [steps]
  // --- steps and limits ---
  double max_step_forward = 0.08;   ///< forward step at full command [m/step]
  double max_step_backward = 0.06;  ///< backward step at full command [m/step]
  double max_step_side = 0.06;      ///< outer foot's side step at full command [m/cycle]
  double max_turn = 0.5;            ///< turn per cycle at full command [rad/cycle]
  double turn_inner_ratio = 0.5;    ///< share of a cycle's turn the closing foot takes [1]
  double acceleration_x = 0.6;      ///< forward speed change per second [m/s^2]
  double acceleration_y = 0.6;      ///< sideways speed change per second [m/s^2]
  double acceleration_turn = 3.0;   ///< turn rate change per second [rad/s^2]
  // --- closed loop (beyond the shared balance, capture and compliance parts) ---
  double timing_gain_pitch = 0.0;  ///< phase rate rise per m of sagittal capture point [1/m]
  // --- arms and servos ---
  double arm_swing = 0.0;   ///< shoulder pitch per m of the opposite foot's advance [rad/m]
  double gain_arms = 10.0;  ///< arm servo gain 0-100 (P register = round(2.54 g))
  double gain_legs = 30.0;  ///< leg servo gain 0-100
};

/// One row of the table.
struct SplineWalkParameterInfo {
  std::string_view name;                             ///< full store name
  double& (*field)(SplineWalkParameters&) noexcept;  ///< the snapshot field the row fills
  double default_value;
  double min;
  double max;
  std::string_view unit;
  std::string_view description;
};

inline constexpr std::size_t kSplineWalkParameterCount = 29;

/// Every row, in the order of the struct.
std::span<const SplineWalkParameterInfo, kSplineWalkParameterCount>
spline_walk_parameter_table() noexcept;

/// The defaults as a snapshot.
SplineWalkParameters default_spline_walk_parameters() noexcept;

/// Registers the rows in a store and reads them back in real time.
class SplineWalkParameterSet {
 public:
  /// Registers every row (throws std::invalid_argument on a name clash; start-up only).
  explicit SplineWalkParameterSet(ParameterStore& store);
  /// The live values. Real-time: no allocation, no exceptions.
  void read(SplineWalkParameters& out) const noexcept;

 private:
  const ParameterStore& store_;
  std::array<ParamHandle, kSplineWalkParameterCount> handles_{};
};

}  // namespace stride::fw::walk
