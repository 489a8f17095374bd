// The smallest valid task config (a walk with one gene and the seed's NSGA-II settings), which
// the task config tests vary one field at a time, and the one-line error a config gives.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "stride/optimiser/tasks/task_config.hpp"

namespace stride::opt {

inline nlohmann::json minimal_task_config() {
  return {
      {"task", "walk"},
      {"seed", 1},
      {"pop", 8},
      {"generations", 2},
      {"pc", 0.8},
      {"pm", 0.1},
      {"etac", 13},
      {"etam", 20},
      {"genes",
       {{{"parameter", "walk.walk_cycle.zmp_time"}, {"min", 0.2}, {"max", 0.6}, {"start", 0.4}}}}};
}

/// "ok", or the message of the error parsing `doc` gives.
inline std::string parse_error_of(const nlohmann::json& doc) {
  TaskConfig c;
  const Status s = parse_task_config(doc, c);
  return s ? std::string("ok") : s.message();
}

}  // namespace stride::opt
