// Flight log header: firmware identity, servo table, parameters at start, description hash.
#include "stride/firmware/recorder/flight_log_header.hpp"

#include <cstdio>
#include <ctime>

#include "stride/firmware/motion_manager.hpp"
#include "stride/firmware/recorder/flight_log_format.hpp"

#ifndef STRIDE_VERSION
#define STRIDE_VERSION "unknown"
#endif
#ifndef STRIDE_GIT_DESCRIBE
#define STRIDE_GIT_DESCRIBE ""
#endif

namespace stride::fw::flight_log {

std::string_view firmware_version() noexcept {
  return STRIDE_VERSION;
}

std::string_view firmware_git() noexcept {
  return STRIDE_GIT_DESCRIBE;
}

nlohmann::json servo_table_json(const ServoTable& servos) {
  nlohmann::json list = nlohmann::json::array();
  for (const ServoSpec& s : servos.servos()) {
    list.push_back({{"id", s.id},
                    {"name", s.name},
                    {"model", std::string(to_string(s.model))},
                    {"direction", s.direction},
                    {"offset_rad", s.offset_rad},
                    {"min_rad", s.min_rad},
                    {"max_rad", s.max_rad}});
  }
  return list;
}

std::string robot_description_hash(const ServoTable& servos, const RobotDescription& robot) {
  char model[17];
  std::snprintf(model, sizeof model, "%016llx", static_cast<unsigned long long>(robot.hash()));
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : servo_table_json(servos).dump() + model) {
    hash ^= static_cast<std::uint8_t>(c);
    hash *= 0x100000001b3ULL;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return std::string("fnv1a64:") + hex;
}

nlohmann::json make_header(const HeaderInputs& in) {
  nlohmann::json params = nlohmann::json::array();
  for (ParamHandle h = 0; h < in.params->size(); ++h) {
    const ParamSpec& spec = in.params->spec(h);
    params.push_back({{"name", spec.name},
                      {"type", std::string(to_string(spec.type))},
                      {"unit", spec.unit},
                      {"min", spec.min},
                      {"max", spec.max},
                      {"default", spec.default_value},
                      {"value", in.params->value(h)},
                      {"read_only", spec.read_only},
                      {"needs_restart", spec.needs_restart}});
  }
  nlohmann::json motion_states = nlohmann::json::array();
  for (MotionState s : {MotionState::kStand, MotionState::kWalk, MotionState::kScript,
                        MotionState::kFallen, MotionState::kGetUp, MotionState::kFalling}) {
    motion_states.push_back(std::string(to_string(s)));
  }
  char started[32] = "";
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  if (gmtime_r(&now, &utc) != nullptr) std::strftime(started, sizeof started, "%FT%TZ", &utc);
  return {{"format", "stride-flight-log"},
          {"format_version", kFormatVersion},
          {"firmware",
           {{"name", "stride-fw"},
            {"version", std::string(firmware_version())},
            {"git", std::string(firmware_git())}}},
          {"started_utc", started},
          {"hal", in.hal},
          {"params_file", in.params_file.string()},
          {"period_ns", in.period_ns},
          {"robot_description",
           {{"kind", "servo-table+rigid-body"},
            {"servo_table_file", in.servo_table_file.string()},
            {"file", in.robot_description_file.string()},
            {"hash", robot_description_hash(*in.servos, *in.robot)}}},
          {"servo_table", servo_table_json(*in.servos)},
          {"parameters", params},
          {"motion_states", motion_states},
          {"tick_fixed_bytes", kTickFixedBytes},
          {"param_change_bytes", kParamChangeBytes}};
}

}  // namespace stride::fw::flight_log
