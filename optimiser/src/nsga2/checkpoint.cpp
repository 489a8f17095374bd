// Nsga2 checkpoint() / restore(): the engine state as JSON with exact doubles.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "stride/optimiser/nsga2/nsga2.hpp"

namespace stride::opt {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "stride-nsga2-checkpoint";
constexpr int kFormatVersion = 1;

json exact_array(const std::vector<double>& values) {
  json out = json::array();
  for (const double v : values) out.push_back(exact_double(v));
  return out;
}

Status parse_array(const json& j, const char* what, std::vector<double>& out) {
  if (!j.is_array()) return Status::error(std::string("checkpoint: ") + what + " is not an array");
  out.clear();
  for (const json& item : j) {
    double v = 0;
    if (!parse_exact_double(item, v)) {
      return Status::error(std::string("checkpoint: ") + what + " holds a malformed number");
    }
    out.push_back(v);
  }
  return {};
}

json genome_json(const Individual& ind) {
  return json{{"id", ind.id},
              {"reals", exact_array(ind.genome.reals)},
              {"bits", bits_to_text(ind.genome.bits)}};
}

Status parse_genome(const json& j, const ProblemShape& shape, Individual& ind) {
  if (!j.is_object() || !j.contains("id") || !j["id"].is_number_unsigned() ||
      !j.contains("reals") || !j.contains("bits") || !j["bits"].is_string()) {
    return Status::error("checkpoint: an individual lacks id, reals or bits");
  }
  ind.id = j["id"].get<std::uint64_t>();
  if (auto st = parse_array(j["reals"], "reals", ind.genome.reals); !st) return st;
  if (!bits_from_text(j["bits"].get<std::string>(), ind.genome.bits)) {
    return Status::error("checkpoint: bits of individual " + std::to_string(ind.id) +
                         " are not 0/1 text");
  }
  if (ind.genome.reals.size() != shape.reals.size() ||
      ind.genome.bits.size() != static_cast<std::size_t>(shape.total_bits())) {
    return Status::error("checkpoint: individual " + std::to_string(ind.id) +
                         " does not fit the problem's genes");
  }
  return {};
}

json settings_json(const Nsga2Settings& s) {
  json j{{"seed", s.seed},
         {"pop_size", s.pop_size},
         {"generations", s.generations},
         {"real_cross_prob", exact_double(s.real_cross_prob)},
         {"real_mut_prob", exact_double(s.real_mut_prob)},
         {"eta_c", exact_double(s.eta_c)},
         {"eta_m", exact_double(s.eta_m)},
         {"bin_cross_prob", exact_double(s.bin_cross_prob)},
         {"bin_mut_prob", exact_double(s.bin_mut_prob)},
         {"seed_mutation_fraction", exact_double(s.seed_mutation_fraction)}};
  if (s.resample) j["resample"] = true;  // written only when on: older checkpoints stay equal
  return j;
}

Status parse_settings(const json& j, Nsga2Settings& s) {
  try {
    s.seed = j.at("seed").get<std::uint64_t>();
    s.pop_size = j.at("pop_size").get<int>();
    s.generations = j.at("generations").get<int>();
    const std::pair<const char*, double*> reals[] = {
        {"real_cross_prob", &s.real_cross_prob},
        {"real_mut_prob", &s.real_mut_prob},
        {"eta_c", &s.eta_c},
        {"eta_m", &s.eta_m},
        {"bin_cross_prob", &s.bin_cross_prob},
        {"bin_mut_prob", &s.bin_mut_prob},
        {"seed_mutation_fraction", &s.seed_mutation_fraction}};
    for (const auto& [name, target] : reals) {
      if (!parse_exact_double(j.at(name), *target)) {
        return Status::error(std::string("checkpoint: settings.") + name + " is malformed");
      }
    }
    s.resample = j.value("resample", false);
  } catch (const json::exception& e) {
    return Status::error(std::string("checkpoint: settings are malformed: ") + e.what());
  }
  return validate(s);
}

}  // namespace

std::string exact_double(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", value);
  return text;
}

bool parse_exact_double(const json& text, double& value) {
  if (text.is_number()) {
    value = text.get<double>();
    return true;
  }
  if (!text.is_string()) return false;
  const std::string& s = text.get_ref<const std::string&>();
  if (s.empty()) return false;
  char* end = nullptr;
  value = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

namespace {

/// One member of a checkpoint's population: its genome, its exact results, rank and crowding
/// (json::exception for a missing field, which the caller words).
Status parse_member(const json& j, const ProblemShape& shape, Individual& ind) {
  if (auto st = parse_genome(j, shape, ind); !st) return st;
  if (auto st = parse_array(j.at("objectives"), "objectives", ind.result.objectives); !st) {
    return st;
  }
  if (auto st = parse_array(j.at("constraints"), "constraints", ind.result.constraints); !st) {
    return st;
  }
  if (!parse_exact_double(j.at("violation"), ind.result.violation) ||
      !parse_exact_double(j.at("crowding"), ind.crowding)) {
    return Status::error("checkpoint: violation or crowding is malformed");
  }
  if (ind.result.objectives.size() != static_cast<std::size_t>(shape.objectives) ||
      ind.result.constraints.size() != static_cast<std::size_t>(shape.constraints)) {
    return Status::error("checkpoint: an individual has the wrong number of results");
  }
  ind.result.failed = j.at("failed").get<bool>();
  ind.result.reason = j.at("reason").get<std::string>();
  ind.from_cache = j.at("from_cache").get<bool>();
  ind.rank = j.at("rank").get<int>();
  ind.evaluated = true;
  return {};
}

}  // namespace

json Nsga2::checkpoint() const {
  json population = json::array();
  for (const Individual& ind : population_) {
    json j = genome_json(ind);
    j["objectives"] = exact_array(ind.result.objectives);
    j["constraints"] = exact_array(ind.result.constraints);
    j["violation"] = exact_double(ind.result.violation);
    j["failed"] = ind.result.failed;
    j["reason"] = ind.result.reason;
    j["from_cache"] = ind.from_cache;
    j["rank"] = ind.rank;
    j["crowding"] = exact_double(ind.crowding);
    population.push_back(std::move(j));
  }
  json batch = json::array();
  for (const Individual& ind : batch_) batch.push_back(genome_json(ind));
  return json{{"format", kFormat},
              {"format_version", kFormatVersion},
              {"settings", settings_json(settings_)},
              {"shape",
               {{"reals", shape_.reals.size()},
                {"bits", shape_.total_bits()},
                {"objectives", shape_.objectives},
                {"constraints", shape_.constraints}}},
              {"completed_generations", completed_},
              {"next_id", next_id_},
              {"counters",
               {{"evaluations", counters_.evaluations},
                {"failures", counters_.failures},
                {"cache_hits", counters_.cache_hits}}},
              {"rng", rng_.state()},
              {"population", std::move(population)},
              {"batch", std::move(batch)}};
}

Status Nsga2::restore(const json& cp, const ProblemShape& shape,
                      const std::vector<std::pair<Genome, Result>>& known,
                      std::unique_ptr<Nsga2>& out) {
  if (!cp.is_object() || cp.value("format", std::string()) != kFormat ||
      cp.value("format_version", 0) != kFormatVersion) {
    return Status::error("checkpoint: not a " + std::string(kFormat) + " version " +
                         std::to_string(kFormatVersion));
  }
  if (auto st = validate(shape); !st) return st;
  Nsga2Settings settings;
  if (!cp.contains("settings")) return Status::error("checkpoint: settings missing");
  if (auto st = parse_settings(cp["settings"], settings); !st) return st;
  std::unique_ptr<Nsga2> engine(new Nsga2(settings, shape));
  try {
    const json& sh = cp.at("shape");
    if (sh.at("reals").get<std::size_t>() != shape.reals.size() ||
        sh.at("bits").get<int>() != shape.total_bits() ||
        sh.at("objectives").get<int>() != shape.objectives ||
        sh.at("constraints").get<int>() != shape.constraints) {
      return Status::error("checkpoint: written for a problem of another shape");
    }
    engine->completed_ = cp.at("completed_generations").get<int>();
    engine->next_id_ = cp.at("next_id").get<std::uint64_t>();
    const json& c = cp.at("counters");
    engine->counters_.evaluations = c.at("evaluations").get<std::uint64_t>();
    engine->counters_.failures = c.at("failures").get<std::uint64_t>();
    engine->counters_.cache_hits = c.at("cache_hits").get<std::uint64_t>();
    if (auto st = engine->rng_.restore(cp.at("rng").get<std::string>()); !st) {
      return Status::error("checkpoint: " + st.message());
    }
    for (const json& j : cp.at("population")) {
      Individual ind;
      if (auto st = parse_member(j, shape, ind); !st) return st;
      engine->population_.push_back(std::move(ind));
    }
    for (const json& j : cp.at("batch")) {
      Individual ind;
      if (auto st = parse_genome(j, shape, ind); !st) return st;
      engine->batch_.push_back(std::move(ind));
    }
  } catch (const json::exception& e) {
    return Status::error(std::string("checkpoint: malformed: ") + e.what());
  }
  const auto n = static_cast<std::size_t>(settings.pop_size);
  const bool initial = engine->completed_ == 0;
  // A resampling run's batch holds the parents again after the children (nsga2.hpp).
  const std::size_t batch = engine->finished() ? 0 : settings.resample && !initial ? 2 * n : n;
  if (engine->completed_ < 0 || engine->completed_ > settings.generations ||
      engine->population_.size() != (initial ? 0 : n) || engine->batch_.size() != batch) {
    return Status::error("checkpoint: population or batch size does not match its settings");
  }
  for (std::size_t i = 1; i < engine->batch_.size(); ++i) {
    if (engine->batch_[i].id != engine->batch_[0].id + i) {
      return Status::error("checkpoint: batch ids are not consecutive");
    }
  }
  // The cache of a resampling run holds the current draw only, and nothing of the batch after
  // a checkpoint has been evaluated yet.
  if (!settings.resample) {
    for (const auto& [genome, result] : known)
      engine->cache_.insert_or_assign(HashedGenome{GenomeBitsHash{}(genome), genome}, result);
  }
  engine->resolve_batch();
  out = std::move(engine);
  return {};
}

}  // namespace stride::opt
