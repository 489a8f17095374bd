// WalkParameters: the walk engine's tunable values (the seed's 46 Table-E parameters, igus.md
// 2.1 / 7.5, plus the body height), their registration in the ParameterStore under walk.*, and
// their real-time read-back.
//
// Naming: "walk." + the NUbots YAML key of igus.md 2.1 in snake case, with list entries given
// names instead of indices (stance.foot_offset[0] -> walk.stance.foot_offset.x; the limit lists
// [xmin, xmax, ymin, ymax, amin, amax] -> .x_min ... .angle_max; vectors [x, y, angle] -> .x,
// .y, .angle; arm poses [pitch, roll, elbow] -> .pitch, .roll, .elbow).
// Units: SI (m, s, rad, m/step, rad/step); gains are the scripts' 0-100 scale.
// Defaults: Ind_O of igus.md 7.5 (= configuration D, body height 0.60 m). Bounds: the
// optimiser's, Ind_O +-50 % (absolute bounds where Ind_O is 0 and where +-50 % would leave the
// parameter's meaning, e.g. single-support end < 1). walk_parameter_table() lists them.
//
// Arm angles are in the NUbots convention as in Table E: shoulder pitch 1.57 = arm hanging
// down. The engine commands URDF angles (URDF shoulder pitch = NUbots - pi/2, igus.md 1.5).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "stride/firmware/parameter_store.hpp"

namespace stride::fw::walk {

/// An arm pose [rad] in the NUbots convention (shoulder pitch 1.57 = arm down).
struct ArmPose {
  double pitch = 0.0;
  double roll = 0.0;
  double elbow = 0.0;
};

/// Planar limits [min, max] for x [m], y [m] and angle [rad] (per step, or per step of
/// velocity: the walk's velocities are in m/step and rad/step, igus.md 2.3).
struct PlanarLimits {
  double x_min = 0.0, x_max = 0.0;
  double y_min = 0.0, y_max = 0.0;
  double angle_min = 0.0, angle_max = 0.0;
};

/// Per-axis values x, y, angle.
struct PlanarVector {
  double x = 0.0, y = 0.0, angle = 0.0;
};

/// One consistent snapshot of the walk parameters (plain values, SI units).
struct WalkParameters {
  // --- stance ---
  double body_height = 0.60;  ///< torso reference point above the ground [m] (see walk_engine)
  double body_tilt = 0.174;   ///< torso pitch, forward positive [rad]
  ArmPose left_arm_start, left_arm_end, right_arm_start, right_arm_end;
  double foot_offset_x = -0.072;   ///< footOffset[0] [m]: torso/ZMP ahead of the ankle by -x
  double foot_offset_y = -0.050;   ///< footOffset[1] [m]: stance half-width = 0.055 - y
  double limit_margin_y = -0.050;  ///< feet keep >= 0.11 - margin apart laterally [m]
  double gain_arms = 10.0;         ///< arm servo gain, 0-100 (P = round(2.54 g))
  double gain_legs = 15.0;         ///< leg servo gain, 0-100
  // --- walk cycle ---
  double step_time = 0.85;               ///< T: duration of one step [s]
  double zmp_time = 0.40;                ///< tau: LIPM time constant [s]
  double hip_roll_compensation = 0.024;  ///< support hip roll added in single support [rad]
  double step_height = 0.07;             ///< swing-foot lift [m]
  PlanarLimits step_limits;              ///< swing foot relative to the support foot
  double step_height_slow_fraction = 0.5;
  double step_height_fast_fraction = 1.5;
  PlanarLimits velocity_limits;              ///< [m/step, rad/step]
  double velocity_high = 0.06;               ///< above this vx the "high" acceleration limits apply
  PlanarVector acceleration_limits;          ///< [m/step/s, rad/step/s]
  PlanarVector acceleration_limits_high;     ///< same, for vx > velocity_high
  double acceleration_turning_factor = 0.6;  ///< planar speed factor 1 - |w|/this
  double single_support_start = 0.12;        ///< phi1: phase at which single support starts
  double single_support_end = 0.88;          ///< phi2: phase at which single support ends
};

/// One row of the parameter table.
struct WalkParameterInfo {
  std::string_view name;                       ///< full store name, "walk.walk_cycle.step_time"
  double& (*field)(WalkParameters&) noexcept;  ///< the snapshot field this row fills
  double default_value;                        ///< Ind_O (igus.md 7.5)
  double min;                                  ///< optimiser lower bound
  double max;                                  ///< optimiser upper bound
  std::string_view unit;
  std::string_view description;
  int table_e_index;  ///< 1..46 (Table E order of igus.md 7.5), 0 = not in the genome
};

/// Number of parameters in the genome (Table E) and in total (plus walk.body_height).
inline constexpr std::size_t kGenomeParameterCount = 46;
inline constexpr std::size_t kWalkParameterCount = 47;

/// All walk parameters: body height first, then Table E order 1..46.
std::span<const WalkParameterInfo, kWalkParameterCount> walk_parameter_table() noexcept;

/// A range wider than the seed's +-50 % that the store accepts for a parameter (issue 22: the
/// omnidirectional task searches these; at +-50 % the walk cannot go faster sideways than
/// 0.015 m/step). The row's min/max stay the seed's optimiser bounds (walk.json).
struct WalkParameterRange {
  std::string_view name;
  double min;
  double max;
};
/// The widened ranges (velocity, step and acceleration limits of the omnidirectional walk).
std::span<const WalkParameterRange> walk_parameter_wide_ranges() noexcept;
/// The range the store registers for a row: its wide range if it has one, else [min, max].
WalkParameterRange walk_parameter_store_range(const WalkParameterInfo& row) noexcept;

/// The defaults (Ind_O) as a snapshot.
WalkParameters default_walk_parameters() noexcept;

/// Registers the walk parameters in a store and reads them back in real time.
class WalkParameterSet {
 public:
  /// Registers every row of walk_parameter_table() (throws std::invalid_argument if a name
  /// is already registered; start-up only).
  explicit WalkParameterSet(ParameterStore& store);

  /// The live values. Real-time: no allocation, no exceptions.
  void read(WalkParameters& out) const noexcept;

 private:
  const ParameterStore& store_;
  std::array<ParamHandle, kWalkParameterCount> handles_{};
};

}  // namespace stride::fw::walk
