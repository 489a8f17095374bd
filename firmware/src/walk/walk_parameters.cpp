// The walk parameter table (names, Ind_O defaults, optimiser bounds, units) and its
// registration in the ParameterStore. See walk_parameters.hpp for the naming scheme.
#include "stride/firmware/walk/walk_parameters.hpp"

namespace stride::fw::walk {
namespace {

#define STRIDE_WALK_FIELD(expr) [](WalkParameters& p) noexcept -> double& { return p.expr; }

// Rows: name, field, Ind_O, min, max, unit, description, Table E index.
// Bounds are Ind_O +- 50 % unless noted.
constexpr std::array<WalkParameterInfo, kWalkParameterCount> kTable{{
    {"walk.stance.body_height", STRIDE_WALK_FIELD(body_height), 0.60, 0.50, 0.615, "m",
     "height of the torso reference point (0.18 m above the hip pitch axes) over the ground "
     "(not in the genome; bounds: leg reach)",
     0},
    {"walk.stance.body_tilt", STRIDE_WALK_FIELD(body_tilt), 0.174, 0.087, 0.261, "rad",
     "torso pitch while walking, forward positive", 1},
    {"walk.stance.arms.left.start.pitch", STRIDE_WALK_FIELD(left_arm_start.pitch), 1.570, 0.785,
     2.355, "rad", "left shoulder pitch at the swing start (NUbots angle: 1.57 = arm down)", 2},
    {"walk.stance.arms.left.start.roll", STRIDE_WALK_FIELD(left_arm_start.roll), 0.0, -0.3, 0.3,
     "rad", "left shoulder roll at the swing start (absolute bounds)", 3},
    {"walk.stance.arms.left.start.elbow", STRIDE_WALK_FIELD(left_arm_start.elbow), -0.523, -0.7845,
     -0.2615, "rad", "left elbow at the swing start", 4},
    {"walk.stance.arms.left.end.pitch", STRIDE_WALK_FIELD(left_arm_end.pitch), 1.570, 0.785, 2.355,
     "rad", "left shoulder pitch at the swing end (NUbots angle)", 5},
    {"walk.stance.arms.left.end.roll", STRIDE_WALK_FIELD(left_arm_end.roll), 0.0, -0.3, 0.3, "rad",
     "left shoulder roll at the swing end (absolute bounds)", 6},
    {"walk.stance.arms.left.end.elbow", STRIDE_WALK_FIELD(left_arm_end.elbow), -0.523, -0.7845,
     -0.2615, "rad", "left elbow at the swing end", 7},
    {"walk.stance.arms.right.start.pitch", STRIDE_WALK_FIELD(right_arm_start.pitch), 1.570, 0.785,
     2.355, "rad", "right shoulder pitch at the swing start (NUbots angle)", 8},
    {"walk.stance.arms.right.start.roll", STRIDE_WALK_FIELD(right_arm_start.roll), 0.0, -0.3, 0.3,
     "rad", "right shoulder roll at the swing start (absolute bounds)", 9},
    {"walk.stance.arms.right.start.elbow", STRIDE_WALK_FIELD(right_arm_start.elbow), -0.523,
     -0.7845, -0.2615, "rad", "right elbow at the swing start", 10},
    {"walk.stance.arms.right.end.pitch", STRIDE_WALK_FIELD(right_arm_end.pitch), 1.570, 0.785,
     2.355, "rad", "right shoulder pitch at the swing end (NUbots angle)", 11},
    {"walk.stance.arms.right.end.roll", STRIDE_WALK_FIELD(right_arm_end.roll), 0.0, -0.3, 0.3,
     "rad", "right shoulder roll at the swing end (absolute bounds)", 12},
    {"walk.stance.arms.right.end.elbow", STRIDE_WALK_FIELD(right_arm_end.elbow), -0.523, -0.7845,
     -0.2615, "rad", "right elbow at the swing end", 13},
    {"walk.stance.foot_offset.x", STRIDE_WALK_FIELD(foot_offset_x), -0.072, -0.108, -0.036, "m",
     "footOffset[0]: the torso and the ZMP ride -x ahead of the ankles", 14},
    {"walk.stance.foot_offset.y", STRIDE_WALK_FIELD(foot_offset_y), -0.050, -0.075, -0.025, "m",
     "footOffset[1]: feet 0.055 - y from the torso; ZMP -y outward of the ankle", 15},
    {"walk.stance.gains.arms", STRIDE_WALK_FIELD(gain_arms), 10.0, 5.0, 15.0, "1",
     "arm servo gain 0-100 (P register = round(2.54 g))", 16},
    {"walk.stance.gains.legs", STRIDE_WALK_FIELD(gain_legs), 15.0, 7.5, 22.5, "1",
     "leg servo gain 0-100 (P register = round(2.54 g))", 17},
    {"walk.stance.limit_margin_y", STRIDE_WALK_FIELD(limit_margin_y), -0.050, -0.075, -0.025, "m",
     "lateral collision margin: feet at least 0.11 - margin apart", 18},
    {"walk.walk_cycle.step_time", STRIDE_WALK_FIELD(step_time), 0.85, 0.425, 1.275, "s",
     "duration of one step", 19},
    {"walk.walk_cycle.zmp_time", STRIDE_WALK_FIELD(zmp_time), 0.40, 0.20, 0.60, "s",
     "inverted-pendulum time constant tau (x'' = (x - zmp)/tau^2)", 20},
    {"walk.walk_cycle.hip_roll_compensation", STRIDE_WALK_FIELD(hip_roll_compensation), 0.024,
     0.012, 0.036, "rad", "support hip roll added during single support", 21},
    {"walk.walk_cycle.step.height", STRIDE_WALK_FIELD(step_height), 0.07, 0.035, 0.105, "m",
     "swing-foot lift", 22},
    {"walk.walk_cycle.step.limits.x_min", STRIDE_WALK_FIELD(step_limits.x_min), -0.10, -0.15, -0.05,
     "m", "swing foot x relative to the support foot, minimum", 23},
    {"walk.walk_cycle.step.limits.x_max", STRIDE_WALK_FIELD(step_limits.x_max), 0.10, 0.05, 0.15,
     "m", "swing foot x relative to the support foot, maximum", 24},
    {"walk.walk_cycle.step.limits.y_min", STRIDE_WALK_FIELD(step_limits.y_min), 0.0, 0.0, 0.05, "m",
     "outward swing foot y change, minimum (absolute bounds)", 25},
    {"walk.walk_cycle.step.limits.y_max", STRIDE_WALK_FIELD(step_limits.y_max), 0.30, 0.15, 0.45,
     "m", "outward swing foot y relative to the support foot, maximum", 26},
    {"walk.walk_cycle.step.limits.angle_min", STRIDE_WALK_FIELD(step_limits.angle_min), 0.0, 0.0,
     0.1, "rad", "outward swing foot yaw relative to the support foot, minimum (absolute)", 27},
    {"walk.walk_cycle.step.limits.angle_max", STRIDE_WALK_FIELD(step_limits.angle_max), 0.262,
     0.131, 0.393, "rad", "outward swing foot yaw relative to the support foot, maximum", 28},
    {"walk.walk_cycle.step.height_slow_fraction", STRIDE_WALK_FIELD(step_height_slow_fraction), 0.5,
     0.25, 0.75, "1", "lift factor at zero speed", 29},
    {"walk.walk_cycle.step.height_fast_fraction", STRIDE_WALK_FIELD(step_height_fast_fraction), 1.5,
     0.75, 2.25, "1", "lift factor at full speed", 30},
    {"walk.walk_cycle.velocity.limits.x_min", STRIDE_WALK_FIELD(velocity_limits.x_min), -0.027,
     -0.0405, -0.0135, "m/step", "backward velocity limit (command -1)", 31},
    {"walk.walk_cycle.velocity.limits.x_max", STRIDE_WALK_FIELD(velocity_limits.x_max), 0.30, 0.15,
     0.45, "m/step", "forward velocity limit (command +1)", 32},
    {"walk.walk_cycle.velocity.limits.y_min", STRIDE_WALK_FIELD(velocity_limits.y_min), -0.010,
     -0.015, -0.005, "m/step", "rightward velocity limit (command -1)", 33},
    {"walk.walk_cycle.velocity.limits.y_max", STRIDE_WALK_FIELD(velocity_limits.y_max), 0.010,
     0.005, 0.015, "m/step", "leftward velocity limit (command +1)", 34},
    {"walk.walk_cycle.velocity.limits.angle_min", STRIDE_WALK_FIELD(velocity_limits.angle_min),
     -0.8, -1.2, -0.4, "rad/step", "clockwise turning limit (command -1)", 35},
    {"walk.walk_cycle.velocity.limits.angle_max", STRIDE_WALK_FIELD(velocity_limits.angle_max), 0.8,
     0.4, 1.2, "rad/step", "anticlockwise turning limit (command +1)", 36},
    {"walk.walk_cycle.velocity.high_speed", STRIDE_WALK_FIELD(velocity_high), 0.06, 0.03, 0.09,
     "m/step", "above this forward velocity the high acceleration limits apply", 37},
    {"walk.walk_cycle.acceleration.limits.x", STRIDE_WALK_FIELD(acceleration_limits.x), 1.5, 0.75,
     2.25, "m/step/s", "x velocity change per second", 38},
    {"walk.walk_cycle.acceleration.limits.y", STRIDE_WALK_FIELD(acceleration_limits.y), 0.045,
     0.0225, 0.0675, "m/step/s", "y velocity change per second", 39},
    {"walk.walk_cycle.acceleration.limits.angle", STRIDE_WALK_FIELD(acceleration_limits.angle), 5.0,
     2.5, 7.5, "rad/step/s", "turning velocity change per second", 40},
    {"walk.walk_cycle.acceleration.limits_high.x", STRIDE_WALK_FIELD(acceleration_limits_high.x),
     0.08, 0.04, 0.12, "m/step/s", "x velocity change per second at high speed", 41},
    {"walk.walk_cycle.acceleration.limits_high.y", STRIDE_WALK_FIELD(acceleration_limits_high.y),
     0.05, 0.025, 0.075, "m/step/s", "y velocity change per second at high speed", 42},
    {"walk.walk_cycle.acceleration.limits_high.angle",
     STRIDE_WALK_FIELD(acceleration_limits_high.angle), 5.0, 2.5, 7.5, "rad/step/s",
     "turning velocity change per second at high speed", 43},
    {"walk.walk_cycle.acceleration.turning_factor", STRIDE_WALK_FIELD(acceleration_turning_factor),
     0.6, 0.3, 0.9, "rad/step", "planar speed is scaled by max(0, 1 - |w|/factor) while turning",
     44},
    {"walk.walk_cycle.single_support_phase.start", STRIDE_WALK_FIELD(single_support_start), 0.12,
     0.06, 0.18, "1", "step phase at which single support starts (phi1)", 45},
    {"walk.walk_cycle.single_support_phase.end", STRIDE_WALK_FIELD(single_support_end), 0.88, 0.44,
     0.94, "1", "step phase at which single support ends (phi2; upper bound < 1)", 46},
}};

#undef STRIDE_WALK_FIELD

// Store ranges wider than the seed's bounds, for the omnidirectional task (issue 22). Chosen so
// that the published speeds of this robot class (Bit-Bots' NUgus in simulation: 0.38 m/s forward,
// 0.42 backward, 0.26 sideways, 1.97 rad/s turning) are reachable at step times of 0.5-0.85 s:
// velocities in m/step or rad/step = speed x step time, step limits about 1.5 x that, and
// acceleration limits that reach full speed within about two steps.
// Turning (issue 41 point 3): a step pair turns at most step.limits.angle_max (the inner foot only
// closes up to the outer one), so 1.97 rad/s needs angle_max / (2 step_time) >= 1.97. The feet's
// relative yaw is shared by the two hip yaw servos (the torso is midway), whose limits are
// +-0.8 rad (servo_table.json): angle_max up to 1.6 rad; and steps down to 0.35 s (the step
// frequency of the teams that walk this robot class fast, 2.5-3 steps/s), with which 1.6 rad per
// pair is 2.3 rad/s.
constexpr std::array<WalkParameterRange, 15> kWideRanges{{
    {"walk.walk_cycle.step_time", 0.35, 1.275},
    {"walk.walk_cycle.step.limits.x_min", -0.30, -0.02},
    {"walk.walk_cycle.step.limits.x_max", 0.05, 0.30},
    {"walk.walk_cycle.step.limits.angle_max", 0.131, 1.6},
    {"walk.walk_cycle.velocity.limits.x_min", -0.30, -0.0135},
    {"walk.walk_cycle.velocity.limits.y_min", -0.25, -0.005},
    {"walk.walk_cycle.velocity.limits.y_max", 0.005, 0.25},
    {"walk.walk_cycle.velocity.limits.angle_min", -1.5, -0.4},
    {"walk.walk_cycle.velocity.limits.angle_max", 0.4, 1.5},
    {"walk.walk_cycle.acceleration.limits.y", 0.0225, 0.5},
    {"walk.walk_cycle.acceleration.limits.angle", 2.5, 15.0},
    {"walk.walk_cycle.acceleration.limits_high.x", 0.04, 1.0},
    {"walk.walk_cycle.acceleration.limits_high.y", 0.025, 0.5},
    {"walk.walk_cycle.acceleration.limits_high.angle", 2.5, 15.0},
    {"walk.walk_cycle.acceleration.turning_factor", 0.3, 2.0},
}};

}  // namespace

std::span<const WalkParameterRange> walk_parameter_wide_ranges() noexcept {
  return kWideRanges;
}

WalkParameterRange walk_parameter_store_range(const WalkParameterInfo& row) noexcept {
  for (const auto& wide : kWideRanges)
    if (wide.name == row.name) return wide;
  return {row.name, row.min, row.max};
}

std::span<const WalkParameterInfo, kWalkParameterCount> walk_parameter_table() noexcept {
  return kTable;
}

WalkParameters default_walk_parameters() noexcept {
  WalkParameters params;
  for (const auto& row : kTable) row.field(params) = row.default_value;
  return params;
}

WalkParameterSet::WalkParameterSet(ParameterStore& store) : store_(store) {
  for (std::size_t i = 0; i < kTable.size(); ++i) {
    const auto& row = kTable[i];
    const WalkParameterRange range = walk_parameter_store_range(row);
    handles_[i] = store.add_real(std::string(row.name), row.default_value, range.min, range.max,
                                 std::string(row.unit), std::string(row.description));
  }
}

void WalkParameterSet::read(WalkParameters& out) const noexcept {
  for (std::size_t i = 0; i < kTable.size(); ++i) kTable[i].field(out) = store_.value(handles_[i]);
}

}  // namespace stride::fw::walk
