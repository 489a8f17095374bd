// The world option table, WorldSpec and its one mapping from names to models (world_spec.hpp).
#include "stride/sim_hal/world_spec.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <system_error>

#include "stride/firmware/parameter_store.hpp"
#include "stride/sim_hal/grounds.hpp"

namespace stride::sim {

namespace {

/// The physics step's range [us]: up to 20 ms (a 50 Hz firmware's period).
constexpr double kMinStepUs = 1.0, kMaxStepUs = 20000.0;
/// A relative randomisation range below 1 (a scale never reaches 0).
constexpr double kMaxRange = 0.99;
/// The bounds of a drawn servo friction or torque scale (world_file.cpp's calibration bounds
/// are 0..5 for friction and 0.1..3 for torque; a draw stays inside both).
constexpr double kMinServoScale = 0.1, kMaxServoScale = 3.0;
/// The largest drawn supply voltage [V] (the MX's recommended maximum is 14.8 V; a full 4S
/// LiPo gives 16.8 V).
constexpr double kMaxSupplyV = 20.0;

using nlohmann::json;

Status set_base(WorldSpec& s, const std::string& value, double, const std::string& shown) {
  if (looks_like_world_file(value)) {
    WorldFile file;
    if (Status st = load_world_file(value, file); !st)
      return Status::error(shown + ": " + st.message());
    s.use_world_file(std::move(file), value);
    return {};
  }
  WorldPreset preset = WorldPreset::kFaithful;
  if (!parse_world_preset(value, preset))
    return Status::error(shown + ": expected faithful, seed or a world file (.json), got '" +
                         value + "'");
  s.base = preset;
  s.file.reset();
  s.file_path.clear();
  return {};
}

Status set_urdf(WorldSpec& s, const std::string& value, double, const std::string& shown) {
  std::error_code error;
  if (value.empty() || !std::filesystem::is_regular_file(value, error))
    return Status::error(shown + ": no such file '" + value + "'");
  auto model = std::make_shared<RobotModel>();
  if (Status st = RobotModel::load_file(value, *model); !st)
    return Status::error(shown + ": " + st.message());
  s.urdf = value;
  s.model = std::move(model);
  return {};
}

Status add_push(WorldSpec& s, const std::string& value, double, const std::string& shown) {
  TorsoPush push;
  // The time is checked against the episode by its runner.
  if (Status st = parse_push(value, std::numeric_limits<double>::infinity(), push, shown); !st)
    return st;
  s.pushes.push_back(push);
  return {};
}

/// An optional field as JSON: null when unset.
template <typename T>
json optional_json(const std::optional<T>& value) {
  return value ? json(*value) : json();
}

/// A default's value as the help shows it: a name as is, a number as the parameters print it.
std::string default_text(const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_float()) return fw::format_number(value.get<double>());
  return value.dump();
}

// The rows name only the fields they give (designated initialisers); GCC 12 warns of the
// fields left at their defaults, which is the point.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

/// One of the per-reset randomisation ranges: a number in [0, max] bound to `field`.
template <double Randomisation::*field>
WorldOptionInfo randomisation_row(std::string_view key, std::string_view unit,
                                  std::string_view help, double max, double min = 0.0) {
  return {.key = key,
          .unit = unit,
          .help = help,
          .value = WorldValue::kNumber,
          .min = min,
          .max = max,
          .randomisation = true,
          .set = [](WorldSpec& s, const std::string&, double v, const std::string&) -> Status {
            s.randomise.*field = v;
            return {};
          },
          .get = [](const WorldSpec& s) { return json(s.randomise.*field); }};
}

std::vector<WorldOptionInfo> make_table() {
  using V = WorldValue;
  using S = WorldSpec;
  using Text = const std::string&;
  std::vector<WorldOptionInfo> table = {
      {.key = "base",
       .help = "named world: faithful (identified servo law, CM730 IMU, turf), seed (the "
               "thesis's: seed servo law, ideal IMU, 2 cm grass) or a world file (.json, from "
               "stride calibrate); servo_law, imu and contact override its parts",
       .value = V::kWorld,
       .choices = {"faithful", "seed"},
       .always_written = true,
       .set = set_base,
       .get = [](const S& s) { return s.file ? to_json(*s.file) : json(to_string(s.base)); }},
      {.key = "engine",
       .help = "physics engine: simbody (Stride's contact) or mujoco (MuJoCo's)",
       .choices = {"simbody", "mujoco"},
       .set = [](S& s, Text v, double, Text) -> Status {
         parse_engine_kind(v, s.engine);
         return {};
       },
       .get = [](const S& s) { return json(to_string(s.engine)); }},
      {.key = "physics_step_us",
       .unit = "us",
       .help = "fixed physics step, dividing the firmware's control period",
       .value = V::kInteger,
       .min = kMinStepUs,
       .max = kMaxStepUs,
       .always_written = true,
       .set = [](S& s, Text, double v, Text) -> Status {
         s.physics_step_us = static_cast<std::int64_t>(v);
         return {};
       },
       .get = [](const S& s) { return json(s.physics_step_us); }},
      {.key = "servo_law",
       .default_text = "the world's",
       .help = "servo model: seed (Gazebo figures) or identified (MX, BAM M6)",
       .choices = {"seed", "identified"},
       .set = [](S& s, Text v, double, Text) -> Status {
         s.servo_law = v == "seed" ? ServoLaw::kSeed : ServoLaw::kIdentified;
         return {};
       },
       .get =
           [](const S& s) {
             return s.servo_law ? json(*s.servo_law == ServoLaw::kSeed ? "seed" : "identified")
                                : json();
           }},
      {.key = "imu",
       .default_text = "the world's",
       .help = "IMU model: ideal (true value plus white noise), cm730 (chips and the stock "
               "CM730) or cm730-nimbro (chips and the CM730 with NimbRo's firmware: 16-bit "
               "registers, a magnetometer)",
       .choices = {"ideal", "cm730", "cm730-nimbro"},
       .set = [](S& s, Text v, double, Text) -> Status {
         s.imu = v == "cm730"          ? ImuKind::kCm730
                 : v == "cm730-nimbro" ? ImuKind::kCm730Nimbro
                                       : ImuKind::kIdeal;
         return {};
       },
       .get = [](const S& s) { return s.imu ? json(to_string(*s.imu)) : json(); }},
      {.key = "mag_disturbance",
       .unit = "gauss",
       .default_text = fw::format_number(ImuChain::cm730_nimbro().magnetometer.disturbance_gauss),
       .help = "amplitude of the floor's magnetic disturbance the cm730-nimbro magnetometer "
               "reads (per horizontal axis, varying over 3 m; sim_hal/models/README.md "
               "\"Magnetometer\")",
       .value = V::kNumber,
       .min = 0.0,
       .max = 0.5,
       .set = [](S& s, Text, double v, Text) -> Status {
         s.mag_disturbance = v;
         return {};
       },
       .get = [](const S& s) { return optional_json(s.mag_disturbance); }},
      {.key = "contact",
       .default_text = "the world's",
       .help = "field contact: seed (the seed's 2 cm grass; a standing robot's studs sink "
               "5.3 mm), turf (a 5 mm layer over solid ground, 4.7 mm), soft (a deep turf: "
               "15 mm layer, more damping, 4.0 mm) or hard (a carpet or stiff floor, 0.4 mm); "
               "sim_hal/models/README.md \"Grounds\"",
       .choices = {"seed", "turf", "soft", "hard"},
       .set = [](S& s, Text v, double, Text) -> Status {
         s.contact = v;
         return {};
       },
       .get = [](const S& s) { return optional_json(s.contact); }},
      {.key = "friction",
       .default_text = "the contact's, " + fw::format_number(ContactOptions::turf().friction),
       .help = "Coulomb friction coefficient of feet and links on the field",
       .value = V::kNumber,
       .min = 0.05,
       .max = 3.0,
       .set = [](S& s, Text, double v, Text) -> Status {
         s.friction = v;
         return {};
       },
       .get = [](const S& s) { return optional_json(s.friction); }},
      {.key = "urdf",
       .help = "robot description (URDF) to simulate instead of the igus model",
       .value = V::kPath,
       .set = set_urdf,
       .get =
           [](const S& s) {
             return s.urdf.empty() ? json() : json(std::filesystem::absolute(s.urdf).string());
           }},
      {.key = "noise",
       .help = "sensor noise and per-episode IMU bias: on or off",
       .choices = {"on", "off"},
       .set = [](S& s, Text v, double, Text) -> Status {
         s.noise = v == "on";
         return {};
       },
       .get = [](const S& s) { return json(s.noise ? "on" : "off"); }},
      {.key = "seed",
       .help = "world random seed (randomisation and sensor noise)",
       .value = V::kInteger,
       .min = 0.0,
       .max = 9007199254740992.0,
       .set = [](S& s, Text, double v, Text) -> Status {
         s.seed = static_cast<std::uint64_t>(v);
         return {};
       },
       .get = [](const S& s) { return json(s.seed); }},
      randomisation_row<&Randomisation::friction_range>(
          "friction_range", "", "friction scale drawn at each reset, uniform 1 +- range",
          kMaxRange),
      randomisation_row<&Randomisation::mass_range>(
          "mass_range", "", "per-link mass and inertia scale drawn at each reset, 1 +- range",
          kMaxRange),
      randomisation_row<&Randomisation::strength_range>(
          "strength_range", "", "per-servo stall torque scale drawn at each reset, 1 +- range",
          kMaxRange),
      randomisation_row<&Randomisation::latency_probability>(
          "latency_probability", "",
          "chance per reset of one control period of extra command latency", 1.0),
      randomisation_row<&Randomisation::contact_range>(
          "contact_range", "",
          "ground drawn at each reset: u uniform in +-range, the contact's stiffness, damping "
          "and layer thickness moved |u| of the way (log scale) towards hard (u < 0) or soft "
          "(u > 0); 1 spans hard..soft",
          kMaxContactRange),
      randomisation_row<&Randomisation::com_range>(
          "com_range", "m",
          "trunk centre of mass moved at each reset, x and y uniform in +-range "
          "(make_variants.py: 0.01)",
          kMaxComRange),
      randomisation_row<&Randomisation::servo_friction_min>(
          "servo_friction_min", "",
          "every servo's friction scale drawn at each reset, uniform in [min, max] (worn "
          "gears; issue 54: 0.8); equal bounds: that scale, no draw",
          kMaxServoScale, kMinServoScale),
      randomisation_row<&Randomisation::servo_friction_max>(
          "servo_friction_max", "", "the upper bound of servo_friction_min's draw (issue 54: 1.6)",
          kMaxServoScale, kMinServoScale),
      randomisation_row<&Randomisation::servo_torque_min>(
          "servo_torque_min", "",
          "every servo's motor torque scale drawn at each reset, uniform in [min, max] (issue "
          "54: 0.8); equal bounds: that scale, no draw",
          kMaxServoScale, kMinServoScale),
      randomisation_row<&Randomisation::servo_torque_max>(
          "servo_torque_max", "", "the upper bound of servo_torque_min's draw (issue 54: 1.05)",
          kMaxServoScale, kMinServoScale),
      randomisation_row<&Randomisation::supply_min_v>(
          "supply_min", "V",
          "supply voltage drawn at each reset, uniform in [min, max] (a battery through a half; "
          "issue 54: 12); 0 with supply_max 0: the world's",
          kMaxSupplyV),
      randomisation_row<&Randomisation::supply_max_v>(
          "supply_max", "V", "the upper bound of supply_min's draw (a full 4S battery: 16.8)",
          kMaxSupplyV),
      {.key = "latency_ticks",
       .default_text = "the world file's, " + std::to_string(RobotCalibration{}.latency_ticks),
       .help = "control periods between a command and the servos acting on it",
       .value = V::kInteger,
       .min = 0.0,
       .max = static_cast<double>(RobotCalibration::kMaxLatencyTicks),
       .set = [](S& s, Text, double v, Text) -> Status {
         s.latency_ticks = static_cast<int>(v);
         return {};
       },
       .get = [](const S& s) { return optional_json(s.latency_ticks); }},
      {.key = "push",
       .help = "T,DIR,IMPULSE: push the trunk T s after the start, DIR "
               "forward|backward|left|right or degrees anticlockwise from the robot's heading, "
               "IMPULSE in N s (a force over 10 ms at the trunk's centre of mass); repeatable",
       .value = V::kPushes,
       .set = add_push,
       .get =
           [](const S& s) {
             if (s.pushes.empty()) return json();
             json pushes = json::array();
             for (const TorsoPush& p : s.pushes) pushes.push_back(push_text(p));
             return pushes;
           },
       .clear = [](S& s) { s.pushes.clear(); }},
  };
  // The defaults the help shows are the values a default spec holds.
  const WorldSpec defaults;
  for (WorldOptionInfo& o : table)
    if (o.default_text.empty())
      if (const json v = o.get(defaults); !v.is_null()) o.default_text = default_text(v);
  return table;
}

#pragma GCC diagnostic pop

}  // namespace

const std::vector<WorldOptionInfo>& world_option_table() {
  static const std::vector<WorldOptionInfo> table = make_table();
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

std::string world_option_cli_flag(std::string_view key) {
  return key == "base" ? std::string("--world") : world_option_flag(key);
}

std::string world_option_keys() {
  std::string keys;
  for (const WorldOptionInfo& o : world_option_table())
    keys += (keys.empty() ? "" : ", ") + std::string(o.key);
  return keys;
}

std::string world_option_choices(const WorldOptionInfo& o) {
  std::string text;
  for (std::size_t i = 0; i < o.choices.size(); ++i) {
    if (i > 0) text += i + 1 == o.choices.size() ? " or " : ", ";
    text += o.choices[i];
  }
  return text;
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

Status WorldSpec::set(const WorldOptionInfo& option, const std::string& value,
                      const std::string& shown) {
  double number = 0.0;
  if (option.value == WorldValue::kName) {
    bool known = false;
    for (const std::string_view c : option.choices) known = known || c == value;
    if (!known)
      return Status::error(shown + ": expected " + world_option_choices(option) + ", got '" +
                           value + "'");
  }
  if (option.value == WorldValue::kInteger || option.value == WorldValue::kNumber) {
    const bool integer = option.value == WorldValue::kInteger;
    char* end = nullptr;
    number = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(number) ||
        (integer && number != std::floor(number)))
      return Status::error(shown + ": expected " + (integer ? "an integer" : "a number") +
                           (option.unit.empty() ? "" : " of " + std::string(option.unit)) +
                           ", got '" + value + "'");
    if (!(number >= option.min && number <= option.max))
      return Status::error(shown + ": must be in " + fw::format_number(option.min) + ".." +
                           fw::format_number(option.max) +
                           (option.unit.empty() ? "" : " " + std::string(option.unit)) + ", got " +
                           value);
  }
  return option.set(*this, value, number, shown);
}

Status WorldSpec::set(std::string_view key, const std::string& value, const std::string& shown) {
  const WorldOptionInfo* option = find_world_option(key);
  if (option == nullptr)
    return Status::error(shown + ": unknown world option (known: " + world_option_keys() + ")");
  return set(*option, value, shown);
}

bool WorldSpec::is_set(std::string_view key) const {
  const WorldOptionInfo* option = find_world_option(key);
  return option != nullptr && option->get(*this) != option->get(WorldSpec{});
}

void WorldSpec::use_world_file(WorldFile world, std::filesystem::path path) {
  base = world.base;
  file = std::move(world);
  file_path = std::move(path);
}

WorldOptions WorldSpec::to_options() const {
  WorldOptions w;
  w.engine = engine;
  w.seed = seed;
  if (noise) w.imu.set_noise(true);
  w.randomise = randomise;
  if (!urdf.empty()) {
    w.urdf = urdf;
    w.model = model;
  }
  if (file) {
    file->apply(w);
  } else {
    w.apply(base);
  }
  if (servo_law) w.servo.law = *servo_law;
  if (imu) w.use_imu(*imu);
  if (mag_disturbance) w.imu.chain.magnetometer.disturbance_gauss = *mag_disturbance;
  if (contact) parse_contact_kind(*contact, w.contact);
  if (friction) w.contact.friction = *friction;
  w.physics_step_ns = physics_step_us * 1000;
  if (latency_ticks) w.robot.latency_ticks = *latency_ticks;
  w.pushes = pushes;
  return w;
}

}  // namespace stride::sim
