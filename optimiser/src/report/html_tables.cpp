// The tables of report.html: settings, Ind_O against the picks, validation, Table E.
#include "stride/optimiser/report/html_tables.hpp"
#include "stride/core/json_file.hpp"
#include "stride/optimiser/tasks/task_type.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "stride/optimiser/report/html_page.hpp"
#include "stride/optimiser/run/validation.hpp"

namespace stride::opt::report {

using nlohmann::json;

namespace {

std::string cell(const std::string& text, const char* cls = nullptr) {
  return std::string("<td") + (cls ? std::string(" class=\"") + cls + "\"" : "") + ">" +
         html_escape(text) + "</td>";
}

std::string scalar_text(const json& v) {
  if (v.is_number()) return format_number(v.get<double>(), 5);
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_null()) return "-";
  return v.dump();
}

bool is_scalar(const json& v) {
  return v.is_primitive();
}

// Rows of the tolerant validation reader: objects with a number among their values.
void collect_rows(const json& node, const std::string& path,
                  std::vector<std::pair<std::string, const json*>>& rows) {
  if (rows.size() >= 500) return;
  if (node.is_object()) {
    bool has_number = false;
    for (const auto& [k, v] : node.items()) has_number = has_number || v.is_number();
    if (has_number) rows.emplace_back(path, &node);
    for (const auto& [k, v] : node.items())
      if (v.is_structured()) collect_rows(v, path.empty() ? k : path + " / " + k, rows);
  } else if (node.is_array()) {
    std::size_t i = 0;
    for (const auto& v : node) {
      std::string label = std::to_string(i++);
      // Name an array element by its "name"/"pick"/"world" fields when it has them.
      if (v.is_object())
        for (const char* key : {"name", "pick", "individual", "world", "engine"})
          if (v.contains(key) && v[key].is_string()) label = v[key].get<std::string>();
      if (v.is_structured()) collect_rows(v, path.empty() ? label : path + " / " + label, rows);
    }
  }
}

}  // namespace

std::string settings_table_html(const RunData& data) {
  const json& run = data.run;
  const json settings =
      run.contains("settings") && run["settings"].is_object() ? run["settings"] : json::object();
  const json task = run.contains("task") && run["task"].is_object() ? run["task"] : json::object();
  std::vector<std::pair<std::string, std::string>> rows = {
      {"task", data.task.empty() ? "-" : data.task},
      {"Stride version",
       run.contains("stride_version") ? scalar_text(run["stride_version"]) : "-"}};
  for (const char* k : {"seed", "popSize", "generations", "realCrossProb", "realMutProb", "etaC",
                        "etaM", "seedMutationFraction"})
    if (settings.contains(k)) rows.emplace_back(k, scalar_text(settings[k]));
  // The shared episode settings and the run's own task's settings only (an older run.json holds
  // every task's).
  std::vector<std::string> keys = {"duration_s"};
  if (const TaskType* type = find_task_type(data.task))
    for (std::string_view k : type->descriptor().settings_fields) keys.emplace_back(k);
  for (const char* k : {"trials", "aggregate", "trial_seed"}) keys.emplace_back(k);
  for (const std::string& k : keys)
    if (task.contains(k)) rows.emplace_back(k, scalar_text(task[k]));
  if (task.contains("genes") && task["genes"].is_array())
    rows.emplace_back("genes", std::to_string(task["genes"].size()));
  rows.emplace_back("evaluations logged", std::to_string(data.evaluations.size()));
  rows.emplace_back("generations logged", std::to_string(data.generations.size()));
  rows.emplace_back("final front members", std::to_string(data.front.size()));
  std::string html = "<table id=\"settings-table\">";
  for (const auto& [k, v] : rows)
    html += "<tr><th class=\"name\">" + html_escape(k) + "</th>" + cell(v, "name") + "</tr>";
  return html + "</table>\n";
}

std::string picks_table_html(const RunData& data, const std::vector<PickRow>& rows) {
  const ObjectiveNames names = objective_names(data);
  if (rows.empty())
    return missing_note("Neither Ind_O nor a front member is in this run directory.");
  std::string html = "<table id=\"picks-table\"><tr><th class=\"name\">individual</th><th>" +
                     html_escape(names.f1) + "</th><th>change</th><th>" + html_escape(names.f2) +
                     "</th><th>change</th>";
  const TaskType* type = find_task_type(data.task);
  const bool ball = type != nullptr && type->descriptor().uses_ball;
  if (ball) html += "<th>ball distance [m]</th>";
  html += "<th class=\"name\">re-run for the replay</th><th class=\"name\">front file</th></tr>\n";
  const std::vector<double>* o = nullptr;
  if (rows[0].name == "Ind_O" && rows[0].objectives.size() >= 2) o = &rows[0].objectives;
  for (const PickRow& r : rows) {
    html += "<tr><td class=\"name\"><span class=\"swatch\" style=\"background:" + r.colour +
            "\"></span>" + html_escape(r.name) + "</td>";
    for (std::size_t m = 0; m < 2; ++m) {
      if (r.objectives.size() < 2) {
        html += cell("-") + cell("");
        continue;
      }
      html += cell(format_number(r.objectives[m], 5));
      const std::string c = o ? percent_change(r.objectives[m], (*o)[m]) : "";
      const double d = o ? r.objectives[m] - (*o)[m] : 0.0;
      const char* cls = c.empty() || d == 0.0 ? nullptr : d < 0 ? "better" : "worse";
      html += cell(&r == &rows[0] ? "" : c, cls);
    }
    if (ball)
      html += cell(r.objectives.size() >= 2 && r.objectives[1] > 0 && r.objectives[1] < 999
                       ? format_number(1.0 / r.objectives[1], 4)
                       : "-");
    std::string rerun = r.outcome;
    if (r.rerun && r.rerun->size() >= 2)
      rerun = format_number((*r.rerun)[0], 5) + " / " + format_number((*r.rerun)[1], 5) +
              (r.rerun == std::optional(r.objectives) ? " (same as logged)" : " (differs)") + "; " +
              r.outcome;
    html +=
        cell(rerun, "name") + cell(r.file.empty() ? "start genome" : r.file, "name") + "</tr>\n";
  }
  return html + "</table>\n";
}

// validation.json as `stride validate` writes it: the worlds, then one row per individual and
// world (gate passed or failed marked), the walk-omni speeds as extra columns.
static std::string stride_validation_html(const json& doc) {
  std::string html =
      "<table id=\"validation-worlds\"><tr><th class=\"name\">world</th>"
      "<th>engine</th><th>step [us]</th><th>ground</th><th>friction +-</th><th>mass +-</th>"
      "<th>strength +-</th><th>latency p</th><th>ground +-</th><th>seeds</th>"
      "<th class=\"name\">note</th></tr>\n";
  for (const json& world : doc["worlds"]) {
    if (!world.is_object()) continue;
    const json w = validation_world_columns(world);
    html += "<tr>" + cell(world.value("name", ""), "name") + cell(w.value("engine", ""));
    for (const char* k : {"physics_step_us", "contact", "friction_range", "mass_range",
                          "strength_range", "latency_probability", "contact_range"})
      html += cell(w.contains(k) ? scalar_text(w[k]) : "-");
    html += cell(std::to_string(world.value("seeds", json::array()).size())) +
            cell(world.contains("unavailable") ? "unavailable: " + scalar_text(world["unavailable"])
                                               : validation_servo_draws_text(w),
                 "name") +
            "</tr>\n";
  }
  html += "</table>\n";
  // The table's own order first (JSON objects come back sorted by key), then any other column.
  std::vector<std::string> columns = {"individual", "world",        "reached_fraction",
                                      "falls",      "median_f1",    "median_f2",
                                      "gate",       "gain_kept_f1", "gain_kept_f2"};
  // The run's gain and the seeds' spread decide whether a gain kept is shown (gain_kept_text);
  // they stay in validation.json, not as columns.
  const std::vector<std::string> hidden = {"run_gain_f1", "run_gain_f2", "seed_spread_f1",
                                           "seed_spread_f2"};
  for (const json& r : doc["table"])
    if (r.is_object())
      for (const auto& [k, v] : r.items())
        if (is_scalar(v) && std::find(columns.begin(), columns.end(), k) == columns.end() &&
            std::find(hidden.begin(), hidden.end(), k) == hidden.end())
          columns.push_back(k);
  html += "<table id=\"validation-table\"><tr>";
  for (const auto& c : columns) html += "<th>" + html_escape(c) + "</th>";
  html += "</tr>\n";
  for (const json& r : doc["table"]) {
    if (!r.is_object()) continue;
    html += "<tr>";
    for (const auto& c : columns) {
      const std::string text = c == "gain_kept_f1"   ? gain_kept_text(r, 0)
                               : c == "gain_kept_f2" ? gain_kept_text(r, 1)
                               : r.contains(c)       ? scalar_text(r[c])
                                                     : "";
      const char* cls = c == "individual" || c == "world" ? "name"
                        : c != "gate"                     ? nullptr
                        : text == "pass"                  ? "better"
                                                          : "worse";
      html += cell(text, cls);
    }
    html += "</tr>\n";
  }
  return html +
         "</table>\n<p class=\"note\">Gate: at least 80 % of the seeds reach the goal "
         "without a fall and the median of the task's measure is within 25 % of the "
         "individual's own value in the run. Gain kept = (Ind_O's median - the pick's) "
         "in the world / the same in the run, shown to two significant digits only where Ind_O "
         "passes the gate and the run's gain exceeds the seeds' spread (the larger interquartile "
         "range of Ind_O's and the pick's values over the world's seeds); otherwise \"-\".</p>\n";
}

std::string validation_table_html(const std::filesystem::path& file) {
  json doc;
  core::JsonFileError why = core::JsonFileError::kNone;
  if (!core::read_json_file(file, doc, &why)) {
    if (why == core::JsonFileError::kCannotOpen) return "";
    return missing_note(file.filename().string() +
                        " exists but cannot be parsed (not valid JSON).");
  }
  if (is_validation_file(doc) && doc.contains("worlds") && doc["worlds"].is_array() &&
      doc.contains("table") && doc["table"].is_array())
    return stride_validation_html(doc);
  std::vector<std::pair<std::string, const json*>> rows;
  collect_rows(doc, "", rows);
  if (rows.empty())
    return missing_note(file.filename().string() + " has no rows with numbers to show.");
  std::vector<std::string> columns;
  for (const auto& [path, obj] : rows)
    for (const auto& [k, v] : obj->items())
      if (is_scalar(v) && std::find(columns.begin(), columns.end(), k) == columns.end())
        columns.push_back(k);
  std::string html = "<table id=\"validation-table\"><tr><th class=\"name\">row</th>";
  for (const auto& c : columns) html += "<th>" + html_escape(c) + "</th>";
  html += "</tr>\n";
  for (const auto& [path, obj] : rows) {
    html += "<tr>" + cell(path.empty() ? "(top level)" : path, "name");
    for (const auto& c : columns)
      html += cell(obj->contains(c) && is_scalar((*obj)[c]) ? scalar_text((*obj)[c]) : "");
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

std::string parameter_table_html(const RunData& data, const std::vector<RunPick>& picks,
                                 std::size_t top) {
  const json& run = data.run;
  if (!run.contains("task") || !run["task"].is_object() || !run["task"].contains("genes") ||
      !run["task"]["genes"].is_array())
    return missing_note("run.json has no gene list (task.genes).");
  const json& genes = run["task"]["genes"];
  if (picks.empty()) return missing_note("No front member to compare with Ind_O.");
  struct Row {
    std::string name;
    double start, lo, hi, moved;
    std::vector<double> values;
  };
  std::vector<Row> table;
  for (std::size_t g = 0; g < genes.size(); ++g) {
    const json& gene = genes[g];
    Row r{gene.value("parameter", "gene " + std::to_string(g)),
          gene.value("start", 0.0),
          gene.value("min", 0.0),
          gene.value("max", 0.0),
          0.0,
          {}};
    const double range = r.hi > r.lo ? r.hi - r.lo : 1.0;
    for (const RunPick& p : picks) {
      const double v = g < p.genes.size() ? p.genes[g] : std::nan("");
      r.values.push_back(v);
      if (std::isfinite(v)) r.moved = std::max(r.moved, std::abs(v - r.start) / range);
    }
    table.push_back(std::move(r));
  }
  std::stable_sort(table.begin(), table.end(),
                   [](const Row& a, const Row& b) { return a.moved > b.moved; });
  auto render = [&](std::size_t count, const char* id) {
    std::string html = std::string("<table id=\"") + id +
                       "\"><tr><th class=\"name\">parameter</th><th>range</th><th>Ind_O</th>";
    for (std::size_t i = 0; i < picks.size(); ++i)
      html += "<th>" + html_escape(picks[i].label) + "</th><th>change</th>";
    html += "</tr>\n";
    for (std::size_t k = 0; k < count && k < table.size(); ++k) {
      const Row& r = table[k];
      const double range = r.hi > r.lo ? r.hi - r.lo : 1.0;
      html += "<tr>" + cell(r.name, "name") +
              cell(format_number(r.lo, 4) + " .. " + format_number(r.hi, 4)) +
              cell(format_number(r.start, 5));
      for (double v : r.values) {
        char change[32];
        std::snprintf(change, sizeof change, "%+.1f %%", 100.0 * (v - r.start) / range);
        html += cell(format_number(v, 5)) + cell(std::isfinite(v) ? change : "-");
      }
      html += "</tr>\n";
    }
    return html + "</table>\n";
  };
  return "<p class=\"note\">Change in % of the gene's range (max - min), largest first.</p>\n" +
         render(top, "parameter-table") + "<details><summary>All " + std::to_string(table.size()) +
         " genes</summary>\n" + render(table.size(), "all-genes") + "</details>\n";
}

}  // namespace stride::opt::report
