// Validation summaries: gate, gain kept, the flat table and its text (validation_summary.hpp).
#include "stride/optimiser/run/validation_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "stride/optimiser/run/direction_speeds.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::opt {

using nlohmann::json;

namespace {

json number_or_null(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

json world_json(const ValidationWorld& w, const std::string& unavailable) {
  json j = {{"name", w.name}, {"world", sim::to_json(w.world)}, {"seeds", w.seeds}};
  if (!unavailable.empty()) j["unavailable"] = unavailable;
  return j;
}

/// The interquartile range of `values` (quartiles by linear interpolation between the sorted
/// values; NaN if empty): the seeds' spread that a gain kept must exceed to be shown.
double interquartile_range(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  auto quantile = [&](double q) {
    const double pos = q * static_cast<double>(values.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (pos - static_cast<double>(lo)) * (values[hi] - values[lo]);
  };
  return quantile(0.75) - quantile(0.25);
}

/// The gate and medians of one individual in one world.
struct Cell {
  int seeds = 0, reached = 0, falls = 0;
  std::vector<double> medians;
  std::vector<double> spreads;  ///< per objective, the interquartile range over the seeds
  bool gate = false;
  double gate_median = 0.0, gate_limit = 0.0;
  std::string unavailable;
  json failures = json::array();
  ValidationFigures figures;  ///< the task's own, over the seeds (TaskType::validation_figures)
};

Cell summarise_cell(const TaskConfig& config, const ValidationIndividual& ind,
                    const ValidationWorld& world, const std::vector<EpisodeOutcome>& seeds) {
  Cell c;
  c.seeds = static_cast<int>(seeds.size());
  std::vector<std::vector<double>> values(2);
  std::vector<const EpisodeScore*> scores;
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    const EpisodeOutcome& e = seeds[s];
    if (!e.setup_error.empty()) {
      c.unavailable = e.setup_error;
      return c;
    }
    if (e.score.fell) ++c.falls;
    if (validation_reached(config, e.score)) ++c.reached;
    if (!e.score.world_failure.empty())
      c.failures.push_back({{"seed", world.seeds[s]}, {"reason", e.score.world_failure}});
    for (std::size_t m = 0; m < 2 && m < e.score.objectives.size(); ++m)
      values[m].push_back(e.score.objectives[m]);
    scores.push_back(&e.score);
  }
  if (const TaskType* type = find_task_type(config.task))
    c.figures = type->validation_figures(scores);
  for (auto& v : values) {
    c.medians.push_back(median(v));
    c.spreads.push_back(interquartile_range(v));
  }
  const int m = gate_objective(config);
  const double own = ind.run_objectives.size() > static_cast<std::size_t>(m)
                         ? ind.run_objectives[m]
                         : std::numeric_limits<double>::quiet_NaN();
  c.gate_median = c.medians[m];
  c.gate_limit = own + kGateMaxWorseFraction * std::abs(own);
  const int needed = static_cast<int>(std::ceil(kGateMinReachedFraction * c.seeds - 1e-9));
  c.gate = c.seeds > 0 && c.reached >= needed && c.gate_median <= c.gate_limit;
  return c;
}

std::string fixed(const json& v, int decimals) {
  if (!v.is_number()) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, v.get<double>());
  return text;
}

/// How the plain-language summary names a task's goal and its gate measure.
ValidationWords task_words(const std::string& task) {
  if (const TaskType* type = find_task_type(task)) return type->descriptor().words;
  return find_task_type("walk")->descriptor().words;
}

/// "on MuJoCo", "on fresh seeds", "with wider randomisation", "at half the physics step".
std::string world_phrase(const std::string& name) {
  if (name == "fresh seeds") return "on fresh seeds";
  if (name == "wider randomisation") return "with wider randomisation";
  if (name == "half step") return "at half the physics step";
  if (name.rfind("engine ", 0) == 0) {
    const std::string engine = name.substr(7);
    return engine == "mujoco" ? "on MuJoCo" : engine == "simbody" ? "on Simbody" : "on " + engine;
  }
  if (name.rfind("step ", 0) == 0) return "at a " + name.substr(5) + " physics step";
  if (name.rfind("ground ", 0) == 0) return "on the " + name.substr(7) + " ground";
  return "in " + name;
}

/// "a", "a and b", "a, b and c".
std::string join_and(const std::vector<std::string>& parts) {
  std::string text;
  for (std::size_t i = 0; i < parts.size(); ++i)
    text += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
  return text;
}

/// Why one cell fails its gate, in words: falls, misses, or a worse median than in the run.
std::string fail_reason(const ValidationWords& words, const json& cell, int seeds, int reached,
                        double min_reached, const json& own) {
  const int falls = cell.value("falls", 0);
  const int misses = std::max(0, seeds - reached - falls);
  const int needed = static_cast<int>(std::ceil(min_reached * seeds - 1e-9));
  const std::string of = " of " + std::to_string(seeds) + " seeds";
  if (seeds > 0 && reached >= needed) {
    const json median = cell.value("gate", json::object()).value("median", json());
    std::string text = words.reaches + " in " + std::to_string(reached) + of + " but ";
    if (median.is_number() && own.is_number() && std::abs(own.get<double>()) > 1e-12) {
      const double worse =
          100.0 * (median.get<double>() - own.get<double>()) / std::abs(own.get<double>());
      std::string phrase = words.worse;  // "{} % slower than in the run"
      phrase.replace(phrase.find("{}"), 2, fixed(json(worse), 0));
      return text + phrase;
    }
    return text + "worse than in the run";
  }
  if (falls > 0 && misses > 0)
    return words.falls + " in " + std::to_string(falls) + " and " + words.misses + " in " +
           std::to_string(misses) + of;
  if (falls > 0) return words.falls + " in " + std::to_string(falls) + of;
  if (misses > 0) return words.misses + " in " + std::to_string(misses) + of;
  return "no seed run";
}

}  // namespace

bool validation_reached(const TaskConfig& config, const EpisodeScore& score) {
  if (score.fell || !score.world_failure.empty()) return false;
  const TaskType* type = find_task_type(config.task);
  return type != nullptr && type->succeeded(config, score);
}

int gate_objective(const TaskConfig& config) {
  const TaskType* type = find_task_type(config.task);
  return type != nullptr ? type->descriptor().gate_objective : 0;
}

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

json summarise_validation(const std::filesystem::path& dir, const TaskConfig& config,
                          const std::vector<ValidationIndividual>& individuals,
                          const std::vector<ValidationWorld>& worlds,
                          const std::vector<std::vector<std::vector<EpisodeOutcome>>>& outcomes) {
  (void)dir;  // not recorded: the same run validated anywhere gives the same file
  std::vector<std::vector<Cell>> cells(individuals.size());
  for (std::size_t i = 0; i < individuals.size(); ++i)
    for (std::size_t w = 0; w < worlds.size(); ++w)
      cells[i].push_back(summarise_cell(config, individuals[i], worlds[w], outcomes[i][w]));
  json engines = json::array();
  for (sim::EngineKind e : config.engines) engines.push_back(sim::to_string(e));
  json worlds_json = json::array();
  for (std::size_t w = 0; w < worlds.size(); ++w)
    worlds_json.push_back(world_json(worlds[w], cells.empty() ? "" : cells[0][w].unavailable));
  json individuals_json = json::array(), table = json::array();
  bool all_passed = true;
  for (std::size_t i = 0; i < individuals.size(); ++i) {
    const ValidationIndividual& ind = individuals[i];
    json per_world = json::array();
    for (std::size_t w = 0; w < worlds.size(); ++w) {
      const Cell& c = cells[i][w];
      json row = {{"world", worlds[w].name}};
      json flat = {{"individual", ind.name}, {"world", worlds[w].name}};
      if (!c.unavailable.empty()) {
        row["unavailable"] = c.unavailable;
        flat["gate"] = "unavailable";
        per_world.push_back(row);
        table.push_back(flat);
        all_passed = false;
        continue;
      }
      json gain = nullptr, run_gains = nullptr, spreads = nullptr;
      const Cell& o = cells[0][w];
      if (i > 0 && o.gate) {
        gain = json::array();
        run_gains = json::array();
        spreads = json::array();
        for (std::size_t m = 0; m < 2; ++m) {
          const double run_gain = individuals[0].run_objectives[m] - ind.run_objectives[m];
          const double world_gain = o.medians[m] - c.medians[m];
          gain.push_back(std::abs(run_gain) > 1e-12 ? number_or_null(world_gain / run_gain)
                                                    : json(nullptr));
          run_gains.push_back(number_or_null(run_gain));
          spreads.push_back(number_or_null(std::max(o.spreads[m], c.spreads[m])));
        }
      }
      json medians = json::array();
      for (double v : c.medians) medians.push_back(number_or_null(v));
      row["seeds"] = c.seeds;
      row["reached"] = c.reached;
      row["reached_fraction"] = c.seeds > 0 ? static_cast<double>(c.reached) / c.seeds : 0.0;
      row["falls"] = c.falls;
      row["median_objectives"] = medians;
      row["gate"] = {{"passed", c.gate},
                     {"objective", gate_objective(config) + 1},
                     {"median", number_or_null(c.gate_median)},
                     {"limit", number_or_null(c.gate_limit)}};
      row["gain_kept"] = gain;
      json own_spreads = json::array();
      for (double v : c.spreads) own_spreads.push_back(number_or_null(v));
      row["seed_spread"] = own_spreads;
      row["failures"] = c.failures;
      flat["reached_fraction"] = row["reached_fraction"];
      flat["falls"] = c.falls;
      flat["median_f1"] = medians[0];
      flat["median_f2"] = medians[1];
      flat["gate"] = c.gate ? "pass" : "fail";
      flat["gain_kept_f1"] = gain.is_array() ? gain[0] : json(nullptr);
      flat["gain_kept_f2"] = gain.is_array() ? gain[1] : json(nullptr);
      if (gain.is_array()) {
        flat["run_gain_f1"] = run_gains[0];
        flat["run_gain_f2"] = run_gains[1];
        flat["seed_spread_f1"] = spreads[0];
        flat["seed_spread_f2"] = spreads[1];
      }
      row.update(c.figures.cell);
      flat.update(c.figures.table_row);
      all_passed = all_passed && c.gate;
      per_world.push_back(row);
      table.push_back(flat);
    }
    json run_objectives = json::array();
    for (double v : ind.run_objectives) run_objectives.push_back(number_or_null(v));
    individuals_json.push_back({{"name", ind.name},
                                {"file", ind.file},
                                {"run_objectives", run_objectives},
                                {"worlds", per_world}});
  }
  return {{"format", kValidationFormat},
          {"task", config.task},
          {"run_engines", engines},
          {"gate",
           {{"min_reached_fraction", kGateMinReachedFraction},
            {"max_worse_fraction", kGateMaxWorseFraction},
            {"objective", gate_objective(config) + 1}}},
          {"worlds", worlds_json},
          {"individuals", individuals_json},
          {"table", table},
          {"all_passed", all_passed}};
}

bool is_validation_file(const json& doc) {
  if (!doc.is_object()) return false;
  const std::string format = doc.value("format", "");
  return format == kValidationFormat || format == "stride-validation-1";
}

json validation_world_columns(const json& world) {
  if (!world.is_object()) return json::object();
  if (!world.contains("world")) return world;  // stride-validation-1: the figures in place
  json options = world["world"];
  sim::WorldSpec spec;
  // The robot does not change what the tables show, and its URDF may not be on this machine.
  if (options.is_object()) options.erase("urdf");
  if (!read_world_spec(options, "world.", spec)) return options;
  const sim::WorldOptions o = spec.to_options();
  json columns = {{"engine", sim::to_string(spec.engine)},
                  {"physics_step_us", spec.physics_step_us},
                  {"noise", spec.noise},
                  {"contact", sim::contact_kind_name(o.contact)},
                  {"friction_range", spec.randomise.friction_range},
                  {"mass_range", spec.randomise.mass_range},
                  {"strength_range", spec.randomise.strength_range},
                  {"latency_probability", spec.randomise.latency_probability},
                  {"contact_range", spec.randomise.contact_range}};
  if (spec.randomise.com_range > 0.0) columns["com_range"] = spec.randomise.com_range;
  // The servo and supply draws, where the world has them (issue 54).
  for (const char* key : {"servo_friction_min", "servo_friction_max", "servo_torque_min",
                          "servo_torque_max", "supply_min", "supply_max"})
    if (spec.is_set(key)) columns[key] = sim::find_world_option(key)->get(spec);
  return columns;
}

std::string validation_servo_draws_text(const json& columns) {
  if (!columns.contains("servo_friction_min") && !columns.contains("servo_friction_max") &&
      !columns.contains("servo_torque_min") && !columns.contains("servo_torque_max") &&
      !columns.contains("supply_min") && !columns.contains("supply_max"))
    return "";
  char text[160];
  std::snprintf(text, sizeof text, "servo friction x%.3g-%.3g, torque x%.3g-%.3g%s",
                columns.value("servo_friction_min", 1.0), columns.value("servo_friction_max", 1.0),
                columns.value("servo_torque_min", 1.0), columns.value("servo_torque_max", 1.0),
                columns.contains("supply_max") ? "" : ", the world's supply");
  std::string out = text;
  if (columns.contains("supply_max")) {
    std::snprintf(text, sizeof text, ", supply %.3g-%.3g V", columns.value("supply_min", 0.0),
                  columns.value("supply_max", 0.0));
    out += text;
  }
  return out;
}

std::string validation_text(const json& result) {
  std::ostringstream out;
  char line[512];
  const std::string task = result.value("task", "");
  const TaskType* type = find_task_type(task);
  out << "validation of a " << task << " run (objectives: "
      << (type != nullptr ? type->descriptor().legend : std::string("f1, f2"))
      << ")\nworlds (IMU noise on in all):\n";
  for (const json& world : result.value("worlds", json::array())) {
    const json w = validation_world_columns(world);
    const std::string servos = validation_servo_draws_text(w);
    std::snprintf(
        line, sizeof line,
        "  %-20s %-7s step %4lld us, %s, friction +-%.3g, mass +-%.3g, strength "
        "+-%.3g, latency p %.2g, ground +-%.2g, %zu seeds%s%s%s%s\n",
        world.value("name", "").c_str(), w.value("engine", "").c_str(),
        static_cast<long long>(w.value("physics_step_us", 0)), w.value("contact", "turf").c_str(),
        w.value("friction_range", 0.0), w.value("mass_range", 0.0), w.value("strength_range", 0.0),
        w.value("latency_probability", 0.0), w.value("contact_range", 0.0),
        world.value("seeds", json::array()).size(), servos.empty() ? "" : ", ", servos.c_str(),
        world.contains("unavailable") ? ": UNAVAILABLE, " : "",
        world.contains("unavailable") ? world["unavailable"].get<std::string>().c_str() : "");
    out << line;
  }
  std::snprintf(line, sizeof line, "%-26s %-20s %7s %5s %10s %10s %5s %8s %8s\n", "individual",
                "world", "reached", "falls", "median f1", "median f2", "gate", "kept f1",
                "kept f2");
  out << line;
  for (const json& r : result.value("table", json::array())) {
    const std::string gate = r.value("gate", "");
    std::snprintf(line, sizeof line, "%-26s %-20s %7s %5s %10s %10s %5s %8s %8s\n",
                  r.value("individual", "").c_str(), r.value("world", "").c_str(),
                  r.contains("reached_fraction")
                      ? (fixed(r["reached_fraction"].get<double>() * 100.0, 0) + "%").c_str()
                      : "-",
                  r.contains("falls") ? std::to_string(r["falls"].get<int>()).c_str() : "-",
                  fixed(r.value("median_f1", json()), 3).c_str(),
                  fixed(r.value("median_f2", json()), 3).c_str(), gate.c_str(),
                  gain_kept_text(r, 0).c_str(), gain_kept_text(r, 1).c_str());
    out << line;
  }
  if (type != nullptr && type->descriptor().measures_directions) {
    for (const json& w : result.value("worlds", json::array())) {
      std::vector<DirectionSpeeds> rows;
      for (const json& ind : result.value("individuals", json::array()))
        for (const json& cell : ind.value("worlds", json::array())) {
          if (cell.value("world", "") != w.value("name", "") || !cell.contains("speeds")) continue;
          DirectionSpeeds row;
          row.label = ind.value("name", "");
          for (int d = 0; d < kOmniSegments; ++d)
            row.speed[d] = cell["speeds"].value(to_string(static_cast<OmniDirection>(d)), 0.0);
          row.falls = cell.value("falls", 0);
          row.trials = cell.value("seeds", 0);
          rows.push_back(row);
        }
      if (rows.empty()) continue;
      rows.push_back(reference_direction_speeds());
      out << "\nspeeds per direction, world " << w.value("name", "") << " (mean over seeds)\n"
          << direction_table_text(rows);
    }
  }
  out << (result.value("all_passed", false)
              ? "every individual passes the gate in every world\n"
              : "not every individual passes the gate in every world\n")
      << validation_words(result);
  return out.str();
}

std::string two_significant_digits(const json& value) {
  if (!value.is_number()) return "-";
  const double v = value.get<double>();
  if (!std::isfinite(v)) return "-";
  if (v == 0.0) return "0";
  char text[64];
  // Round to two significant digits first, then print with the decimals the rounded value
  // needs (9.96 rounds to 10 and prints "10", not "10.0").
  int exponent = static_cast<int>(std::floor(std::log10(std::abs(v))));
  const double unit = std::pow(10.0, exponent - 1);
  const double rounded = std::round(v / unit) * unit;
  exponent = static_cast<int>(std::floor(std::log10(std::abs(rounded))));
  std::snprintf(text, sizeof text, "%.*f", std::max(0, 1 - exponent), rounded);
  return text;
}

std::string gain_kept_text(const json& row, int m) {
  const std::string suffix = "_f" + std::to_string(m + 1);
  const json gain = row.value("gain_kept" + suffix, json());
  if (!gain.is_number()) return "-";
  const json run_gain = row.value("run_gain" + suffix, json());
  const json spread = row.value("seed_spread" + suffix, json());
  if (row.contains("run_gain" + suffix) &&
      !(run_gain.is_number() && spread.is_number() &&
        std::abs(run_gain.get<double>()) > spread.get<double>()))
    return "-";  // the run's gain is within the seeds' spread: the ratio is of two noises
  return two_significant_digits(gain);
}

std::string validation_words(const json& result) {
  const ValidationWords words = task_words(result.value("task", ""));
  const json gate = result.value("gate", json::object());
  const double min_reached = gate.value("min_reached_fraction", kGateMinReachedFraction);
  const double max_worse = gate.value("max_worse_fraction", kGateMaxWorseFraction);
  std::ostringstream out;
  out << "in words:\n";
  std::string best_name, best_file;
  int best_held = 0, best_falls = 0, worlds_count = 0;
  for (const json& ind : result.value("individuals", json::array())) {
    const std::string name = ind.value("name", "");
    const json own = ind.value("run_objectives", json::array());
    std::vector<std::string> held, failed, untested;
    int held_reached = 0, held_seeds = 0, falls = 0;
    for (const json& cell : ind.value("worlds", json::array())) {
      const std::string where = world_phrase(cell.value("world", ""));
      if (cell.contains("unavailable")) {
        untested.push_back(where + " (" + cell["unavailable"].get<std::string>() + ")");
        continue;
      }
      const int seeds = cell.value("seeds", 0), reached = cell.value("reached", 0);
      falls += cell.value("falls", 0);
      const json cell_gate = cell.value("gate", json::object());
      if (cell_gate.value("passed", false)) {
        held.push_back(where);
        held_reached += reached;
        held_seeds += seeds;
        continue;
      }
      const int objective = cell_gate.value("objective", 1) - 1;
      failed.push_back(
          where + " (" +
          fail_reason(words, cell, seeds, reached, min_reached,
                      objective >= 0 && static_cast<std::size_t>(objective) < own.size()
                          ? own[static_cast<std::size_t>(objective)]
                          : json()) +
          ")");
    }
    std::string line = "  " + name + ": ";
    const std::size_t tested = held.size() + failed.size();
    if (!held.empty()) {
      line += held.size() == tested ? std::string("holds in every world tested")
                                    : "holds " + join_and(held);
      line += " (" + words.reaches + " in " + std::to_string(held_reached) + " of " +
              std::to_string(held_seeds) + " seeds)";
    }
    if (!failed.empty()) line += (held.empty() ? "fails " : "; fails ") + join_and(failed);
    if (tested == 0) line += "not tested";
    if (!untested.empty()) line += "; not tested " + join_and(untested);
    out << line << "\n";
    worlds_count = std::max(worlds_count, static_cast<int>(tested));
    const int held_count = static_cast<int>(held.size());
    if (name != "Ind_O" && (held_count > best_held ||
                            (held_count == best_held && held_count > 0 && falls < best_falls))) {
      best_name = name;
      best_file = ind.value("file", "");
      best_held = held_count;
      best_falls = falls;
    }
  }
  // toolchain/demo.sh reads the front file from the end of this line (pinned by
  // validation_summary_test.cpp).
  if (best_held > 0)
    out << "  the pick that holds in most worlds: " << best_name << " (" << best_held << " of "
        << worlds_count << " worlds), " << best_file << "\n";
  else
    out << "  no pick holds in any world\n";
  char legend[768];
  std::snprintf(legend, sizeof legend,
                "pass (holds): at least %.0f %% of the seeds %s%s, and the median %s "
                "is at most %.0f %% worse than the individual's own value in the run.\n"
                "fail: not so in that world: the %s does not carry over to it (for a pick: "
                "what the run tuned does not hold there). A finding about the %s in that "
                "world, not an error of the program.\n",
                100.0 * min_reached, words.reach.c_str(), words.without_fall.c_str(),
                words.measure.c_str(), 100.0 * max_worse, words.motion.c_str(),
                words.motion.c_str());
  out << legend;
  return out.str();
}

}  // namespace stride::opt
