// Run reports: front/ parameter files, SVG plots and the summary of a robot run directory.
#include "stride/optimiser/run/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "stride/firmware/atomic_file.hpp"

namespace stride::opt {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

Status read_json_file(const fs::path& path, json& out) {
  std::ifstream in(path);
  if (!in) return Status::error(path.string() + ": cannot open");
  out = json::parse(in, nullptr, false);
  if (out.is_discarded()) return Status::error(path.string() + ": not valid JSON");
  return {};
}

Status read_jsonl(const fs::path& path, std::vector<json>& out) {
  std::ifstream in(path);
  if (!in) return Status::error(path.string() + ": cannot open");
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty()) continue;
    json j = json::parse(line, nullptr, false);
    if (j.is_discarded())
      return Status::error(path.string() + ": line " + std::to_string(n) + " is not valid JSON");
    out.push_back(std::move(j));
  }
  return {};
}

bool feasible(const json& e) {
  return !e.value("failed", false) && e.contains("violation") && e["violation"].is_number() &&
         e["violation"].get<double>() <= 0.0 && e.contains("objectives");
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

/// A small SVG line/scatter chart.
class Chart {
 public:
  Chart(std::string title, std::string x_label, std::string y_label, double x0, double x1,
        double y0, double y1)
      : x0_(x0), x1_(x1 > x0 ? x1 : x0 + 1), y0_(y0), y1_(y1 > y0 ? y1 : y0 + 1) {
    svg_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"480\" "
            "font-family=\"sans-serif\" font-size=\"12\">\n"
         << "<rect width=\"720\" height=\"480\" fill=\"white\"/>\n"
         << "<text x=\"360\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" << title
         << "</text>\n"
         << "<text x=\"360\" y=\"470\" text-anchor=\"middle\">" << x_label << "</text>\n"
         << "<text x=\"16\" y=\"240\" text-anchor=\"middle\" transform=\"rotate(-90 16 240)\">"
         << y_label << "</text>\n"
         << "<rect x=\"70\" y=\"40\" width=\"620\" height=\"380\" fill=\"none\" "
            "stroke=\"black\"/>\n";
    for (int i = 0; i <= 5; ++i) {
      const double fx = x0_ + (x1_ - x0_) * i / 5.0, fy = y0_ + (y1_ - y0_) * i / 5.0;
      svg_ << "<text x=\"" << px(fx) << "\" y=\"436\" text-anchor=\"middle\">" << fmt(fx)
           << "</text>\n"
           << "<text x=\"64\" y=\"" << py(fy) + 4 << "\" text-anchor=\"end\">" << fmt(fy)
           << "</text>\n"
           << "<line x1=\"70\" x2=\"690\" y1=\"" << py(fy) << "\" y2=\"" << py(fy)
           << "\" stroke=\"#ddd\"/>\n";
    }
  }
  double px(double x) const { return 70.0 + 620.0 * (x - x0_) / (x1_ - x0_); }
  double py(double y) const { return 420.0 - 380.0 * (y - y0_) / (y1_ - y0_); }
  void polyline(const std::vector<std::vector<double>>& pts, const std::string& colour,
                bool markers) {
    svg_ << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
    for (const auto& p : pts) svg_ << px(p[0]) << "," << py(p[1]) << " ";
    svg_ << "\"/>\n";
    if (markers)
      for (const auto& p : pts)
        svg_ << "<circle cx=\"" << px(p[0]) << "\" cy=\"" << py(p[1]) << "\" r=\"3\" fill=\""
             << colour << "\"/>\n";
  }
  void marker(double x, double y, const std::string& label) {
    svg_ << "<rect x=\"" << px(x) - 5 << "\" y=\"" << py(y) - 5
         << "\" width=\"10\" height=\"10\" fill=\"none\" stroke=\"black\" stroke-width=\"2\"/>\n"
         << "<text x=\"" << px(x) + 8 << "\" y=\"" << py(y) - 8 << "\">" << label << "</text>\n";
  }
  void legend(int row, const std::string& colour, const std::string& text) {
    const int y = 56 + 16 * row;
    svg_ << "<line x1=\"560\" x2=\"580\" y1=\"" << y << "\" y2=\"" << y << "\" stroke=\"" << colour
         << "\" stroke-width=\"3\"/>\n"
         << "<text x=\"586\" y=\"" << y + 4 << "\">" << text << "</text>\n";
  }
  std::string str() { return svg_.str() + "</svg>\n"; }

 private:
  double x0_, x1_, y0_, y1_;
  std::ostringstream svg_;
};

std::string colour_for(double t) {  // blue (early) to red (late)
  char buf[16];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(40 + 200 * t), 60,
                static_cast<int>(220 - 180 * t));
  return buf;
}

std::vector<double> start_reals(const json& run) {
  if (run.contains("start") && run["start"].is_object() && run["start"].contains("reals"))
    return run["start"]["reals"].get<std::vector<double>>();
  return {};
}

const json* find_ind_o(const std::vector<json>& evaluations, const std::vector<double>& start) {
  for (const auto& e : evaluations)
    if (e.value("generation", 0) == 1 && e.contains("reals") &&
        e["reals"].get<std::vector<double>>() == start)
      return &e;
  return nullptr;
}

}  // namespace

std::vector<std::vector<double>> non_dominated(std::vector<std::vector<double>> points) {
  std::sort(points.begin(), points.end());
  std::vector<std::vector<double>> front;
  double best_f2 = std::numeric_limits<double>::infinity();
  for (const auto& p : points) {
    if (p[1] < best_f2) {
      if (!front.empty() && front.back()[0] == p[0]) front.pop_back();
      front.push_back(p);
      best_f2 = p[1];
    }
  }
  return front;
}

std::size_t knee_index(const std::vector<std::vector<double>>& front) {
  if (front.empty()) return 0;
  std::vector<double> lo(front[0].size(), std::numeric_limits<double>::infinity());
  std::vector<double> hi(front[0].size(), -std::numeric_limits<double>::infinity());
  for (const auto& p : front)
    for (std::size_t m = 0; m < p.size(); ++m)
      lo[m] = std::min(lo[m], p[m]), hi[m] = std::max(hi[m], p[m]);
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < front.size(); ++i) {
    double d = 0.0;
    for (std::size_t m = 0; m < front[i].size(); ++m) {
      const double range = hi[m] - lo[m];
      const double z = range > 0 ? (front[i][m] - lo[m]) / range : 0.0;
      d += z * z;
    }
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

Status read_pareto_csv(const fs::path& path, int objectives, std::vector<FrontMember>& out) {
  std::ifstream in(path);
  if (!in) return Status::error(path.string() + ": cannot open");
  std::string line;
  out.clear();
  if (!std::getline(in, line)) return Status::error(path.string() + ": empty");
  std::size_t row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    std::stringstream cells(line);
    std::string cell;
    FrontMember m;
    int column = 0;
    while (std::getline(cells, cell, ',')) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0')
        return Status::error(path.string() + ": row " + std::to_string(row) +
                             " has a non-number '" + cell + "'");
      (column < objectives ? m.objectives : m.genes).push_back(v);
      ++column;
    }
    out.push_back(std::move(m));
  }
  return {};
}

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
    if (Status s = fw::write_file_atomically(front / name, task.parameter_file(g).dump(2) + "\n");
        !s)
      return s;
  }
  return {};
}

Status write_plots(const fs::path& dir) {
  json run;
  if (Status s = read_json_file(dir / "run.json", run); !s) return s;
  std::vector<json> evaluations, generations;
  if (Status s = read_jsonl(dir / "evaluations.jsonl", evaluations); !s) return s;
  if (Status s = read_jsonl(dir / "generations.jsonl", generations); !s) return s;
  const std::string task = run.value("problem", std::string("run"));
  const bool kick = task == "kick";
  const std::string f1 = kick                  ? "max field-plane sway [m/s^2]"
                         : task == "walk-omni" ? "-(v_f + v_b + 2 v_side + 0.2 w_turn)"
                                               : "time to 2.5 m [s]";
  const std::string f2 = kick ? "1 / ball distance [1/m]" : "max |a| [m/s^2]";

  // Pareto front (feasible, cumulative) after selected generations.
  int last_generation = 0;
  for (const auto& e : evaluations)
    last_generation = std::max(last_generation, e.value("generation", 0));
  std::vector<int> shown;
  const int count = std::min(last_generation, 6);
  for (int k = 0; k < count; ++k) {
    const int g = count == 1 ? last_generation : 1 + (last_generation - 1) * k / (count - 1);
    if (shown.empty() || shown.back() != g) shown.push_back(g);
  }
  // With no feasible evaluation yet (e.g. every walk fell), the plot shows the best infeasible
  // ones instead and says so in its title.
  bool any_feasible = false;
  for (const auto& e : evaluations) any_feasible = any_feasible || feasible(e);
  auto usable = [&](const json& e) {
    if (any_feasible) return feasible(e);
    return !e.value("failed", false) && e.contains("objectives") && e["objectives"].size() == 2 &&
           e["objectives"][0].get<double>() < 1e29;
  };
  std::vector<std::vector<std::vector<double>>> fronts;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (int g : shown) {
    std::vector<std::vector<double>> pts;
    for (const auto& e : evaluations)
      if (e.value("generation", 0) <= g && usable(e))
        pts.push_back(e["objectives"].get<std::vector<double>>());
    fronts.push_back(non_dominated(pts));
    for (const auto& p : fronts.back())
      x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]),
      y1 = std::max(y1, p[1]);
  }
  const json* ind_o = find_ind_o(evaluations, start_reals(run));
  std::vector<double> o;
  if (ind_o != nullptr) {
    o = (*ind_o)["objectives"].get<std::vector<double>>();
    if (o.size() >= 2 && o[0] < 1e29)
      x0 = std::min(x0, o[0]), x1 = std::max(x1, o[0]), y0 = std::min(y0, o[1]),
      y1 = std::max(y1, o[1]);
  }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  const double mx = 0.05 * (x1 - x0 + 1e-9), my = 0.05 * (y1 - y0 + 1e-9);
  Chart front_chart(
      "Pareto front by generation (" + task + ")" +
          (any_feasible ? std::string() : std::string(", no feasible member yet: all fell")),
      f1, f2, x0 - mx, x1 + mx, y0 - my, y1 + my);
  for (std::size_t i = 0; i < fronts.size(); ++i) {
    const std::string c = colour_for(
        fronts.size() > 1 ? static_cast<double>(i) / static_cast<double>(fronts.size() - 1) : 1.0);
    front_chart.polyline(fronts[i], c, true);
    front_chart.legend(static_cast<int>(i), c, "generation " + std::to_string(shown[i]));
  }
  if (o.size() >= 2 && o[0] < 1e29) front_chart.marker(o[0], o[1], "Ind_O");
  if (Status s = fw::write_file_atomically(dir / "pareto_by_generation.svg", front_chart.str()); !s)
    return s;

  // Hypervolume against evaluations.
  std::vector<std::vector<double>> hv;
  for (const auto& g : generations)
    if (g.contains("hypervolume") && g["hypervolume"].is_number())
      hv.push_back({g.value("evaluations", 0.0), g["hypervolume"].get<double>()});
  double hx = 1, hy = 1e-9;
  for (const auto& p : hv) hx = std::max(hx, p[0]), hy = std::max(hy, p[1]);
  Chart hv_chart("Hypervolume (" + task + ")", "evaluations", "hypervolume (normalised)", 0, hx, 0,
                 hy * 1.1);
  hv_chart.polyline(hv, "#c03030", true);
  return fw::write_file_atomically(dir / "hypervolume.svg", hv_chart.str());
}

RunPickNames run_pick_names(const std::string& task) {
  if (task == "kick") return {"least_sway", "longest_kick"};
  if (task == "walk" || task == "walk-omni") return {"fastest", "most_stable"};
  return {"best_obj1", "best_obj2"};
}

Status summarise_run(const fs::path& dir, json& out) {
  json run;
  if (Status s = read_json_file(dir / "run.json", run); !s) return s;
  const std::string task = run.value("problem", std::string());
  std::vector<json> evaluations;
  if (Status s = read_jsonl(dir / "evaluations.jsonl", evaluations); !s) return s;
  std::vector<FrontMember> members;
  if (Status s = read_pareto_csv(dir / "pareto.csv", 2, members); !s) return s;
  out = json::object();
  out["task"] = task;
  out["evaluations"] = evaluations.size();
  out["front_size"] = members.size();
  const json* ind_o = find_ind_o(evaluations, start_reals(run));
  if (ind_o != nullptr)
    out["ind_o"] = {{"objectives", (*ind_o)["objectives"]}, {"violation", (*ind_o)["violation"]}};
  else
    out["ind_o"] = nullptr;
  if (members.empty()) return {};
  std::vector<std::vector<double>> objs;
  for (const auto& m : members) objs.push_back(m.objectives);
  auto pick = [&](std::size_t i) {
    char name[32];
    std::snprintf(name, sizeof name, "front/%03zu.json", i);
    return json{{"objectives", objs[i]}, {"file", name}};
  };
  std::size_t best1 = 0, best2 = 0;
  for (std::size_t i = 0; i < objs.size(); ++i) {
    if (objs[i][0] < objs[best1][0]) best1 = i;
    if (objs[i][1] < objs[best2][1]) best2 = i;
  }
  const RunPickNames names = run_pick_names(task);
  out[names.best_obj1] = pick(best1);
  out[names.best_obj2] = pick(best2);
  out["knee"] = pick(knee_index(objs));
  return {};
}

}  // namespace stride::opt
