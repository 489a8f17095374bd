// Task configuration parsing with field-naming errors: a config object into a TaskConfig, one
// section at a time; the task's own settings by its type (TaskType::parse_settings). Reading it
// from a file and writing it back: task_config_file.cpp.
#include "stride/optimiser/tasks/task_config.hpp"

#include <algorithm>
#include <cmath>
#include <system_error>

#include "stride/core/json_file.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::opt {

namespace {

Status number(const nlohmann::json& doc, const std::string& field, double& out, bool required,
              const std::string& prefix = "") {
  if (!doc.contains(field)) {
    if (required) return Status::error(prefix + field + ": missing");
    return {};
  }
  const auto& v = doc.at(field);
  if (!v.is_number()) return Status::error(prefix + field + ": must be a number");
  out = v.get<double>();
  if (!std::isfinite(out)) return Status::error(prefix + field + ": must be finite");
  return {};
}

Status integer(const nlohmann::json& doc, const std::string& field, std::int64_t lo,
               std::int64_t hi, std::int64_t& out, bool required) {
  if (!doc.contains(field)) {
    if (required) return Status::error(field + ": missing");
    return {};
  }
  const auto& v = doc.at(field);
  if (!v.is_number_integer()) return Status::error(field + ": must be an integer");
  out = v.get<std::int64_t>();
  if (out < lo || out > hi) {
    return Status::error(field + ": " + std::to_string(out) + " is outside [" + std::to_string(lo) +
                         ", " + std::to_string(hi) + "]");
  }
  return {};
}

Status vector_of(const nlohmann::json& doc, const std::string& field, std::vector<double>& out) {
  out.clear();
  if (!doc.contains(field)) return {};
  const auto& v = doc.at(field);
  if (!v.is_array() || v.size() != 2)
    return Status::error(field + ": must be an array of 2 numbers");
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number())
      return Status::error(field + "[" + std::to_string(i) + "]: must be a number");
    out.push_back(v[i].get<double>());
  }
  return {};
}

const char* const kKnownFields[] = {"task",
                                    "seed",
                                    "pop",
                                    "generations",
                                    "pc",
                                    "pm",
                                    "etac",
                                    "etam",
                                    "seed_fraction",
                                    "resample",
                                    "starts",
                                    "genes",
                                    "duration_s",
                                    "trials",
                                    "aggregate",
                                    "trial_seed",
                                    "randomisation",
                                    "engine",
                                    "engines",
                                    "urdf",
                                    "world",
                                    "params",
                                    "servo_law",
                                    "imu",
                                    "contact",
                                    "physics_step_us",
                                    "validate",
                                    "hypervolume_ideal",
                                    "hypervolume_nadir",
                                    "_comment"};

/// A JSON value as the text the world option table reads (a string as is, else its JSON).
std::string option_text(const nlohmann::json& v) {
  return v.is_string() ? v.get<std::string>() : v.dump();
}

/// A world option a task's trials set (trial_seed, randomisation), not its world: the noise,
/// the seed and the table's randomisation ranges.
bool set_per_trial(const sim::WorldOptionInfo& o) {
  return o.randomisation || o.key == "noise" || o.key == "seed";
}

/// A parameter file named by a config field (`params`, `starts[i]`); the error starts with the
/// field.
Status read_parameter_file(const std::string& file, const std::string& field, nlohmann::json& out) {
  core::JsonFileError why = core::JsonFileError::kNone;
  if (Status s = core::read_json_file(file, out, &why); !s) {
    if (why == core::JsonFileError::kCannotOpen)
      return Status::error(field + ": cannot open '" + file + "'");
    return Status::error(field + ": " + s.message());
  }
  return {};
}

// The simulated world (TaskConfig::world): `world` is a named world ("faithful", "seed"), a
// world file (its path or its object, with "format": "stride-world") or an object of the
// world option table's fields (sim::read_world_spec), whose `engine` is the run's engine. The
// flat fields of before the table (`urdf`, `servo_law`, `imu`, `contact`, `physics_step_us`)
// override its parts. The physics step is checked against the firmware's control period when
// the task is built (RobotTask::check).
Status parse_robot(const nlohmann::json& doc, TaskConfig& c) {
  sim::WorldSpec spec = c.world;
  if (doc.contains("world")) {
    const auto& w = doc.at("world");
    spec = sim::WorldSpec{};  // the world replaces the one before
    if (w.is_object() && !w.contains("format")) {
      for (const sim::WorldOptionInfo& o : sim::world_option_table())
        if (set_per_trial(o) && w.contains(std::string(o.key)))
          return Status::error("world." + std::string(o.key) +
                               ": set per trial by the task (trial_seed, randomisation), not "
                               "in world");
      if (Status s = sim::read_world_spec(w, "world", spec); !s) return s;
      if (w.contains("engine")) {
        if (doc.contains("engine") || doc.contains("engines"))
          return Status::error(
              "world.engine: give the engine in world or at the top level, not both");
        c.engines = {spec.engine};
        spec.engine = sim::WorldSpec{}.engine;  // the run's engines are c.engines
      }
    } else if (w.is_object()) {
      sim::WorldFile file;
      if (Status s = sim::parse_world_file(w, file); !s)
        return Status::error("world: " + s.message());
      spec.base = file.base;
      spec.file = file;
    } else {
      const std::string text = w.is_string() ? w.get<std::string>() : std::string();
      const Status s = w.is_string() ? spec.set("base", text, "world") : Status::error("");
      if (!s && w.is_string() && sim::looks_like_world_file(text)) return s;  // names the file
      if (!s)
        return Status::error(
            "world: must be \"faithful\", \"seed\", a world file (.json), its object or an "
            "object of world options, got " +
            w.dump());
    }
  }
  if (doc.contains("urdf")) {
    const auto& u = doc.at("urdf");
    if (!u.is_string() || u.get<std::string>().empty())
      return Status::error("urdf: must be the path of a robot description (URDF)");
    if (Status s = spec.set("urdf", u.get<std::string>(), "urdf"); !s) return s;
  }
  // The world option table's fields at the top level (the flat form of before the table).
  for (const char* key : {"servo_law", "imu", "contact", "physics_step_us"})
    if (doc.contains(key))
      if (Status s = spec.set(key, option_text(doc.at(key)), key); !s) return s;
  // The trials' physics step: unless the config gives one, the faithful world's trials step at
  // the task's trial_physics_step_us() on its engines, the largest step at which its results
  // hold on all of them. The seed's world and a world file keep the table's default.
  const bool step_given =
      doc.contains("physics_step_us") || (doc.contains("world") && doc.at("world").is_object() &&
                                          doc.at("world").contains("physics_step_us"));
  c.trial_step_from_task = !step_given && spec.base == sim::WorldPreset::kFaithful && !spec.file &&
                           find_task_type(c.task) != nullptr;
  c.world = std::move(spec);
  apply_task_trial_step(c);
  if (doc.contains("params")) {
    nlohmann::json values = doc.at("params");
    if (values.is_string()) {
      const std::string file = values.get<std::string>();
      if (Status s = read_parameter_file(file, "params", values); !s) return s;
    }
    if (!values.is_object())
      return Status::error("params: must be a parameter file's path or an object {name: number}");
    c.base_params.clear();
    for (const auto& [name, value] : values.items()) {
      if (!value.is_number())
        return Status::error("params: " + name + " must be a number, got " + value.dump());
      c.base_params.emplace_back(name, value.get<double>());
    }
  }
  return {};
}

Status parse_engines(const nlohmann::json& doc, std::vector<sim::EngineKind>& out) {
  const auto parse = [](const nlohmann::json& v, const std::string& field, sim::EngineKind& kind) {
    sim::WorldSpec w;
    if (Status s = w.set("engine", option_text(v), field); !s) return s;
    kind = w.engine;
    return Status::ok();
  };
  if (doc.contains("engine") && doc.contains("engines"))
    return Status::error("engines: give either engine or engines, not both");
  if (doc.contains("engine")) {
    sim::EngineKind kind{};
    if (Status s = parse(doc.at("engine"), "engine", kind); !s) return s;
    out = {kind};
  }
  if (doc.contains("engines")) {
    const auto& list = doc.at("engines");
    if (!list.is_array() || list.empty())
      return Status::error("engines: must be a non-empty array of engine names");
    out.clear();
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string field = "engines[" + std::to_string(i) + "]";
      sim::EngineKind kind{};
      if (Status s = parse(list[i], field, kind); !s) return s;
      for (sim::EngineKind other : out)
        if (other == kind)
          return Status::error(field + ": '" + sim::to_string(kind) + "' appears twice");
      out.push_back(kind);
    }
  }
  return {};
}

}  // namespace

/// Config `starts`: a list of parameter files (read here), objects or "defaults"; a start
/// keeps the values of the config's genes only.
Status parse_starts(const nlohmann::json& doc, TaskConfig& c) {
  c.starts.clear();
  if (!doc.contains("starts")) return {};
  const nlohmann::json& list = doc.at("starts");
  if (!list.is_array()) return Status::error("starts: must be a list");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = "starts[" + std::to_string(i) + "]";
    nlohmann::json values = list[i];
    TaskConfig::Start start;
    if (values.is_string() && values.get<std::string>() == "defaults") {
      start.firmware_defaults = true;
      c.starts.push_back(std::move(start));
      continue;
    }
    if (values.is_string()) {
      const std::string file = values.get<std::string>();
      if (Status s = read_parameter_file(file, field, values); !s) return s;
    }
    if (!values.is_object())
      return Status::error(field +
                           ": must be a parameter file's path, an object {name: number} or "
                           "\"defaults\"");
    for (const auto& [name, value] : values.items()) {
      if (!value.is_number())
        return Status::error(field + "." + name + ": must be a number, got " + value.dump());
      for (const TaskGene& g : c.genes)
        if (g.parameter == name) start.values.emplace_back(name, value.get<double>());
    }
    c.starts.push_back(std::move(start));
  }
  if (c.starts.size() + 1 > static_cast<std::size_t>(c.settings.pop_size))
    return Status::error("starts: " + std::to_string(c.starts.size()) +
                         " starts and Ind_O do not fit a population of " +
                         std::to_string(c.settings.pop_size));
  return {};
}

namespace {

/// seed, pop, generations and the NSGA-II operators' settings.
Status parse_settings(const nlohmann::json& doc, TaskConfig& c) {
  std::int64_t v = 0;
  if (Status s = integer(doc, "seed", 0, INT64_MAX, v, true); !s) return s;
  c.settings.seed = static_cast<std::uint64_t>(v);
  if (Status s = integer(doc, "pop", 4, 1000000, v, true); !s) return s;
  c.settings.pop_size = static_cast<int>(v);
  if (Status s = integer(doc, "generations", 1, 1000000, v, true); !s) return s;
  c.settings.generations = static_cast<int>(v);
  if (Status s = number(doc, "pc", c.settings.real_cross_prob, true); !s) return s;
  if (Status s = number(doc, "pm", c.settings.real_mut_prob, true); !s) return s;
  if (Status s = number(doc, "etac", c.settings.eta_c, true); !s) return s;
  if (Status s = number(doc, "etam", c.settings.eta_m, true); !s) return s;
  if (Status s = number(doc, "seed_fraction", c.settings.seed_mutation_fraction, false); !s)
    return s;
  if (doc.contains("resample")) {
    if (!doc.at("resample").is_boolean())
      return Status::error("resample: must be true or false, got " + doc.at("resample").dump());
    c.settings.resample = doc.at("resample").get<bool>();
  }
  if (Status s = validate(c.settings); !s) return s;
  return {};
}

/// genes: the parameters the genome sets, each with its range and start.
Status parse_genes(const nlohmann::json& doc, TaskConfig& c) {
  if (!doc.contains("genes") || !doc.at("genes").is_array() || doc.at("genes").empty())
    return Status::error("genes: missing or not a non-empty array");
  const auto& genes = doc.at("genes");
  for (std::size_t i = 0; i < genes.size(); ++i) {
    const std::string prefix = "genes[" + std::to_string(i) + "].";
    const auto& g = genes[i];
    if (!g.is_object()) return Status::error("genes[" + std::to_string(i) + "]: must be an object");
    TaskGene gene;
    if (!g.contains("parameter") || !g.at("parameter").is_string())
      return Status::error(prefix + "parameter: missing or not a string");
    gene.parameter = g.at("parameter").get<std::string>();
    if (Status s = number(g, "min", gene.min, true, prefix); !s) return s;
    if (Status s = number(g, "max", gene.max, true, prefix); !s) return s;
    if (Status s = number(g, "start", gene.start, true, prefix); !s) return s;
    if (!(gene.min < gene.max)) return Status::error(prefix + "max: must be greater than min");
    if (gene.start < gene.min || gene.start > gene.max)
      return Status::error(prefix + "start: must lie within [min, max]");
    for (const auto& other : c.genes)
      if (other.parameter == gene.parameter)
        return Status::error(prefix + "parameter: '" + gene.parameter + "' appears twice");
    c.genes.push_back(gene);
  }
  return {};
}

/// The episode's length (the task's own settings: its type's).
Status parse_episode(const nlohmann::json& doc, TaskConfig& c) {
  if (Status s = number(doc, "duration_s", c.duration_s, false); !s) return s;
  if (!(c.duration_s > 0.0 && c.duration_s <= 600.0))
    return Status::error("duration_s: must be in (0, 600]");
  return {};
}

/// trials, aggregate, trial_seed and the randomisation of the trial worlds.
Status parse_trials(const nlohmann::json& doc, TaskConfig& c) {
  std::int64_t v = 0;
  if (Status s = integer(doc, "trials", 1, 1000, v, false); !s) return s;
  if (doc.contains("trials")) c.trials = static_cast<int>(v);
  if (doc.contains("aggregate")) {
    const auto& a = doc.at("aggregate");
    if (!a.is_string() || (a != "mean" && a != "worst"))
      return Status::error("aggregate: must be \"mean\" or \"worst\"");
    c.aggregate = a == "mean" ? Aggregate::kMean : Aggregate::kWorst;
  }
  if (Status s = integer(doc, "trial_seed", 0, INT64_MAX, v, false); !s) return s;
  if (doc.contains("trial_seed")) c.trial_seed = static_cast<std::uint64_t>(v);
  if (doc.contains("randomisation")) {
    const auto& r = doc.at("randomisation");
    if (!r.is_object()) return Status::error("randomisation: must be an object");
    if (r.contains("imu_noise")) {
      if (!r.at("imu_noise").is_boolean())
        return Status::error("randomisation.imu_noise: must be true or false");
      c.randomisation.imu_noise = r.at("imu_noise").get<bool>();
    }
    // The ranges are the world option table's randomisation rows (names, range, message).
    sim::WorldSpec ranges;
    ranges.randomise = c.randomisation;
    for (const sim::WorldOptionInfo& o : sim::world_option_table()) {
      const std::string name(o.key);
      if (!o.randomisation || !r.contains(name)) continue;
      if (!r.at(name).is_number())
        return Status::error("randomisation." + name + ": must be a number");
      if (Status s = ranges.set(o, option_text(r.at(name)), "randomisation." + name); !s) return s;
    }
    if (Status s = sim::check_servo_draws(ranges.randomise); !s)
      return Status::error("randomisation." + s.message());
    static_cast<sim::Randomisation&>(c.randomisation) = ranges.randomise;
  }
  return {};
}

/// validate: the seeds per world of the validation at the end of a run.
Status parse_validate(const nlohmann::json& doc, TaskConfig& c) {
  if (doc.contains("validate")) {
    const auto& val = doc.at("validate");
    if (!val.is_object()) return Status::error("validate: must be an object");
    for (const auto& [key, value] : val.items())
      if (key != "seeds") return Status::error("validate." + key + ": unknown field");
    if (val.contains("seeds")) {
      const auto& n = val.at("seeds");
      if (!n.is_number_integer() || n.get<std::int64_t>() < 1 || n.get<std::int64_t>() > 1000)
        return Status::error("validate.seeds: must be an integer in [1, 1000]");
      c.validate_seeds = n.get<int>();
    }
  }
  return {};
}

/// hypervolume_ideal and hypervolume_nadir: both or neither, ideal below nadir.
Status parse_hypervolume_box(const nlohmann::json& doc, TaskConfig& c) {
  if (Status s = vector_of(doc, "hypervolume_ideal", c.hv_ideal); !s) return s;
  if (Status s = vector_of(doc, "hypervolume_nadir", c.hv_nadir); !s) return s;
  if (c.hv_ideal.empty() != c.hv_nadir.empty())
    return Status::error("hypervolume_nadir: give both hypervolume_ideal and hypervolume_nadir");
  for (std::size_t i = 0; i < c.hv_ideal.size(); ++i)
    if (!(c.hv_ideal[i] < c.hv_nadir[i]))
      return Status::error("hypervolume_nadir[" + std::to_string(i) +
                           "]: must exceed hypervolume_ideal");
  return {};
}

}  // namespace

Status read_config_number(const nlohmann::json& doc, const std::string& field, double& out) {
  return number(doc, field, out, false);
}

std::int64_t task_trial_step_us(const TaskConfig& config) {
  const TaskType* type = find_task_type(config.task);
  if (type == nullptr) return kTrialPhysicsStepUs;
  std::int64_t step = 0;
  for (const sim::EngineKind engine : config.engines) {
    const std::int64_t allowed = type->descriptor().trial_physics_step_us(engine);
    step = step == 0 ? allowed : std::min(step, allowed);
  }
  return step > 0 ? step : type->descriptor().trial_physics_step_us(sim::EngineKind::kSimbody);
}

void apply_task_trial_step(TaskConfig& config) {
  if (config.trial_step_from_task) config.world.physics_step_us = task_trial_step_us(config);
}

Status parse_task_config(const nlohmann::json& doc, TaskConfig& out) {
  if (!doc.is_object()) return Status::error("config: must be a JSON object");
  const auto shared = [](const std::string& key) {
    for (const char* k : kKnownFields)
      if (key == k) return true;
    return false;
  };
  for (const auto& [key, value] : doc.items())
    if (!shared(key) && tasks_owning_field(key).empty())
      return Status::error(key + ": unknown field");
  TaskConfig c;
  if (!doc.contains("task") || !doc.at("task").is_string())
    return Status::error("task: missing or not a string");
  c.task = doc.at("task").get<std::string>();
  const TaskType* type = find_task_type(c.task);
  if (type == nullptr) return Status::error("task: '" + c.task + "' is not " + task_type_list());
  // Another task's own settings are an error (they would be ignored); a run's record of before
  // the tasks owned their settings is read by parse_task_record.
  for (const auto& [key, value] : doc.items())
    if (!shared(key) && !type->descriptor().owns_field(key))
      return Status::error("field '" + key + "' belongs to " + tasks_owning_field(key, c.task) +
                           ", not " + c.task);
  if (Status s = parse_settings(doc, c); !s) return s;
  if (Status s = parse_genes(doc, c); !s) return s;
  if (Status s = parse_starts(doc, c); !s) return s;
  if (Status s = parse_episode(doc, c); !s) return s;
  if (Status s = parse_trials(doc, c); !s) return s;
  if (Status s = parse_engines(doc, c.engines); !s) return s;
  if (Status s = parse_robot(doc, c); !s) return s;
  if (Status s = parse_validate(doc, c); !s) return s;
  if (Status s = parse_hypervolume_box(doc, c); !s) return s;
  if (Status s = type->parse_settings(doc, c, c.own); !s) return s;
  out = std::move(c);
  return {};
}

Status parse_task_record(const nlohmann::json& doc, TaskConfig& out) {
  const TaskType* type = doc.is_object() && doc.contains("task") && doc.at("task").is_string()
                             ? find_task_type(doc.at("task").get<std::string>())
                             : nullptr;
  if (type == nullptr) return parse_task_config(doc, out);  // the error names the field
  nlohmann::json own = doc;
  for (const auto& [key, value] : doc.items())
    if (!type->descriptor().owns_field(key) && !tasks_owning_field(key).empty()) own.erase(key);
  return parse_task_config(own, out);
}

}  // namespace stride::opt
