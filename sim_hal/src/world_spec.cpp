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

}  // namespace

const std::vector<WorldOptionInfo>& world_option_table() {
  using V = WorldValue;
  static const std::vector<WorldOptionInfo> table = {
      {"base",
       "",
       "faithful",
       "named world: faithful (identified servo law, CM730 IMU, turf), seed (the thesis's: seed "
       "servo law, ideal IMU, 2 cm grass) or a world file (.json, from stride calibrate); "
       "servo_law, imu and contact override its parts",
       V::kName,
       {"faithful", "seed"}},
      {"engine",
       "",
       "simbody",
       "physics engine: simbody (Stride's contact) or mujoco (MuJoCo's)",
       V::kName,
       {"simbody", "mujoco"}},
      {"physics_step_us",
       "us",
       "2000",
       "fixed physics step, dividing the firmware's control period",
       V::kInteger,
       {},
       kMinStepUs,
       kMaxStepUs},
      {"servo_law",
       "",
       "the world's",
       "servo model: seed (Gazebo figures) or identified (MX, BAM M6)",
       V::kName,
       {"seed", "identified"}},
      {"imu",
       "",
       "the world's",
       "IMU model: ideal (true value plus white noise), cm730 (chips and the stock CM730) or "
       "cm730-nimbro (chips and the CM730 with NimbRo's firmware: 16-bit registers, a "
       "magnetometer)",
       V::kName,
       {"ideal", "cm730", "cm730-nimbro"}},
      {"mag_disturbance",
       "gauss",
       "0.03",
       "amplitude of the floor's magnetic disturbance the cm730-nimbro magnetometer reads "
       "(per horizontal axis, varying over 3 m; sim_hal/models/README.md \"Magnetometer\")",
       V::kNumber,
       {},
       0.0,
       0.5},
      {"contact",
       "",
       "the world's",
       "field contact: seed (the seed's 2 cm grass; a standing robot's studs sink 5.3 mm), turf "
       "(a 5 mm layer over solid ground, 4.7 mm), soft (a deep turf: 15 mm layer, more damping, "
       "4.0 mm) or hard (a carpet or stiff floor, 0.4 mm); sim_hal/models/README.md \"Grounds\"",
       V::kName,
       {"seed", "turf", "soft", "hard"}},
      {"friction",
       "",
       "the contact's, 1",
       "Coulomb friction coefficient of feet and links on the field",
       V::kNumber,
       {},
       0.05,
       3.0},
      {"urdf",
       "",
       "",
       "robot description (URDF) to simulate instead of the igus model",
       V::kPath,
       {}},
      {"noise",
       "",
       "on",
       "sensor noise and per-episode IMU bias: on or off",
       V::kName,
       {"on", "off"}},
      {"seed",
       "",
       "1",
       "world random seed (randomisation and sensor noise)",
       V::kInteger,
       {},
       0.0,
       9007199254740992.0},
      {"friction_range",
       "",
       "0",
       "friction scale drawn at each reset, uniform 1 +- range",
       V::kNumber,
       {},
       0.0,
       kMaxRange},
      {"mass_range",
       "",
       "0",
       "per-link mass and inertia scale drawn at each reset, 1 +- range",
       V::kNumber,
       {},
       0.0,
       kMaxRange},
      {"strength_range",
       "",
       "0",
       "per-servo stall torque scale drawn at each reset, 1 +- range",
       V::kNumber,
       {},
       0.0,
       kMaxRange},
      {"latency_probability",
       "",
       "0",
       "chance per reset of one control period of extra command latency",
       V::kNumber,
       {},
       0.0,
       1.0},
      {"contact_range",
       "",
       "0",
       "ground drawn at each reset: u uniform in +-range, the contact's stiffness, damping and "
       "layer thickness moved |u| of the way (log scale) towards hard (u < 0) or soft (u > 0); "
       "1 spans hard..soft",
       V::kNumber,
       {},
       0.0,
       kMaxContactRange},
      {"com_range",
       "m",
       "0",
       "trunk centre of mass moved at each reset, x and y uniform in +-range (make_variants.py: "
       "0.01)",
       V::kNumber,
       {},
       0.0,
       0.05},
      {"latency_ticks",
       "",
       "the world file's, 0",
       "control periods between a command and the servos acting on it",
       V::kInteger,
       {},
       0.0,
       static_cast<double>(RobotCalibration::kMaxLatencyTicks)},
      {"push",
       "",
       "",
       "T,DIR,IMPULSE: push the trunk T s after the start, DIR forward|backward|left|right or "
       "degrees anticlockwise from the robot's heading, IMPULSE in N s (a force over 10 ms at the "
       "trunk's centre of mass); repeatable",
       V::kPushes,
       {}},
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

namespace {

/// The name option `key` takes from `value` (already checked against the choices).
Status set_name(WorldSpec& s, std::string_view key, const std::string& value) {
  if (key == "engine") {
    parse_engine_kind(value, s.engine);
  } else if (key == "servo_law") {
    s.servo_law = value == "seed" ? ServoLaw::kSeed : ServoLaw::kIdentified;
  } else if (key == "imu") {
    s.imu = value == "cm730"          ? ImuKind::kCm730
            : value == "cm730-nimbro" ? ImuKind::kCm730Nimbro
                                      : ImuKind::kIdeal;
  } else if (key == "contact") {
    s.contact = value;
  } else if (key == "noise") {
    s.noise = value == "on";
  }
  return {};
}

void set_number(WorldSpec& s, std::string_view key, double v) {
  if (key == "physics_step_us") s.physics_step_us = static_cast<std::int64_t>(v);
  if (key == "friction") s.friction = v;
  if (key == "seed") s.seed = static_cast<std::uint64_t>(v);
  if (key == "friction_range") s.randomise.friction_range = v;
  if (key == "mass_range") s.randomise.mass_range = v;
  if (key == "strength_range") s.randomise.strength_range = v;
  if (key == "latency_probability") s.randomise.latency_probability = v;
  if (key == "contact_range") s.randomise.contact_range = v;
  if (key == "com_range") s.randomise.com_range = v;
  if (key == "latency_ticks") s.latency_ticks = static_cast<int>(v);
  if (key == "mag_disturbance") s.mag_disturbance = v;
}

Status set_base(WorldSpec& s, const std::string& value, const std::string& shown) {
  if (looks_like_world_file(value)) {
    WorldFile file;
    if (Status st = load_world_file(value, file); !st)
      return Status::error(shown + ": " + st.message());
    s.base = file.base;
    s.file = file;
    s.file_path = value;
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

Status set_urdf(WorldSpec& s, const std::string& value, const std::string& shown) {
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

}  // namespace

Status WorldSpec::set(const WorldOptionInfo& option, const std::string& value,
                      const std::string& shown) {
  switch (option.value) {
    case WorldValue::kName: {
      if (option.key == "base") return set_base(*this, value, shown);
      bool known = false;
      for (const std::string_view c : option.choices) known = known || c == value;
      if (!known)
        return Status::error(shown + ": expected " + world_option_choices(option) + ", got '" +
                             value + "'");
      return set_name(*this, option.key, value);
    }
    case WorldValue::kInteger:
    case WorldValue::kNumber: {
      const bool integer = option.value == WorldValue::kInteger;
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (value.empty() || *end != '\0' || !std::isfinite(v) || (integer && v != std::floor(v)))
        return Status::error(shown + ": expected " + (integer ? "an integer" : "a number") +
                             (option.unit.empty() ? "" : " of " + std::string(option.unit)) +
                             ", got '" + value + "'");
      if (!(v >= option.min && v <= option.max))
        return Status::error(shown + ": must be in " + fw::format_number(option.min) + ".." +
                             fw::format_number(option.max) +
                             (option.unit.empty() ? "" : " " + std::string(option.unit)) +
                             ", got " + value);
      set_number(*this, option.key, v);
      return {};
    }
    case WorldValue::kPath:
      return set_urdf(*this, value, shown);
    case WorldValue::kPushes: {
      TorsoPush push;
      // The time is checked against the episode by its runner.
      if (Status s = parse_push(value, std::numeric_limits<double>::infinity(), push, shown); !s)
        return s;
      pushes.push_back(push);
      return {};
    }
  }
  return {};
}

Status WorldSpec::set(std::string_view key, const std::string& value, const std::string& shown) {
  const WorldOptionInfo* option = find_world_option(key);
  if (option == nullptr)
    return Status::error(shown + ": unknown world option (known: " + world_option_keys() + ")");
  return set(*option, value, shown);
}

bool WorldSpec::is_set(std::string_view key) const {
  const WorldSpec d;
  if (key == "base") return base != d.base || file.has_value();
  if (key == "engine") return engine != d.engine;
  if (key == "physics_step_us") return physics_step_us != d.physics_step_us;
  if (key == "servo_law") return servo_law.has_value();
  if (key == "imu") return imu.has_value();
  if (key == "mag_disturbance") return mag_disturbance.has_value();
  if (key == "contact") return contact.has_value();
  if (key == "friction") return friction.has_value();
  if (key == "urdf") return !urdf.empty();
  if (key == "noise") return noise != d.noise;
  if (key == "seed") return seed != d.seed;
  if (key == "friction_range") return randomise.friction_range != 0.0;
  if (key == "mass_range") return randomise.mass_range != 0.0;
  if (key == "strength_range") return randomise.strength_range != 0.0;
  if (key == "latency_probability") return randomise.latency_probability != 0.0;
  if (key == "contact_range") return randomise.contact_range != 0.0;
  if (key == "com_range") return randomise.com_range != 0.0;
  if (key == "latency_ticks") return latency_ticks.has_value();
  if (key == "push") return !pushes.empty();
  return false;
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
