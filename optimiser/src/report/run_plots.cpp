// The run's charts: Pareto front by generation and hypervolume against evaluations.
#include "stride/optimiser/report/run_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "stride/core/atomic_file.hpp"
#include "stride/optimiser/report/svg_chart.hpp"

namespace stride::opt::report {

using nlohmann::json;

namespace {

// Early generations warm and light, the last one dark blue.
constexpr const char* kGenerationColours[] = {"#e6a532", "#d97b2b", "#c4503a", "#a23a63",
                                              "#6f3585", "#3b3a8f", "#10306b"};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string change(double v, double o) {
  if (!(std::abs(o) > 0) || !std::isfinite(o)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.1f %%", 100.0 * (v - o) / o);
  return buf;
}

}  // namespace

const char* individual_colour(std::size_t index) {
  constexpr const char* kColours[] = {"#222222", "#2ca02c", "#9467bd", "#e377c2",
                                      "#17becf", "#bcbd22", "#8c564b"};
  return kColours[index % (sizeof kColours / sizeof kColours[0])];
}

std::vector<int> shown_generations(int last_generation, int count) {
  std::vector<int> shown;
  const int n = std::min(last_generation, count);
  for (int k = 0; k < n; ++k) {
    const int g = n == 1 ? last_generation : 1 + (last_generation - 1) * k / (n - 1);
    if (shown.empty() || shown.back() != g) shown.push_back(g);
  }
  return shown;
}

std::string pareto_chart_svg(const RunData& data, const std::vector<RunPick>& picks) {
  const ObjectiveNames names = objective_names(data);
  int last_generation = 0;
  for (const auto& e : data.evaluations)
    last_generation = std::max(last_generation, e.value("generation", 0));
  bool any_feasible = false;
  for (const auto& e : data.evaluations) any_feasible = any_feasible || feasible(e);
  auto usable = [&](const json& e) {
    if (any_feasible) return feasible(e);
    const std::vector<double> f = objectives_of(e);
    return !e.value("failed", false) && f.size() >= 2 && f[0] < 1e29 && f[1] < 1e29;
  };
  // Front files by objectives (a point of the final front names its file).
  std::map<std::vector<double>, std::string> files;
  for (std::size_t i = 0; i < data.front.size(); ++i)
    files.emplace(data.front[i].objectives, front_file_name(i));

  ChartSpec spec;
  spec.id = "pareto-chart";
  spec.title = "Pareto front by generation (" + (data.task.empty() ? "run" : data.task) + ")" +
               (any_feasible || data.evaluations.empty()
                    ? std::string()
                    : std::string(", no feasible member yet: best infeasible"));
  spec.x_label = names.f1;
  spec.y_label = names.f2;
  const std::vector<int> shown = shown_generations(last_generation);
  for (std::size_t k = 0; k < shown.size(); ++k) {
    const int g = shown[k];
    std::vector<std::vector<double>> pts;
    for (const auto& e : data.evaluations)
      if (e.value("generation", 0) <= g && usable(e)) {
        std::vector<double> p = objectives_of(e);
        p.resize(2);
        p.push_back(e.value("id", -1.0));
        p.push_back(e.value("generation", 0.0));
        pts.push_back(p);
      }
    ChartSeries s;
    s.label = "generation " + std::to_string(g);
    s.colour = kGenerationColours[shown.size() == 1 ? 6 : k * 6 / (shown.size() - 1)];
    s.css_class = "front-generation";
    const bool last = k + 1 == shown.size();
    s.marker_r = last ? 3.0 : 3.5 + 1.0 * static_cast<double>(shown.size() - 1 - k);
    s.hollow = !last;
    s.line_width = last ? 2.0 : 1.2;
    for (const auto& p : non_dominated(pts)) {
      std::string tip = "generation " + std::to_string(g) + " front: " + names.f1 + " = " +
                        fmt(p[0]) + ", " + names.f2 + " = " + fmt(p[1]) + "; evaluation " +
                        fmt(p[2]) + " (generation " + fmt(p[3]) + ")";
      const auto file = files.find({p[0], p[1]});
      tip += file != files.end() ? "; " + file->second : "; not in the final front";
      s.points.push_back({p[0], p[1], tip});
    }
    spec.series.push_back(std::move(s));
  }
  const json* ind_o = find_ind_o(data);
  std::vector<double> o;
  if (ind_o != nullptr) o = objectives_of(*ind_o);
  if (o.size() >= 2 && o[0] < 1e29 && o[1] < 1e29) {
    // Ind_O widens the axes: it is always in view.
    ChartSeries anchor;
    anchor.line = false;
    anchor.points.push_back({o[0], o[1], ""});
    spec.series.push_back(anchor);
    spec.markers.push_back({o[0], o[1], "Ind_O", individual_colour(0), 's',
                            "Ind_O (start genome): " + names.f1 + " = " + fmt(o[0]) + ", " +
                                names.f2 + " = " + fmt(o[1])});
  }
  for (std::size_t i = 0; i < picks.size(); ++i) {
    const RunPick& p = picks[i];
    std::string tip = p.label + ": " + names.f1 + " = " + fmt(p.objectives[0]) + ", " + names.f2 +
                      " = " + fmt(p.objectives[1]) + "; " + p.file;
    if (o.size() >= 2)
      tip += " (" + change(p.objectives[0], o[0]) + ", " + change(p.objectives[1], o[1]) +
             " vs Ind_O)";
    spec.markers.push_back({p.objectives[0], p.objectives[1], p.label, individual_colour(i + 1),
                            i % 2 == 0 ? 'd' : 't', tip});
  }
  return render_chart(spec);
}

std::string hypervolume_chart_svg(const RunData& data) {
  ChartSpec spec;
  spec.id = "hypervolume-chart";
  spec.title = "Hypervolume (" + (data.task.empty() ? "run" : data.task) + ")";
  spec.x_label = "evaluations";
  spec.y_label = "hypervolume (normalised)";
  ChartSeries s;
  s.label = "hypervolume";
  s.colour = "#c03030";
  s.marker_r = 3;
  double top = 0.0;
  for (const auto& g : data.generations)
    if (g.contains("hypervolume") && g["hypervolume"].is_number() && g.contains("evaluations") &&
        g["evaluations"].is_number()) {
      const double hv = g["hypervolume"].get<double>(), ev = g["evaluations"].get<double>();
      top = std::max(top, hv);
      s.points.push_back({ev, hv,
                          "generation " + std::to_string(g.value("generation", 0)) + ": " +
                              fmt(ev) + " evaluations, hypervolume " + fmt(hv)});
    }
  if (s.points.empty()) spec.title += ": no hypervolume recorded";
  double right = 1.0;
  for (const auto& p : s.points) right = std::max(right, p.x);
  spec.x_range = AxisRange{0.0, nice_ticks(0.0, right).back()};
  spec.y_range = AxisRange{0.0, nice_ticks(0.0, top > 0 ? top * 1.05 : 1.0).back()};
  spec.series.push_back(std::move(s));
  return render_chart(spec);
}

}  // namespace stride::opt::report

namespace stride::opt {

Status write_plots(const std::filesystem::path& dir) {
  report::RunData data;
  if (Status s = report::load_run_data(dir, data); !s) return s;
  const auto picks = report::run_picks(data);
  if (Status s = core::write_file_atomically(dir / "pareto_by_generation.svg",
                                             report::pareto_chart_svg(data, picks));
      !s)
    return s;
  return core::write_file_atomically(dir / "hypervolume.svg", report::hypervolume_chart_svg(data));
}

}  // namespace stride::opt
