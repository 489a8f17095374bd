// Window classification for the staged calibration (window_parts.hpp).
#include "stride/calibration/window_parts.hpp"

#include <algorithm>
#include <array>
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
    case WindowPart::kWalk:
      return "walk";
  }
  return "?";
}

std::uint32_t arm_servo_mask(const fw::FlightLog& log) {
  const nlohmann::json table = log.header.value("servo_table", nlohmann::json::array());
  std::uint32_t mask = 0;
  for (std::size_t i = 0; i < hal::kServoCount && i < table.size(); ++i) {
    if (!table[i].is_object()) continue;
    const std::string name = table[i].value("name", "");
    if (name.find("shoulder") != std::string::npos || name.find("elbow") != std::string::npos)
      mask |= 1U << i;
  }
  return mask;
}

std::vector<WindowPart> classify_windows(const fw::FlightLog& log, double window_s) {
  std::size_t n = 0;
  const std::vector<std::size_t> firsts = sim::window_first_indices(log, window_s, &n);
  const std::uint32_t arms = arm_servo_mask(log);
  std::vector<WindowPart> parts;
  parts.reserve(firsts.size());
  for (std::size_t first : firsts) {
    std::array<double, hal::kServoCount> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    bool walking = false;
    for (std::size_t t = first; t <= first + n && t < log.ticks.size(); ++t) {
      walking = walking || log.ticks[t].meta.motion == fw::MotionState::kWalk;
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
    parts.push_back(walking       ? WindowPart::kWalk
                    : others_move ? WindowPart::kLegs
                    : arms_move   ? WindowPart::kArms
                                  : WindowPart::kStill);
  }
  return parts;
}

}  // namespace stride::calibration
