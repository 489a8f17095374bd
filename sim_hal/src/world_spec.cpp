// The world option table and its one mapping from names to models (see world_spec.hpp).
#include "stride/sim_hal/world_spec.hpp"

#include <cmath>

#include "stride/firmware/parameter_store.hpp"

namespace stride::sim {

namespace {

/// The physics step's range [us]: up to 20 ms (a 50 Hz firmware's period).
constexpr double kMinStepUs = 1.0, kMaxStepUs = 20000.0;

std::string choices_text(const WorldOptionInfo& o) {
  std::string text;
  for (std::size_t i = 0; i < o.choices.size(); ++i) {
    if (i > 0) text += i + 1 == o.choices.size() ? " or " : ", ";
    text += o.choices[i];
  }
  return text;
}

}  // namespace

const std::vector<WorldOptionInfo>& world_option_table() {
  static const std::vector<WorldOptionInfo> table = {
      {"base",
       "",
       "faithful",
       "named world: faithful (identified servo law, CM730 IMU, turf) or seed (the thesis's: "
       "seed servo law, ideal IMU, 2 cm grass); servo_law, imu and contact override its parts",
       {"faithful", "seed"}},
      {"engine",
       "",
       "simbody",
       "physics engine: simbody (Stride's contact) or mujoco (MuJoCo's)",
       {"simbody", "mujoco"}},
      {"physics_step_us",
       "us",
       "2000",
       "fixed physics step, dividing the firmware's control period",
       {},
       kMinStepUs,
       kMaxStepUs},
      {"servo_law",
       "",
       "the world's",
       "servo model: seed (Gazebo figures) or identified (MX, BAM M6)",
       {"seed", "identified"}},
      {"imu",
       "",
       "the world's",
       "IMU model: ideal (true value plus white noise) or cm730 (chips and CM730)",
       {"ideal", "cm730"}},
      {"contact",
       "",
       "the world's",
       "field contact: seed (the seed's 2 cm grass) or turf (a 5 mm layer over solid ground, "
       "sim_hal/models/README.md)",
       {"seed", "turf"}},
  };
  return table;
}

const WorldOptionInfo* find_world_option(std::string_view key) {
  for (const WorldOptionInfo& o : world_option_table())
    if (o.key == key) return &o;
  return nullptr;
}

std::string world_option_flag(std::string_view key) {
  std::string flag = "--";
  for (const char c : key) flag += c == '_' ? '-' : c;
  return flag;
}

std::string world_option_keys() {
  std::string keys;
  for (const WorldOptionInfo& o : world_option_table())
    keys += (keys.empty() ? "" : ", ") + std::string(o.key);
  return keys;
}

Status check_physics_step(std::int64_t step_ns, std::int64_t control_period_ns,
                          const std::string& shown) {
  const double step_us = static_cast<double>(step_ns) * 1e-3;
  if (!(step_us >= kMinStepUs && step_us <= kMaxStepUs))
    return Status::error(shown + ": must be in " + fw::format_number(kMinStepUs) + ".." +
                         fw::format_number(kMaxStepUs) + " us, got " + fw::format_number(step_us));
  if (control_period_ns <= 0 || control_period_ns % step_ns != 0)
    return Status::error(shown + ": " + fw::format_number(step_us) +
                         " us does not divide the firmware's control period of " +
                         fw::format_number(static_cast<double>(control_period_ns) * 1e-3) + " us");
  return {};
}

std::string world_option_cli_flag(std::string_view key) {
  return key == "base" ? std::string("--world") : world_option_flag(key);
}

Status apply_world_option(const WorldOptionInfo& option, const std::string& value,
                          const std::string& shown, WorldOptions& out) {
  if (!option.choices.empty()) {
    bool known = false;
    for (const std::string_view c : option.choices) known = known || c == value;
    if (!known)
      return Status::error(shown + ": expected " + choices_text(option) + ", got '" + value + "'");
    if (option.key == "base") {
      WorldPreset preset = WorldPreset::kFaithful;
      parse_world_preset(value, preset);
      out.apply(preset);
    } else if (option.key == "engine") {
      parse_engine_kind(value, out.engine);
    } else if (option.key == "servo_law") {
      out.servo.law = value == "seed" ? ServoLaw::kSeed : ServoLaw::kIdentified;
    } else if (option.key == "imu") {
      out.use_cm730_imu(value == "cm730");
    } else if (option.key == "contact") {
      parse_contact_kind(value, out.contact);
    }
    return {};
  }
  // A number: an integer number of microseconds (the only numeric option today).
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v) || v != std::floor(v))
    return Status::error(shown + ": expected an integer number of " + std::string(option.unit) +
                         ", got '" + value + "'");
  if (!(v >= option.min && v <= option.max))
    return Status::error(shown + ": must be in " + fw::format_number(option.min) + ".." +
                         fw::format_number(option.max) + " " + std::string(option.unit) + ", got " +
                         value);
  if (option.key == "physics_step_us") out.physics_step_ns = static_cast<std::int64_t>(v) * 1000;
  return {};
}

}  // namespace stride::sim
