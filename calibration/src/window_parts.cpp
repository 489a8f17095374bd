// Window classification for the staged calibration (window_parts.hpp).
#include "stride/calibration/window_parts.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include "stride/sim_hal/log_replay.hpp"

namespace stride::calibration {

const char* window_part_name(WindowPart part) {
  switch (part) {
    case WindowPart::kStill:
      return "still";
    case WindowPart::kArms:
      return "arms";
    case WindowPart::kLegs:
      return "legs";
    case WindowPart::kSteps:
      return "steps";
    case WindowPart::kWalk:
      return "walk";
  }
  return "?";
}

namespace {

/// The servos' names from the log's servo table, in hal::servo_index order ("" where absent).
std::array<std::string, hal::kServoCount> servo_names(const fw::FlightLog& log) {
  const nlohmann::json table = log.header.value("servo_table", nlohmann::json::array());
  std::array<std::string, hal::kServoCount> names{};
  for (std::size_t i = 0; i < hal::kServoCount && i < table.size(); ++i)
    if (table[i].is_object()) names[i] = table[i].value("name", "");
  return names;
}

/// The index of the servo named `name` in `names`, or -1.
int servo_named(const std::array<std::string, hal::kServoCount>& names, const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

}  // namespace

std::uint32_t arm_servo_mask(const fw::FlightLog& log) {
  std::uint32_t mask = 0;
  const std::array<std::string, hal::kServoCount> names = servo_names(log);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i].find("shoulder") != std::string::npos ||
        names[i].find("elbow") != std::string::npos)
      mask |= 1U << i;
  return mask;
}

std::vector<WindowPart> classify_windows(const fw::FlightLog& log, double window_s) {
  std::size_t n = 0;
  const std::vector<std::size_t> firsts = sim::window_first_indices(log, window_s, &n);
  const std::uint32_t arms = arm_servo_mask(log);
  const std::array<std::string, hal::kServoCount> names = servo_names(log);
  const int right_knee = servo_named(names, "r_knee"), left_knee = servo_named(names, "l_knee");
  std::vector<WindowPart> parts;
  parts.reserve(firsts.size());
  for (std::size_t first : firsts) {
    std::array<double, hal::kServoCount> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    bool walking = false;
    double knees_apart = 0.0;
    for (std::size_t t = first; t <= first + n && t < log.ticks.size(); ++t) {
      walking = walking || log.ticks[t].meta.motion == fw::MotionState::kWalk;
      if (right_knee >= 0 && left_knee >= 0)
        knees_apart =
            std::max(knees_apart, std::abs(log.ticks[t].commands.servos[right_knee].position_rad -
                                           log.ticks[t].commands.servos[left_knee].position_rad));
      for (std::size_t i = 0; i < hal::kServoCount; ++i) {
        const double goal = log.ticks[t].commands.servos[i].position_rad;
        lo[i] = std::min(lo[i], goal);
        hi[i] = std::max(hi[i], goal);
      }
    }
    bool arms_move = false, others_move = false;
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      if (hi[i] - lo[i] <= kStillRad) continue;
      ((arms >> i) & 1U ? arms_move : others_move) = true;
    }
    parts.push_back(walking                                          ? WindowPart::kWalk
                    : others_move && knees_apart > kSingleSupportRad ? WindowPart::kSteps
                    : others_move                                    ? WindowPart::kLegs
                    : arms_move                                      ? WindowPart::kArms
                                                                     : WindowPart::kStill);
  }
  return parts;
}

}  // namespace stride::calibration
