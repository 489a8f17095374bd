// Run reports: front/ parameter files, SVG plots and the summary of a robot run directory.
#include "stride/optimiser/run/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "stride/core/atomic_file.hpp"
#include "stride/optimiser/report/run_data.hpp"

namespace stride::opt {

namespace fs = std::filesystem;
using nlohmann::json;

Status write_front_files(const fs::path& dir, const RobotTask& task) {
  std::vector<FrontMember> members;
  if (Status s = read_pareto_csv(dir / "pareto.csv", task.shape().objectives, members); !s)
    return s;
  const fs::path front = dir / "front";
  std::error_code ec;
  fs::remove_all(front, ec);
  fs::create_directories(front, ec);
  if (ec) return Status::error(front.string() + ": " + ec.message());
  for (std::size_t i = 0; i < members.size(); ++i) {
    Genome g;
    g.reals = members[i].genes;
    char name[32];
    std::snprintf(name, sizeof name, "%03zu.json", i);
    if (Status s = core::write_file_atomically(front / name, task.parameter_file(g).dump(2) + "\n");
        !s)
      return s;
  }
  return {};
}

Status summarise_run(const fs::path& dir, json& out) {
  report::RunData data;
  if (Status s = report::load_run_data(dir, data); !s) return s;
  out = json::object();
  out["task"] = data.task;
  out["evaluations"] = data.evaluations.size();
  out["front_size"] = data.front.size();
  out["generations"] = data.generations_done;
  out["generations_planned"] = data.generations_planned;
  const json* ind_o = report::find_ind_o(data);
  if (ind_o != nullptr)
    out["ind_o"] = {{"objectives", (*ind_o)["objectives"]},
                    {"violation", ind_o->value("violation", 0.0)}};
  else
    out["ind_o"] = nullptr;
  for (const report::RunPick& p : report::run_picks(data))
    for (const std::string& key : p.keys)
      out[key] = {{"objectives", p.objectives}, {"file", p.file}};
  out["warnings"] = data.warnings;
  return {};
}

}  // namespace stride::opt
