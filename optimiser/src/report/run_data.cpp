// RunData: tolerant reading of a robot run directory for reports.
#include "stride/optimiser/report/run_data.hpp"
#include "stride/core/json_file.hpp"
#include "stride/optimiser/tasks/task_type.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace stride::opt::report {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void read_log(const fs::path& path, std::vector<json>& out, std::vector<std::string>& warnings) {
  core::JsonLinesDamage damage;
  if (!core::read_json_lines(path, out, &damage)) {
    warnings.push_back(path.filename().string() + " is missing");
    return;
  }
  if (damage.damaged > 0)
    warnings.push_back(path.filename().string() + ": " + std::to_string(damage.damaged) +
                       " damaged line(s) skipped, the first is line " +
                       std::to_string(damage.first_line) + " (a truncated log?)");
  if (out.empty() && damage.damaged == 0)
    warnings.push_back(path.filename().string() + " is empty");
}

}  // namespace

std::string front_file_name(std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "front/%03zu.json", index);
  return name;
}

std::string run_progress_text(std::size_t done, std::size_t planned) {
  if (planned > done)
    return "generation " + std::to_string(done) + " of " + std::to_string(planned) +
           " (unfinished)";
  return std::to_string(done) + " generations";
}

/// front-rescored.json into the front's rows (nothing if absent; a warning if it does not fit).
void read_rescored(const fs::path& path, std::vector<FrontMember>& front,
                   std::vector<std::string>& warnings) {
  if (!fs::exists(path)) return;
  json doc;
  const bool parsed = core::read_json_file(path, doc).is_ok();
  const auto fail = [&](const std::string& why) {
    for (FrontMember& m : front) m.rescored.clear();
    warnings.push_back(path.string() + ": " + why + "; the picks use the run's scores");
  };
  if (!parsed || !doc.contains("members") || !doc["members"].is_array())
    return fail("not a rescored front");
  const json& members = doc["members"];
  if (members.size() != front.size()) return fail("its rows do not match pareto.csv");
  for (std::size_t i = 0; i < members.size(); ++i) {
    const json& m = members[i];
    std::vector<double> objectives = objectives_of(m);
    if (objectives.size() != front[i].objectives.size() || !m.contains("run_objectives") ||
        m["run_objectives"] != json(front[i].objectives))
      return fail("row " + std::to_string(i) + " does not match pareto.csv");
    front[i].rescored = std::move(objectives);
    front[i].rescored_feasible = feasible(m);
  }
}

Status load_run_data(const fs::path& dir, RunData& out) {
  out = RunData{};
  out.dir = dir;
  if (Status s = core::read_json_file(dir / "run.json", out.run); !s) return s;
  if (!out.run.is_object())
    return Status::error((dir / "run.json").string() + ": not a JSON object");
  if (out.run.contains("problem") && out.run["problem"].is_string())
    out.task = out.run["problem"].get<std::string>();
  read_log(dir / "evaluations.jsonl", out.evaluations, out.warnings);
  read_log(dir / "generations.jsonl", out.generations, out.warnings);
  if (!fs::exists(dir / "pareto.csv")) {
    out.warnings.push_back("pareto.csv is missing: no front members to show");
  } else if (Status s = read_pareto_csv(dir / "pareto.csv", 2, out.front); !s) {
    out.front.clear();
    out.warnings.push_back(s.message());
  }
  read_rescored(dir / "front-rescored.json", out.front, out.warnings);
  for (const json& g : out.generations)
    if (g.contains("generation") && g["generation"].is_number_unsigned())
      out.generations_done = std::max(out.generations_done, g["generation"].get<std::size_t>());
  const auto settings = out.run.find("settings");
  if (settings != out.run.end() && settings->is_object() && settings->contains("generations") &&
      (*settings)["generations"].is_number_unsigned())
    out.generations_planned = (*settings)["generations"].get<std::size_t>();
  if (out.unfinished())
    out.warnings.push_back("unfinished: generation " + std::to_string(out.generations_done) +
                           " of " + std::to_string(out.generations_planned) +
                           " (stride optimise --out " + dir.string() + " --resume continues it)");
  std::vector<std::size_t> missing;
  for (std::size_t i = 0; i < out.front.size(); ++i)
    if (!fs::exists(dir / front_file_name(i))) missing.push_back(i);
  const bool one_range = !missing.empty() && missing.back() - missing.front() + 1 == missing.size();
  if (one_range && missing.size() > 1)  // an unfinished run has no front/ yet: one line
    out.warnings.push_back(front_file_name(missing.front()) + " to " +
                           front_file_name(missing.back()) + " are missing (pareto.csv rows " +
                           std::to_string(missing.front()) + " to " +
                           std::to_string(missing.back()) + ")");
  else
    for (const std::size_t i : missing)
      out.warnings.push_back(front_file_name(i) + " is missing (pareto.csv row " +
                             std::to_string(i) + ")");
  return {};
}

std::vector<double> objectives_of(const json& e) {
  std::vector<double> out;
  if (!e.contains("objectives") || !e["objectives"].is_array()) return out;
  for (const json& v : e["objectives"]) {
    if (!v.is_number()) return {};
    out.push_back(v.get<double>());
  }
  return out;
}

bool feasible(const json& e) {
  return !e.value("failed", false) && e.contains("violation") && e["violation"].is_number() &&
         e["violation"].get<double>() <= 0.0 && objectives_of(e).size() >= 2;
}

std::vector<double> start_genes(const RunData& data) {
  const json& run = data.run;
  if (run.contains("start") && run["start"].is_object() && run["start"].contains("reals") &&
      run["start"]["reals"].is_array()) {
    std::vector<double> out;
    for (const json& v : run["start"]["reals"])
      if (v.is_number()) out.push_back(v.get<double>());
    return out;
  }
  return {};
}

const json* find_ind_o(const RunData& data) {
  const std::vector<double> start = start_genes(data);
  if (start.empty()) return nullptr;
  for (const auto& e : data.evaluations)
    if (e.value("generation", 0) == 1 && e.contains("reals") && e["reals"].is_array() &&
        e["reals"] == json(start) && objectives_of(e).size() >= 2)
      return &e;
  return nullptr;
}

namespace {

/// The pareto.csv rows the picks are chosen from, and the scores they are chosen by: every row
/// by the run's scores, or for a rescored run the rows feasible and non-dominated on the fresh
/// worlds, by those (all rows by the run's scores if none is feasible there).
void pick_candidates(const RunData& data, std::vector<std::size_t>& rows,
                     std::vector<std::vector<double>>& scores) {
  rows.clear();
  scores.clear();
  for (std::size_t i = 0; i < data.front.size(); ++i)
    if (!data.front[i].rescored.empty() && data.front[i].rescored_feasible) rows.push_back(i);
  if (rows.empty()) {
    for (std::size_t i = 0; i < data.front.size(); ++i) {
      rows.push_back(i);
      scores.push_back(data.front[i].objectives);
    }
    return;
  }
  const auto dominates = [](const std::vector<double>& a, const std::vector<double>& b) {
    bool better = false;
    for (std::size_t m = 0; m < a.size(); ++m) {
      if (a[m] > b[m]) return false;
      better = better || a[m] < b[m];
    }
    return better;
  };
  std::vector<std::size_t> kept;
  for (const std::size_t i : rows) {
    bool dominated = false;
    for (const std::size_t j : rows)
      dominated = dominated || dominates(data.front[j].rescored, data.front[i].rescored);
    if (!dominated) kept.push_back(i);
  }
  rows = kept;
  for (const std::size_t i : rows) scores.push_back(data.front[i].rescored);
}

}  // namespace

std::vector<RunPick> run_picks(const RunData& data) {
  std::vector<RunPick> picks;
  if (data.front.empty()) return picks;
  std::vector<std::size_t> rows;
  std::vector<std::vector<double>> objs;
  pick_candidates(data, rows, objs);
  std::size_t best1 = 0, best2 = 0;
  for (std::size_t i = 0; i < objs.size(); ++i) {
    if (objs[i].size() < 2) return picks;
    if (objs[i][0] < objs[best1][0]) best1 = i;
    if (objs[i][1] < objs[best2][1]) best2 = i;
  }
  const RunPickNames names = run_pick_names(data.task);
  const std::pair<std::string, std::size_t> chosen[] = {{names.best_obj1, rows[best1]},
                                                        {names.best_obj2, rows[best2]},
                                                        {"knee", rows[knee_index(objs)]}};
  for (const auto& [key, index] : chosen) {
    std::string label = key;
    for (char& c : label)
      if (c == '_') c = ' ';
    RunPick* same = nullptr;
    for (RunPick& p : picks)
      if (p.front_index == index) same = &p;
    if (same != nullptr) {
      same->keys.push_back(key);
      same->label += ", " + label;
      continue;
    }
    picks.push_back({{key},
                     label,
                     index,
                     front_file_name(index),
                     data.front[index].objectives,
                     data.front[index].genes,
                     data.front[index].rescored});
  }
  return picks;
}

}  // namespace stride::opt::report

namespace stride::opt::report {

ObjectiveNames objective_names(const RunData& data) {
  if (const TaskType* type = find_task_type(data.task)) {
    const ObjectiveLabels labels = type->objective_labels(
        data.run.is_object() && data.run.contains("task") ? data.run["task"]
                                                          : nlohmann::json::object());
    return {labels.f1, labels.f2};
  }
  return {"f1", "f2"};
}

}  // namespace stride::opt::report
