// The walking tasks' straightness limits read from and written to a config
// (straightness_limits.hpp).
#include "stride/optimiser/tasks/straightness_limits.hpp"

#include <string>
#include <utility>

#include "stride/optimiser/tasks/task_config.hpp"

namespace stride::opt {

Status parse_straightness(const nlohmann::json& doc, StraightnessLimits& out) {
  for (auto [name, target] : {std::pair{"max_drift_ratio", &out.max_drift_ratio},
                              {"max_heading_change_deg", &out.max_heading_change_deg},
                              {"max_turn_translation_m", &out.max_turn_translation_m}}) {
    if (doc.contains(name) && doc.at(name).is_null()) {
      *target = -1.0;
      continue;
    }
    if (Status s = read_config_number(doc, name, *target); !s) return s;
    if (*target < 0.0) return Status::error(std::string(name) + ": must be >= 0 or null (off)");
  }
  return {};
}

void write_straightness(const StraightnessLimits& limits, nlohmann::json& doc) {
  auto limit = [](double v) { return v < 0.0 ? nlohmann::json(nullptr) : nlohmann::json(v); };
  doc["max_drift_ratio"] = limit(limits.max_drift_ratio);
  doc["max_heading_change_deg"] = limit(limits.max_heading_change_deg);
  doc["max_turn_translation_m"] = limit(limits.max_turn_translation_m);
}

}  // namespace stride::opt
