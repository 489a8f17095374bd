// What each replay window of a flight log shows, read from the logged commands (issue 56 point
// 2): the staged calibration fits each value on the windows that tell it best. The same rules
// hold for a robot's log and a simulated one; no part names are needed in the log.
//
//   still: no servo's goal moves by more than kStillRad over the window and nothing walks:
//          the IMU biases (the mean logged-minus-simulated reading is the bias);
//   arms:  only the arms' goals move (shoulders and elbows, MX-64), the legs' stay: the arms
//          hold loads the URDF gives, free of contacts (identify_arms): the MX-64 torque and
//          the friction, from the arms' channels alone;
//   legs:  the legs' goals move, both feet down (sway, squats, weight shifts, the stand's
//          ramps): the MX-106 torque and the trunk's mass and centre of mass;
//   steps: the legs' goals move and one knee bends more than the other by over
//          kSingleSupportRad: a foot is lifted (identify_steps). Single support diverges
//          sooner in replay, but it loads the stance leg with the whole robot: the staged fit
//          keeps these windows for the MX-106 and the trunk (left out, it found them on fewer
//          of the study's robots);
//   walk:  the walk engine runs in the window: the latency (it shows most there).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "stride/firmware/recorder/flight_log_reader.hpp"

namespace stride::calibration {

enum class WindowPart { kStill, kArms, kLegs, kSteps, kWalk };

/// "still", "arms", "legs", "steps" or "walk".
const char* window_part_name(WindowPart part);

/// A goal that moves less than this over a window does not move [rad] (the stand's balance
/// feedback moves the legs' goals by a few hundredths of a degree).
constexpr double kStillRad = 0.005;
/// Knee goals further apart than this lift a foot [rad] (identify_steps: 0.6; squats: 0).
constexpr double kSingleSupportRad = 0.2;

/// The part of each window of `window_s` of `log` (sim::window_first_indices' order).
std::vector<WindowPart> classify_windows(const fw::FlightLog& log, double window_s);

/// The servos (hal::servo_index order) whose name in the log's servo table names an arm joint
/// (shoulder, elbow), as a bit mask.
std::uint32_t arm_servo_mask(const fw::FlightLog& log);

}  // namespace stride::calibration
