// The episode sections of the report pages: replay data, accelerometer charts, pose strips.
#include "stride/optimiser/report/html_replay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

#include "stride/optimiser/report/html_page.hpp"
#include "stride/optimiser/report/svg_chart.hpp"
#include "stride/sim_hal/pose_svg.hpp"
#include "stride/sim_hal/stick_figure.hpp"

namespace stride::opt::report {
namespace {

void put_mm(std::string& bytes, double metres) {
  const double mm = std::clamp(std::round(metres * 1000.0), -32767.0, 32767.0);
  const auto v = static_cast<std::uint16_t>(static_cast<std::int16_t>(std::isfinite(mm) ? mm : 0));
  bytes.push_back(static_cast<char>(v & 0xff));
  bytes.push_back(static_cast<char>(v >> 8));
}

double end_time(const ReplayIndividual& ind) {
  return ind.capture.frames.empty() ? 0.0 : ind.capture.frames.back().time_s;
}

}  // namespace

std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t n = static_cast<std::uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) n |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) n |= static_cast<std::uint8_t>(bytes[i + 2]);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

ReplayScene replay_scene(const sim::WorldOptions& world) {
  ReplayScene scene;
  scene.ground = sim::contact_kind_name(world.contact);
  scene.grass_m = world.contact.grass_thickness_m;
  if (world.ball.present) scene.ball_radius_m = world.ball.radius_m;
  return scene;
}

nlohmann::json replay_data(const sim::RobotModel& model,
                           const std::vector<ReplayIndividual>& individuals,
                           const ReplayScene& scene) {
  const sim::StickFigure figure = sim::stick_figure(model);
  nlohmann::json strokes = nlohmann::json::array(), circles = nlohmann::json::array();
  for (const sim::StickStroke& s : figure.strokes)
    strokes.push_back({s.a, s.b, sim::stick_colour(s.side), s.sole ? 3 : 4});
  for (const sim::StickCircle& c : figure.circles) circles.push_back({c.centre, c.radius_m});
  double frame_dt = 0.05;
  nlohmann::json people = nlohmann::json::array();
  for (const ReplayIndividual& ind : individuals) {
    frame_dt = ind.capture.period_s * ind.capture.frame_every_ticks;
    std::string bytes;
    std::size_t frames = 0;
    for (const sim::PoseSnapshot& f : ind.capture.frames) {
      const std::vector<Eigen::Vector3d> points = sim::stick_points(model, f.links);
      if (static_cast<int>(points.size()) != figure.point_count) break;
      for (const Eigen::Vector3d& p : points)
        for (int k = 0; k < 3; ++k) put_mm(bytes, p[k]);
      for (int k = 0; k < 3; ++k) put_mm(bytes, f.ball[k]);
      ++frames;
    }
    people.push_back({{"name", ind.name},
                      {"note", ind.note},
                      {"colour", ind.colour},
                      {"end_s", end_time(ind)},
                      {"frames", frames},
                      {"data", base64(bytes)}});
  }
  nlohmann::json out = {
      {"frame_dt", frame_dt},
      {"figure", {{"points", figure.point_count}, {"strokes", strokes}, {"circles", circles}}},
      {"ground", scene.ground},
      {"grass_m", scene.grass_m},
      {"ball_radius_m", scene.ball_radius_m},
      {"goal_m", nullptr},
      {"individuals", people}};
  if (scene.goal_m) out["goal_m"] = *scene.goal_m;
  return out;
}

std::string replay_section_html() {
  return "<div id=\"replay-controls\">"
         "<button id=\"replay-play\" type=\"button\" aria-pressed=\"false\">Play</button>"
         "<label>speed <select id=\"replay-speed\"><option value=\"0.1\">0.1x</option>"
         "<option value=\"0.25\">0.25x</option><option value=\"0.5\">0.5x</option>"
         "<option value=\"1\" selected>1x</option><option value=\"2\">2x</option>"
         "<option value=\"4\">4x</option></select></label>"
         "<input id=\"replay-time\" type=\"range\" min=\"0\" max=\"1\" step=\"0.01\" value=\"0\" "
         "aria-label=\"time\">"
         "<span id=\"replay-clock\" data-time=\"0\">t = 0.00 s</span></div>\n"
         "<div id=\"replay-cards\"></div>\n"
         "<noscript><p class=\"note\">The replay needs JavaScript.</p></noscript>\n";
}

namespace {

// One accelerometer panel: component 0 is |a|, 1..3 are a_x, a_y, a_z; samples in [t0, t1],
// thinned to the min and max of each pixel-wide time bucket so that peaks survive.
std::string accel_panel(const std::vector<ReplayIndividual>& individuals, int component, double t0,
                        double t1, const std::string& id, const std::string& title) {
  const char* names[] = {"|a|", "a_x (forward)", "a_y (left)", "a_z (up)"};
  constexpr int kBuckets = 480;
  ChartSpec spec;
  spec.id = id;
  spec.title = title;
  spec.x_label = "time [s]";
  spec.y_label = std::string(names[component]) + " [m/s^2]";
  spec.width = 640;
  spec.height = 300;
  spec.x_range = AxisRange{t0, t1};
  for (const ReplayIndividual& ind : individuals) {
    ChartSeries s;
    s.label = ind.name;
    s.colour = ind.colour;
    s.line_width = 1.0;
    const auto& samples = ind.capture.accel;
    auto value = [&](std::size_t k) {
      return component == 0 ? samples[k].a.norm() : samples[k].a[component - 1];
    };
    std::size_t i = 0;
    while (i < samples.size() && samples[i].t < t0) ++i;
    for (int b = 0; b < kBuckets && i < samples.size() && samples[i].t <= t1; ++b) {
      const double bucket_end = t0 + (t1 - t0) * (b + 1) / kBuckets;
      std::size_t lo = i, hi = i, n = 0;
      for (; i < samples.size() && samples[i].t <= bucket_end; ++i, ++n) {
        if (value(i) < value(lo)) lo = i;
        if (value(i) > value(hi)) hi = i;
      }
      if (n == 0) continue;
      s.points.push_back({samples[std::min(lo, hi)].t, value(std::min(lo, hi)), ""});
      if (lo != hi) s.points.push_back({samples[std::max(lo, hi)].t, value(std::max(lo, hi)), ""});
    }
    spec.series.push_back(std::move(s));
  }
  return render_chart(spec);
}

}  // namespace

std::string accel_charts_html(const std::vector<ReplayIndividual>& individuals,
                              std::optional<std::pair<double, double>> window) {
  double end = 0.0;
  for (const auto& ind : individuals)
    if (!ind.capture.accel.empty()) end = std::max(end, ind.capture.accel.back().t);
  if (end <= 0.0) return missing_note("No accelerometer samples were recorded.");
  const double right = nice_ticks(0.0, end).back();
  std::string html = "<div class=\"chart-row accel\">\n";
  if (window && window->second > window->first) {
    char title[96];
    std::snprintf(title, sizeof title, "|a| from %.2f to %.2f s (torso frame)", window->first,
                  window->second);
    html += accel_panel(individuals, 0, window->first, window->second, "accel-window", title);
  }
  const char* titles[] = {"|a|", "a_x (forward)", "a_y (left)", "a_z (up)"};
  for (int c = 0; c < 4; ++c)
    html +=
        accel_panel(individuals, c, 0.0, right, "accel-" + std::to_string(c),
                    std::string("Accelerometer ") + titles[c] + ", whole episode (torso frame)");
  return html + "</div>\n";
}

double first_ball_motion_s(const std::vector<ReplayIndividual>& individuals, double fallback_s) {
  double first = std::numeric_limits<double>::infinity();
  for (const ReplayIndividual& ind : individuals) {
    const auto& frames = ind.capture.frames;
    for (const sim::PoseSnapshot& f : frames)
      if ((f.ball - frames.front().ball).head<2>().norm() > 0.01) {
        first = std::min(first, f.time_s);
        break;
      }
  }
  return std::isfinite(first) ? first : fallback_s;
}

std::vector<double> strip_times(double start_s, double step_s, int count, double end_s) {
  std::vector<double> out;
  const double start = std::clamp(start_s, 0.0, std::max(0.0, end_s));
  for (int k = 0; k < count; ++k) out.push_back(std::min(start + step_s * k, end_s));
  return out;
}

std::string pose_strips_html(const sim::RobotModel& model,
                             const std::vector<ReplayIndividual>& individuals,
                             const std::vector<double>& times_s, const ReplayScene& scene,
                             bool pick_rows) {
  auto strip = [&](const ReplayIndividual& ind) {
    std::string svg = sim::render_pose_svg(model, sim::snapshots_at(ind.capture, times_s),
                                           scene.grass_m, scene.ball_radius_m);
    if (svg.rfind("<?xml", 0) == 0) svg = svg.substr(svg.find('\n') + 1);
    return "<div class=\"who\"><span class=\"swatch\" style=\"background:" + ind.colour +
           "\"></span>" + html_escape(ind.name) + " &mdash; " + html_escape(ind.note) + "</div>\n" +
           svg;
  };
  if (individuals.empty()) return missing_note("No episode to show.");
  std::string html;
  if (!pick_rows || individuals.size() == 1) {
    for (const auto& ind : individuals) html += "<div class=\"strip\">" + strip(ind) + "</div>\n";
    return html;
  }
  for (std::size_t i = 1; i < individuals.size(); ++i)
    html += "<div class=\"strip\"><h3>" + html_escape(individuals[0].name) + " above " +
            html_escape(individuals[i].name) + "</h3>\n" + strip(individuals[0]) +
            strip(individuals[i]) + "</div>\n";
  return html;
}

}  // namespace stride::opt::report
