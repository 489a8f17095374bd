// A task config read from its file (a relative robot description, world or parameter file is
// relative to the config) and written back as JSON (the task record in a run's run.json; the
// task's own settings by its type).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "stride/core/json_file.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/sim_hal/world_file.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::opt {

Status load_task_config(const std::filesystem::path& path, TaskConfig& out) {
  nlohmann::json doc;
  if (Status s = core::read_json_file(path, doc); !s) return s;
  // A relative robot description or parameter file is relative to the config file.
  const auto relative_to_config = [&path](nlohmann::json& object, const char* key) {
    if (!object.is_object() || !object.contains(key) || !object.at(key).is_string()) return;
    const std::string text = object.at(key).get<std::string>();
    if ((std::string(key) == "world" || std::string(key) == "base") &&
        !sim::looks_like_world_file(text))
      return;  // a named world
    const std::filesystem::path file = text;
    if (file.is_relative() && !file.empty())
      object[key] =
          (std::filesystem::absolute(path).parent_path() / file).lexically_normal().string();
  };
  for (const char* key : {"urdf", "params", "world"}) relative_to_config(doc, key);
  if (doc.is_object() && doc.contains("starts") && doc.at("starts").is_array()) {
    for (nlohmann::json& entry : doc["starts"]) {
      if (!entry.is_string() || entry.get<std::string>() == "defaults") continue;
      const std::filesystem::path file = entry.get<std::string>();
      if (file.is_relative() && !file.empty())
        entry = (std::filesystem::absolute(path).parent_path() / file).lexically_normal().string();
    }
  }
  if (doc.is_object() && doc.contains("world"))
    for (const char* key : {"urdf", "base"}) relative_to_config(doc["world"], key);
  if (Status s = parse_task_config(doc, out); !s)
    return Status::error(path.string() + ": " + s.message());
  return {};
}

namespace {

/// The trials' randomisation through the world option table's randomisation rows. The ranges
/// a run's record has always held are written always; a later one (com_range,
/// latency_probability) only when set, so that the record of a run from before it stays equal.
nlohmann::json randomisation_json(const TrialRandomisation& r) {
  nlohmann::json j = {{"imu_noise", r.imu_noise}};
  sim::WorldSpec ranges;
  ranges.randomise = r;
  for (const sim::WorldOptionInfo& o : sim::world_option_table()) {
    if (!o.randomisation) continue;
    const bool always = o.key == "friction_range" || o.key == "mass_range" ||
                        o.key == "strength_range" || o.key == "contact_range";
    if (always || ranges.is_set(o.key)) j[std::string(o.key)] = o.get(ranges);
  }
  return j;
}

}  // namespace

nlohmann::json to_json(const TaskConfig& c) {
  nlohmann::json genes = nlohmann::json::array();
  for (const auto& g : c.genes)
    genes.push_back(
        {{"parameter", g.parameter}, {"min", g.min}, {"max", g.max}, {"start", g.start}});
  nlohmann::json j = {{"task", c.task},
                      {"seed", c.settings.seed},
                      {"pop", c.settings.pop_size},
                      {"generations", c.settings.generations},
                      {"pc", c.settings.real_cross_prob},
                      {"pm", c.settings.real_mut_prob},
                      {"etac", c.settings.eta_c},
                      {"etam", c.settings.eta_m},
                      {"seed_fraction", c.settings.seed_mutation_fraction},
                      {"genes", genes},
                      {"duration_s", c.duration_s},
                      {"trials", c.trials},
                      {"aggregate", c.aggregate == Aggregate::kMean ? "mean" : "worst"},
                      {"trial_seed", c.trial_seed},
                      {"randomisation", randomisation_json(c.randomisation)}};
  nlohmann::json engines = nlohmann::json::array();
  for (sim::EngineKind e : c.engines) engines.push_back(sim::to_string(e));
  j["engines"] = engines;
  j["validate"] = {{"seeds", c.validate_seeds}};
  if (!c.base_params.empty()) {
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [name, value] : c.base_params) params[name] = value;
    j["params"] = params;  // the values, so that run.json stands alone
  }
  // Written only when set, so that the run.json of a run from before them stays equal.
  if (c.settings.resample) j["resample"] = true;
  if (!c.starts.empty()) {
    nlohmann::json starts = nlohmann::json::array();
    for (const TaskConfig::Start& s : c.starts) {
      if (s.firmware_defaults) {
        starts.push_back("defaults");
        continue;
      }
      nlohmann::json values = nlohmann::json::object();
      for (const auto& [name, value] : s.values) values[name] = value;
      starts.push_back(values);
    }
    j["starts"] = starts;
  }
  j["world"] = sim::to_json(c.world);  // a world file by value, as the params
  // The task's own settings, and no other task's (written by its type).
  if (const TaskType* type = find_task_type(c.task)) type->write_settings(c, j);
  if (!c.hv_ideal.empty()) {
    j["hypervolume_ideal"] = c.hv_ideal;
    j["hypervolume_nadir"] = c.hv_nadir;
  }
  return j;
}

}  // namespace stride::opt
