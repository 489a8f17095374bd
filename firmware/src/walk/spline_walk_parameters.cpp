// The spline walk's parameter table (meanings and sources in spline_walk_parameters.hpp).
#include "stride/firmware/walk/spline_walk_parameters.hpp"

#include <string>

namespace stride::fw::walk {
namespace {

#define STRIDE_SPLINE_FIELD(member) \
  [](SplineWalkParameters& p) noexcept -> double& { return p.member; }

constexpr std::array<SplineWalkParameterInfo, kSplineWalkParameterCount> kTable{{
    {"walk.spline.frequency", STRIDE_SPLINE_FIELD(frequency), 1.5, 0.5, 3.5, "Hz",
     "full walking cycles (two steps) per second"},
    {"walk.spline.double_support_ratio", STRIDE_SPLINE_FIELD(double_support_ratio), 0.2, 0.0, 0.5,
     "1", "share of each step with both feet on the ground"},
    {"walk.spline.foot_distance", STRIDE_SPLINE_FIELD(foot_distance), 0.20, 0.14, 0.30, "m",
     "lateral distance between the ankles when standing"},
    {"walk.spline.foot_rise", STRIDE_SPLINE_FIELD(foot_rise), 0.035, 0.005, 0.12, "m",
     "highest lift of the swing ankle"},
    {"walk.spline.foot_apex_phase", STRIDE_SPLINE_FIELD(foot_apex_phase), 0.5, 0.2, 0.8, "1",
     "share of the swing at which the foot is highest"},
    {"walk.spline.foot_overshoot", STRIDE_SPLINE_FIELD(foot_overshoot), 0.0, 0.0, 0.5, "1",
     "the swing foot passes its target by this share of the step before it settles"},
    {"walk.spline.foot_overshoot_phase", STRIDE_SPLINE_FIELD(foot_overshoot_phase), 0.8, 0.55, 0.95,
     "1", "share of the swing at which the overshoot is largest"},
    {"walk.spline.foot_put_down", STRIDE_SPLINE_FIELD(foot_put_down), 0.0, 0.0, 0.02, "m",
     "the swing foot aims this far below the ground at the step's end (an early, firm touchdown)"},
    {"walk.spline.foot_clearance", STRIDE_SPLINE_FIELD(foot_clearance), 0.02, 0.0, 0.06, "m",
     "least gap between the soles' inner edges (the collision rule)"},
    {"walk.spline.trunk_height", STRIDE_SPLINE_FIELD(trunk_height), 0.40, 0.33, 0.45, "m",
     "height of the hip roll/pitch crossings above the ground"},
    {"walk.spline.trunk_pitch", STRIDE_SPLINE_FIELD(trunk_pitch), 0.15, -0.1, 0.4, "rad",
     "trunk pitched forward"},
    {"walk.spline.trunk_pitch_vx", STRIDE_SPLINE_FIELD(trunk_pitch_vx), 0.0, -1.0, 1.0, "rad s/m",
     "extra trunk pitch per m/s of forward speed"},
    {"walk.spline.trunk_x_offset", STRIDE_SPLINE_FIELD(trunk_x_offset), 0.0, -0.05, 0.05, "m",
     "hips ahead of the midpoint of the feet"},
    {"walk.spline.trunk_sway", STRIDE_SPLINE_FIELD(trunk_sway), 0.025, 0.0, 0.08, "m",
     "lateral sway amplitude of the hips, towards the support foot"},
    {"walk.spline.trunk_sway_phase", STRIDE_SPLINE_FIELD(trunk_sway_phase), 0.0, -0.25, 0.25, "1",
     "sway delayed by this share of a cycle"},
    {"walk.spline.trunk_sway_vy", STRIDE_SPLINE_FIELD(trunk_sway_vy), 0.0, -0.5, 0.5, "s",
     "sway amplitude change per m/s of sideways speed"},
    {"walk.spline.start_steps", STRIDE_SPLINE_FIELD(start_steps), 2.0, 0.0, 8.0, "steps",
     "steps in place after the start, the sway ramping in, before the walk moves"},
    {"walk.spline.max_step_forward", STRIDE_SPLINE_FIELD(max_step_forward), 0.08, 0.0, 0.25,
     "m/step", "forward step at full command"},
    {"walk.spline.max_step_backward", STRIDE_SPLINE_FIELD(max_step_backward), 0.06, 0.0, 0.20,
     "m/step", "backward step at full command"},
    {"walk.spline.max_step_side", STRIDE_SPLINE_FIELD(max_step_side), 0.06, 0.0, 0.25, "m/cycle",
     "side step of the outer foot at full command (one side step per cycle)"},
    {"walk.spline.max_turn", STRIDE_SPLINE_FIELD(max_turn), 0.5, 0.0, 1.6, "rad/cycle",
     "turn per cycle at full command"},
    {"walk.spline.turn_inner_ratio", STRIDE_SPLINE_FIELD(turn_inner_ratio), 0.5, 0.0, 0.5, "1",
     "share of a cycle's turn the closing (inner) foot takes: 0.5 both feet alike, 0 toe-out only"},
    {"walk.spline.acceleration_x", STRIDE_SPLINE_FIELD(acceleration_x), 0.6, 0.05, 3.0, "m/s^2",
     "forward speed change per second"},
    {"walk.spline.acceleration_y", STRIDE_SPLINE_FIELD(acceleration_y), 0.6, 0.05, 3.0, "m/s^2",
     "sideways speed change per second"},
    {"walk.spline.acceleration_turn", STRIDE_SPLINE_FIELD(acceleration_turn), 3.0, 0.2, 15.0,
     "rad/s^2", "turn rate change per second"},
    {"walk.spline.timing_gain_pitch", STRIDE_SPLINE_FIELD(timing_gain_pitch), 0.0, 0.0, 30.0, "1/m",
     "phase rate rise per m of sagittal capture-point deviation (0: off)"},
    {"walk.spline.arm_swing", STRIDE_SPLINE_FIELD(arm_swing), 0.0, -3.0, 3.0, "rad/m",
     "URDF shoulder pitch taken off per m the opposite foot is ahead of the hips (0: arms still)"},
    {"walk.spline.gains.arms", STRIDE_SPLINE_FIELD(gain_arms), 10.0, 1.0, 100.0, "0-100",
     "arm servo gain (P register = round(2.54 g))"},
    {"walk.spline.gains.legs", STRIDE_SPLINE_FIELD(gain_legs), 30.0, 5.0, 100.0, "0-100",
     "leg servo gain (P register = round(2.54 g))"},
}};

#undef STRIDE_SPLINE_FIELD

}  // namespace

std::span<const SplineWalkParameterInfo, kSplineWalkParameterCount>
spline_walk_parameter_table() noexcept {
  return kTable;
}

SplineWalkParameters default_spline_walk_parameters() noexcept {
  SplineWalkParameters params;
  for (const auto& row : kTable) row.field(params) = row.default_value;
  return params;
}

SplineWalkParameterSet::SplineWalkParameterSet(ParameterStore& store) : store_(store) {
  for (std::size_t i = 0; i < kTable.size(); ++i) {
    const auto& row = kTable[i];
    handles_[i] = store.add_real(std::string(row.name), row.default_value, row.min, row.max,
                                 std::string(row.unit), std::string(row.description));
  }
}

void SplineWalkParameterSet::read(SplineWalkParameters& out) const noexcept {
  for (std::size_t i = 0; i < kTable.size(); ++i) kTable[i].field(out) = store_.value(handles_[i]);
}

}  // namespace stride::fw::walk
