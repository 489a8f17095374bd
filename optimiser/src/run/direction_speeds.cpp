// Per-direction speed table of the omnidirectional walk (see direction_speeds.hpp).
#include "stride/optimiser/run/direction_speeds.hpp"

#include <cstdio>
#include <limits>
#include <sstream>

#include "stride/optimiser/run/run_report.hpp"
#include "stride/optimiser/tasks/direction_figures.hpp"

namespace stride::opt {

namespace fs = std::filesystem;
using nlohmann::json;

DirectionSpeeds reference_direction_speeds() {
  DirectionSpeeds r;
  r.label = "Bit-Bots NUgus (sim)";
  r.speed = kReferenceSpeeds;
  return r;
}

Status measure_direction_speeds(const RobotTask& task, const Genome& genome,
                                const std::string& label, DirectionSpeeds& out) {
  if (task.type() == nullptr || !task.type()->descriptor().measures_directions)
    return Status::error("per-direction speeds need a task that walks every direction, not '" +
                         task.config().task + "'");
  DirectionSpeeds row;
  row.label = label;
  const int trials = task.config().world_count();
  for (int k = 0; k < trials; ++k) {
    EpisodeScore score;
    if (Status s = task.run_trial(genome, k, score); !s)
      return Status::error(label + ", trial " + std::to_string(k) + ": " + s.message());
    const OmniSegments segments = task.type()->direction_segments(score);
    for (int d = 0; d < kOmniSegments; ++d) row.speed[d] += segments[d].speed / trials;
    if (score.fell) ++row.falls;
  }
  row.trials = trials;
  out = std::move(row);
  return {};
}

DirectionSpeeds best_per_direction(const std::vector<DirectionSpeeds>& rows,
                                   const std::string& label) {
  DirectionSpeeds best;
  best.label = label;
  for (int d = 0; d < kOmniSegments; ++d) {
    double top = -std::numeric_limits<double>::infinity();
    for (const auto& r : rows) {
      if (r.speed[d] > top) {
        top = r.speed[d];
        best.source[d] = r.file.empty() ? r.label : r.file;
      }
    }
    best.speed[d] = rows.empty() ? 0.0 : top;
  }
  return best;
}

std::string direction_table_text(const std::vector<DirectionSpeeds>& rows) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-22s %8s %8s %8s %8s %9s %9s  %s\n", "speeds", "fwd m/s",
                "back m/s", "left m/s", "right m/s", "turnL r/s", "turnR r/s", "falls");
  out << line;
  for (const auto& r : rows) {
    std::snprintf(
        line, sizeof line, "%-22s %8.3f %8.3f %8.3f %8.3f %9.3f %9.3f  %s\n", r.label.c_str(),
        r.speed[0], r.speed[1], r.speed[2], r.speed[3], r.speed[4], r.speed[5],
        r.trials > 0 ? (std::to_string(r.falls) + "/" + std::to_string(r.trials)).c_str() : "-");
    out << line;
    bool any_source = false;
    for (const auto& s : r.source) any_source = any_source || !s.empty();
    if (any_source) {
      out << "  (from";
      for (int d = 0; d < kOmniSegments; ++d)
        out << ' ' << to_string(static_cast<OmniDirection>(d)) << ' ' << r.source[d]
            << (d + 1 < kOmniSegments ? "," : ")\n");
    }
  }
  return out.str();
}

json direction_table_json(const std::vector<DirectionSpeeds>& rows) {
  json table = json::array();
  for (const auto& r : rows) {
    json speeds = json::object();
    json source = json::object();
    bool any_source = false;
    for (int d = 0; d < kOmniSegments; ++d) {
      const char* name = to_string(static_cast<OmniDirection>(d));
      speeds[name] = r.speed[d];
      if (!r.source[d].empty()) {
        source[name] = r.source[d];
        any_source = true;
      }
    }
    json row = {{"label", r.label}, {"speeds", speeds}};
    if (!r.file.empty()) row["file"] = r.file;
    if (r.trials > 0) {
      row["falls"] = r.falls;
      row["trials"] = r.trials;
    }
    if (any_source) row["source"] = source;
    table.push_back(row);
  }
  return table;
}

Status run_direction_table(const fs::path& dir, const RobotTask& task, const json& summary,
                           std::vector<DirectionSpeeds>& rows) {
  rows.clear();
  std::vector<FrontMember> members;
  if (Status s = read_pareto_csv(dir / "pareto.csv", 2, members); !s) return s;
  DirectionSpeeds ind_o;
  if (Status s = measure_direction_speeds(task, task.start_genome(), "Ind_O", ind_o); !s) return s;
  rows.push_back(ind_o);
  // Every front member (front/NNN.json is row NNN of pareto.csv).
  std::vector<DirectionSpeeds> front;
  for (std::size_t i = 0; i < members.size(); ++i) {
    char file[32];
    std::snprintf(file, sizeof file, "front/%03zu.json", i);
    Genome g;
    g.reals = members[i].genes;
    DirectionSpeeds row;
    if (Status s = measure_direction_speeds(task, g, file, row); !s) return s;
    row.file = file;
    front.push_back(row);
  }
  const RunPickNames names = run_pick_names(task.config().task);
  for (const char* key : {names.best_obj1, names.best_obj2, "knee"}) {
    if (!summary.contains(key) || !summary[key].contains("file")) continue;
    const std::string file = summary[key]["file"].get<std::string>();
    for (const auto& row : front) {
      if (row.file != file) continue;
      DirectionSpeeds pick = row;
      pick.label = key;
      for (char& c : pick.label)
        if (c == '_') c = ' ';
      rows.push_back(pick);
    }
  }
  if (!front.empty()) rows.push_back(best_per_direction(front, "best per direction"));
  rows.push_back(reference_direction_speeds());
  return {};
}

}  // namespace stride::opt
