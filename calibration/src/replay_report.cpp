// `stride replay`'s outputs: text table, JSON summary, HTML page with inline SVG traces.
#include "stride/calibration/replay_report.hpp"

#include "stride/core/text_escape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>

namespace stride::calibration {

using sim::ReplayErrors;
using sim::ReplayResult;
using sim::ReplayWindow;

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

/// A number for JSON: null for NaN (nothing compared).
nlohmann::json number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json per_joint(const std::array<double, hal::kServoCount>& values, double all,
                         const std::array<std::string, hal::kServoCount>& names) {
  nlohmann::json joints = nlohmann::json::object();
  for (std::size_t i = 0; i < hal::kServoCount; ++i) joints[names[i]] = number(values[i]);
  return {{"all", number(all)}, {"per_joint", joints}};
}

nlohmann::json xyz(const Eigen::Vector3d& v) {
  return {{"x", number(v.x())}, {"y", number(v.y())}, {"z", number(v.z())}};
}

std::string format(const char* pattern, double v) {
  if (!std::isfinite(v)) return "-";
  char text[64];
  std::snprintf(text, sizeof text, pattern, v);
  return text;
}

/// The servo with the largest position error, as "name x.x".
std::string worst_joint(const ReplayErrors& e, const std::array<std::string, hal::kServoCount>& n) {
  std::size_t worst = hal::kServoCount;
  for (std::size_t i = 0; i < hal::kServoCount; ++i)
    if (std::isfinite(e.position_rad[i]) &&
        (worst == hal::kServoCount || e.position_rad[i] > e.position_rad[worst]))
      worst = i;
  if (worst == hal::kServoCount) return "-";
  return n[worst] + " " + format("%.1f", e.position_rad[worst] / kEncoderTickRad);
}

std::string table_row(const std::string& label, const ReplayErrors& e,
                      const std::array<std::string, hal::kServoCount>& names) {
  char line[512];
  std::snprintf(line, sizeof line, "%-12s %6zu %9s %8s %8s %7s %7s %7s %8s %9s  %s\n",
                label.c_str(), e.samples, format("%.5f", e.position_all_rad).c_str(),
                format("%.2f", e.position_all_rad / kEncoderTickRad).c_str(),
                format("%.3f", e.speed_all_rad_s).c_str(), format("%.3f", e.load_all).c_str(),
                format("%.2f", e.roll_rad * kRadToDeg).c_str(),
                format("%.2f", e.pitch_rad * kRadToDeg).c_str(),
                format("%.3f", e.gyro_rad_s.norm()).c_str(),
                format("%.3f", e.accel_mps2.norm()).c_str(), worst_joint(e, names).c_str());
  return line;
}

}  // namespace

nlohmann::json to_json(const ReplayErrors& e,
                       const std::array<std::string, hal::kServoCount>& names) {
  return {{"ticks", e.samples},
          {"position_rms_rad", per_joint(e.position_rad, e.position_all_rad, names)},
          {"position_rms_encoder_ticks", number(e.position_all_rad / kEncoderTickRad)},
          {"speed_rms_rad_s", per_joint(e.speed_rad_s, e.speed_all_rad_s, names)},
          {"load_rms", per_joint(e.load, e.load_all, names)},
          {"roll_rms_rad", number(e.roll_rad)},
          {"pitch_rms_rad", number(e.pitch_rad)},
          {"gyro_rms_rad_s", xyz(e.gyro_rad_s)},
          {"accel_rms_mps2", xyz(e.accel_mps2)}};
}

nlohmann::json replay_summary_json(const ReplayResult& r,
                                   const std::vector<std::pair<std::string, std::string>>& facts) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : facts) out[name] = value;
  out["period_s"] = r.period_s;
  out["window_s"] = static_cast<double>(r.window_ticks) * r.period_s;
  out["window_ticks"] = r.window_ticks;
  out["ticks_in_log"] = r.ticks_in_log;
  out["ticks_not_replayed"] = r.ticks_not_replayed;
  nlohmann::json windows = nlohmann::json::array();
  for (const ReplayWindow& w : r.windows) {
    nlohmann::json j = to_json(w.errors, r.servo_names);
    j["start_s"] = w.start_s;
    j["start_tick"] = w.start_tick;
    j["start_roll_rad"] = w.start_roll_pitch.x();
    j["start_pitch_rad"] = w.start_roll_pitch.y();
    j["failure"] = w.failure.empty() ? nlohmann::json(nullptr) : nlohmann::json(w.failure);
    windows.push_back(std::move(j));
  }
  out["windows"] = std::move(windows);
  out["overall"] = to_json(r.overall, r.servo_names);
  return out;
}

std::string replay_table(const ReplayResult& r) {
  std::string out;
  out +=
      "RMS error, simulated - logged (position also in encoder ticks of 2pi/4096 rad; gyro "
      "and accelerometer: the three axes together)\n";
  char header[256];
  std::snprintf(header, sizeof header, "%-12s %6s %9s %8s %8s %7s %7s %7s %8s %9s  %s\n", "window",
                "ticks", "pos[rad]", "pos[tk]", "spd[r/s]", "load", "roll[d]", "ptch[d]",
                "gyr[r/s]", "acc[m/s2]", "worst joint [tk]");
  out += header;
  for (const ReplayWindow& w : r.windows) {
    out += table_row(format("%.2f s", w.start_s), w.errors, r.servo_names);
    if (!w.failure.empty()) out += "             simulation stopped: " + w.failure + "\n";
  }
  out += table_row("overall", r.overall, r.servo_names);
  out += "\njoint                 pos[rad]  pos[tk]  spd[rad/s]   load\n";
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    char line[256];
    std::snprintf(line, sizeof line, "%2zu %-18s %9s %8s %11s %6s\n", i + 1,
                  r.servo_names[i].c_str(), format("%.5f", r.overall.position_rad[i]).c_str(),
                  format("%.2f", r.overall.position_rad[i] / kEncoderTickRad).c_str(),
                  format("%.3f", r.overall.speed_rad_s[i]).c_str(),
                  format("%.3f", r.overall.load[i]).c_str());
    out += line;
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// HTML

namespace {

/// One chart: logged (grey) and simulated (colour) over the replayed windows, decimated to at
/// most kMaxPoints per trace; a gap between windows breaks the line.
class Chart {
 public:
  static constexpr std::size_t kMaxPoints = 1500;
  static constexpr double kWidth = 900, kHeight = 130, kLeft = 60, kTop = 18, kBottom = 16;

  Chart(const ReplayResult& r, double scale) : r_(r), scale_(scale) {
    std::size_t total = 0;
    for (const ReplayWindow& w : r.windows) total += w.traces.time_s.size();
    stride_ = std::max<std::size_t>(1, (total + kMaxPoints - 1) / kMaxPoints);
    for (const ReplayWindow& w : r.windows)
      if (!w.traces.time_s.empty()) {
        t0_ = std::min(t0_, w.start_s);
        t1_ = std::max(t1_, w.traces.time_s.back());
      }
    if (!(t1_ > t0_)) t1_ = t0_ + 1.0;
  }

  using Getter = std::function<const std::vector<float>&(const ReplayWindow&)>;
  /// `logged(w)` and `sim(w)` give window w's traces.
  std::string svg(const std::string& title, const std::string& unit, const Getter& logged,
                  const Getter& sim) const {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t w = 0; w < r_.windows.size(); ++w)
      for (const auto* trace : {&logged(r_.windows[w]), &sim(r_.windows[w])})
        for (float v : *trace)
          if (std::isfinite(v)) {
            lo = std::min(lo, v * scale_);
            hi = std::max(hi, v * scale_);
          }
    if (!(hi >= lo)) lo = hi = 0.0;
    const double pad = std::max(1e-3, 0.08 * (hi - lo));
    lo -= pad;
    hi += pad;
    std::ostringstream s;
    s << "<svg viewBox='0 0 " << kWidth << ' ' << kHeight << "' class='chart'>";
    s << "<text x='4' y='12' class='title'>" << core::xml_escape(title) << " ["
      << core::xml_escape(unit) << "]</text>";
    s << "<text x='4' y='" << kTop + 8 << "'>" << format("%.3g", hi) << "</text>";
    s << "<text x='4' y='" << kHeight - kBottom << "'>" << format("%.3g", lo) << "</text>";
    for (const ReplayWindow& w : r_.windows)
      s << "<line class='win' x1='" << x(w.start_s) << "' x2='" << x(w.start_s) << "' y1='" << kTop
        << "' y2='" << kHeight - kBottom << "'/>";
    s << "<text x='" << kLeft << "' y='" << kHeight - 2 << "'>" << format("%.2f s", t0_)
      << "</text><text x='" << kWidth - 60 << "' y='" << kHeight - 2 << "'>"
      << format("%.2f s", t1_) << "</text>";
    for (int which = 0; which < 2; ++which) {
      s << "<path class='" << (which == 0 ? "logged" : "sim") << "' d='";
      for (const ReplayWindow& w : r_.windows) {
        const std::vector<float>& v = which == 0 ? logged(w) : sim(w);
        bool first = true;
        for (std::size_t k = 0; k < v.size(); k += stride_) {
          const double y = kTop + (hi - v[k] * scale_) / (hi - lo) * (kHeight - kTop - kBottom);
          s << (first ? 'M' : 'L') << format("%.1f", x(w.traces.time_s[k])) << ' '
            << format("%.1f", y) << ' ';
          first = false;
        }
      }
      s << "'/>";
    }
    s << "</svg>\n";
    return s.str();
  }

 private:
  double x(double t) const { return kLeft + (t - t0_) / (t1_ - t0_) * (kWidth - kLeft - 8); }

  const ReplayResult& r_;
  double scale_;
  std::size_t stride_ = 1;
  double t0_ = std::numeric_limits<double>::infinity(), t1_ = -t0_;
};

}  // namespace

std::string replay_html(const ReplayResult& r, const std::string& title,
                        const std::vector<std::pair<std::string, std::string>>& facts) {
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>"
       << core::xml_escape(title)
       << "</title>\n<style>body{font-family:sans-serif;margin:1.5em;max-width:960px}"
          "table{border-collapse:collapse}td,th{padding:2px 8px;border-bottom:1px solid #ddd;"
          "text-align:left}pre{font-size:12px}svg.chart{width:100%;height:auto;display:block;"
          "margin:4px 0}svg text{font-size:10px}svg text.title{font-weight:bold}"
          "path{fill:none;stroke-width:1.2}path.logged{stroke:#555}path.sim{stroke:#d33}"
          "line.win{stroke:#99c;stroke-dasharray:3 3}.key span{padding:0 1em}</style>"
          "</head><body>\n<h1>"
       << core::xml_escape(title) << "</h1>\n<table>";
  for (const auto& [name, value] : facts)
    page << "<tr><th>" << core::xml_escape(name) << "</th><td>" << core::xml_escape(value)
         << "</td></tr>";
  page << "</table>\n<h2>RMS errors</h2>\n<pre>" << core::xml_escape(replay_table(r)) << "</pre>\n";
  page << "<h2>Traces</h2><p class='key'><span style='color:#555'>&#9473; logged</span>"
          "<span style='color:#d33'>&#9473; simulated</span><span style='color:#99c'>"
          "&#9476; window start (the simulated robot is placed in the logged state)</span></p>\n";
  using Window = const ReplayWindow&;
  using Trace = const std::vector<float>&;
  const Chart degrees(r, kRadToDeg), plain(r, 1.0);
  page << degrees.svg(
      "trunk roll (complementary filter)", "deg",
      [](Window w) -> Trace { return w.traces.logged_roll; },
      [](Window w) -> Trace { return w.traces.sim_roll; });
  page << degrees.svg(
      "trunk pitch (complementary filter)", "deg",
      [](Window w) -> Trace { return w.traces.logged_pitch; },
      [](Window w) -> Trace { return w.traces.sim_pitch; });
  const char* axes = "xyz";
  for (std::size_t k = 0; k < 3; ++k)
    page << plain.svg(
        std::string("gyro ") + axes[k], "rad/s",
        [k](Window w) -> Trace { return w.traces.logged_gyro[k]; },
        [k](Window w) -> Trace { return w.traces.sim_gyro[k]; });
  for (std::size_t k = 0; k < 3; ++k)
    page << plain.svg(
        std::string("accelerometer ") + axes[k], "m/s^2",
        [k](Window w) -> Trace { return w.traces.logged_accel[k]; },
        [k](Window w) -> Trace { return w.traces.sim_accel[k]; });
  for (std::size_t i = 0; i < hal::kServoCount; ++i)
    page << degrees.svg(
        std::to_string(i + 1) + " " + r.servo_names[i] + " position", "deg",
        [i](Window w) -> Trace { return w.traces.logged_position[i]; },
        [i](Window w) -> Trace { return w.traces.sim_position[i]; });
  page << "</body></html>\n";
  return page.str();
}

}  // namespace stride::calibration
