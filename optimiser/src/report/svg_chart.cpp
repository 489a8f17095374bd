// SVG charts with 1-2-5 ticks, the legend outside the plot area and hover tooltips.
#include "stride/optimiser/report/svg_chart.hpp"

#include "stride/core/text_escape.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace stride::opt::report {
namespace {

constexpr double kLeft = 74, kTop = 40, kLegendW = 190, kBottomPad = 58;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

double nice_step(double raw) {
  const double e = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / e;
  return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * e;
}

void marker_path(std::ostringstream& svg, char shape, double x, double y, double r,
                 const std::string& fill, const std::string& stroke, double width) {
  if (shape == 'd') {
    svg << "<path d=\"M" << num(x) << ' ' << num(y - r) << "L" << num(x + r) << ' ' << num(y) << "L"
        << num(x) << ' ' << num(y + r) << "L" << num(x - r) << ' ' << num(y) << "Z\"";
  } else if (shape == 't') {
    svg << "<path d=\"M" << num(x) << ' ' << num(y - r) << "L" << num(x + r) << ' '
        << num(y + r * 0.8) << "L" << num(x - r) << ' ' << num(y + r * 0.8) << "Z\"";
  } else {
    svg << "<rect x=\"" << num(x - r) << "\" y=\"" << num(y - r) << "\" width=\"" << num(2 * r)
        << "\" height=\"" << num(2 * r) << "\"";
  }
  svg << " fill=\"" << fill << "\" stroke=\"" << stroke << "\" stroke-width=\"" << width << "\"";
}

AxisRange data_range(const ChartSpec& spec, bool x_axis) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const ChartSeries& s : spec.series)
    for (const ChartPoint& p : s.points) {
      const double v = x_axis ? p.x : p.y;
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
  if (!std::isfinite(lo)) return {0.0, 1.0};
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
    const double pad = std::max(std::abs(hi) * 0.05, 1e-3);
    lo -= pad, hi += pad;
  }
  return {lo, hi};
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double step = nice_step((hi - lo) / std::max(1, target));
  std::vector<double> ticks;
  const double first = std::floor(lo / step + 1e-9) * step;
  for (int i = 0; i < 100; ++i) {
    const double t = first + step * i;
    ticks.push_back(std::abs(t) < step * 1e-9 ? 0.0 : t);
    if (t >= hi - step * 1e-9) break;
  }
  return ticks;
}

std::string tick_label(double value, double step) {
  const int decimals =
      step > 0 ? std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9))) : 0;
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 12), value);
  return buf;
}

namespace {

/// The plot area in the picture [px] and the data range it shows.
struct Plot {
  double right = 0, bottom = 0;  ///< the plot area is kLeft..right, kTop..bottom
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  double xs = 1, ys = 1;  ///< x1 - x0 and y1 - y0 (1 for an empty range)
  double px(double x) const { return kLeft + (right - kLeft) * (x - x0) / xs; }
  double py(double y) const { return bottom - (bottom - kTop) * (y - y0) / ys; }
};

/// The title, axis labels, grid lines with their tick labels, and the plot area's frame.
void draw_axes(std::ostringstream& svg, const ChartSpec& spec, const Plot& plot,
               const std::vector<double>& xt, const std::vector<double>& yt) {
  const double W = spec.width, H = spec.height, right = plot.right, bottom = plot.bottom;
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  svg << "<rect width=\"" << W << "\" height=\"" << H << "\" fill=\"white\"/>\n"
      << "<text x=\"" << num((kLeft + right) / 2) << "\" y=\"22\" text-anchor=\"middle\" "
      << "font-size=\"15\">" << core::xml_escape(spec.title) << "</text>\n"
      << "<text x=\"" << num((kLeft + right) / 2) << "\" y=\"" << num(H - 12)
      << "\" text-anchor=\"middle\">" << core::xml_escape(spec.x_label) << "</text>\n"
      << "<text x=\"16\" y=\"" << num((kTop + bottom) / 2)
      << "\" text-anchor=\"middle\" transform=\"rotate(-90 16 " << num((kTop + bottom) / 2)
      << ")\">" << core::xml_escape(spec.y_label) << "</text>\n";
  for (double t : xt) {
    if (t < plot.x0 - 1e-9 * plot.xs || t > plot.x1 + 1e-9 * plot.xs) continue;
    svg << "<line x1=\"" << num(plot.px(t)) << "\" x2=\"" << num(plot.px(t)) << "\" y1=\"" << kTop
        << "\" y2=\"" << num(bottom) << "\" stroke=\"#e4e4e4\"/>\n"
        << "<text x=\"" << num(plot.px(t)) << "\" y=\"" << num(bottom + 16)
        << "\" text-anchor=\"middle\">" << tick_label(t, xstep) << "</text>\n";
  }
  for (double t : yt) {
    if (t < plot.y0 - 1e-9 * plot.ys || t > plot.y1 + 1e-9 * plot.ys) continue;
    svg << "<line x1=\"" << kLeft << "\" x2=\"" << num(right) << "\" y1=\"" << num(plot.py(t))
        << "\" y2=\"" << num(plot.py(t)) << "\" stroke=\"#e4e4e4\"/>\n"
        << "<text x=\"" << kLeft - 6 << "\" y=\"" << num(plot.py(t) + 4)
        << "\" text-anchor=\"end\">" << tick_label(t, ystep) << "</text>\n";
  }
  svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << num(right - kLeft)
      << "\" height=\"" << num(bottom - kTop) << "\" fill=\"none\" stroke=\"black\"/>\n";
}

/// Each series: its line and its markers (a tooltip on those with a tip).
void draw_series(std::ostringstream& svg, const ChartSpec& spec, const Plot& plot) {
  for (const ChartSeries& s : spec.series) {
    svg << "<g";
    if (!s.css_class.empty()) svg << " class=\"" << core::xml_escape(s.css_class) << "\"";
    svg << ">\n";
    if (s.line && s.points.size() > 1) {
      svg << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"" << s.line_width
          << "\" points=\"";
      for (const ChartPoint& p : s.points)
        svg << num(plot.px(p.x)) << ',' << num(plot.py(p.y)) << ' ';
      svg << "\"/>\n";
    }
    if (s.marker_r > 0)
      for (const ChartPoint& p : s.points) {
        svg << "<circle cx=\"" << num(plot.px(p.x)) << "\" cy=\"" << num(plot.py(p.y)) << "\" r=\""
            << s.marker_r << "\" "
            << (s.hollow ? "fill=\"none\" stroke=\"" + s.colour + "\" stroke-width=\"1.5\""
                         : "fill=\"" + s.colour + "\"");
        if (p.tip.empty()) {
          svg << "/>\n";
        } else {
          svg << "><title>" << core::xml_escape(p.tip) << "</title></circle>\n";
        }
      }
    svg << "</g>\n";
  }
}

/// Named markers, their names placed where no earlier name is (beside, below, left, ...); a
/// marker off the scale sits on the frame and says so.
void draw_markers(std::ostringstream& svg, const ChartSpec& spec, const Plot& plot) {
  const double x0 = plot.x0, x1 = plot.x1, y0 = plot.y0, y1 = plot.y1;
  std::vector<std::array<double, 4>> placed;  // x0, y0, x1, y1 of names drawn
  for (const ChartMarker& m : spec.markers) {
    const bool off =
        m.x < x0 || m.x > x1 || m.y < y0 || m.y > y1 || !std::isfinite(m.x) || !std::isfinite(m.y);
    const double cx = plot.px(std::clamp(std::isfinite(m.x) ? m.x : x1, x0, x1));
    const double cy = plot.py(std::clamp(std::isfinite(m.y) ? m.y : y1, y0, y1));
    svg << "<g class=\"marker\">";
    marker_path(svg, m.shape, cx, cy, 6, "white", m.colour, 2.5);
    svg << "><title>" << core::xml_escape(m.tip.empty() ? m.label : m.tip) << "</title>";
    svg << (m.shape == 's' ? "</rect>" : "</path>");
    const std::string text = m.label + (off ? " (off scale)" : "");
    const double tw = 7.2 * static_cast<double>(text.size()), th = 14;
    double tx = cx + 9, ty = cy - 8;
    bool anchor_end = false;
    for (int attempt = 0; attempt < 12; ++attempt) {
      const bool left = (attempt % 2 == 1) != (cx + 9 + tw > plot.right);
      const double dy = (attempt / 2 % 2 == 0 ? -8.0 : 18.0) +
                        (attempt / 4) * (attempt / 2 % 2 == 0 ? -15.0 : 15.0);
      const double bx0 = left ? cx - 9 - tw : cx + 9, by1 = cy + dy;
      bool clash = false;
      for (const auto& b : placed)
        clash = clash || !(bx0 + tw < b[0] || bx0 > b[2] || by1 < b[1] || by1 - th > b[3]);
      tx = left ? cx - 9 : cx + 9, ty = by1, anchor_end = left;
      if (!clash) break;
    }
    const double bx0 = anchor_end ? tx - tw : tx;
    placed.push_back({bx0, ty - th, bx0 + tw, ty});
    svg << "<text x=\"" << num(tx) << "\" y=\"" << num(ty) << "\" text-anchor=\""
        << (anchor_end ? "end" : "start") << "\" font-weight=\"bold\" fill=\"" << m.colour
        << "\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\">"
        << core::xml_escape(text) << "</text></g>\n";
  }
}

/// The legend right of the plot area: the labelled series, then the markers.
void draw_legend(std::ostringstream& svg, const ChartSpec& spec, double right) {
  double y = kTop + 8;
  const double lx = right + 14;
  for (const ChartSeries& s : spec.series) {
    if (s.label.empty()) continue;
    svg << "<line x1=\"" << num(lx) << "\" x2=\"" << num(lx + 22) << "\" y1=\"" << num(y)
        << "\" y2=\"" << num(y) << "\" stroke=\"" << s.colour << "\" stroke-width=\"3\"/>";
    if (s.marker_r > 0)
      svg << "<circle cx=\"" << num(lx + 11) << "\" cy=\"" << num(y) << "\" r=\""
          << std::min(s.marker_r, 5.0) << "\" "
          << (s.hollow ? "fill=\"white\" stroke=\"" + s.colour + "\"" : "fill=\"" + s.colour + "\"")
          << "/>";
    svg << "<text x=\"" << num(lx + 28) << "\" y=\"" << num(y + 4) << "\">"
        << core::xml_escape(s.label) << "</text>\n";
    y += 18;
  }
  for (const ChartMarker& m : spec.markers) {
    marker_path(svg, m.shape, lx + 11, y, 5, "white", m.colour, 2);
    svg << "/><text x=\"" << num(lx + 28) << "\" y=\"" << num(y + 4) << "\">"
        << core::xml_escape(m.label) << "</text>\n";
    y += 18;
  }
}

}  // namespace

std::string render_chart(const ChartSpec& spec) {
  const double W = spec.width, H = spec.height;
  Plot plot;
  plot.right = W - kLegendW;
  plot.bottom = H - kBottomPad;
  const AxisRange xr = spec.x_range.value_or(data_range(spec, true));
  const AxisRange yr = spec.y_range.value_or(data_range(spec, false));
  const std::vector<double> xt = nice_ticks(xr.lo, xr.hi), yt = nice_ticks(yr.lo, yr.hi);
  plot.x0 = spec.x_range ? xr.lo : xt.front();
  plot.x1 = spec.x_range ? xr.hi : xt.back();
  plot.y0 = spec.y_range ? yr.lo : yt.front();
  plot.y1 = spec.y_range ? yr.hi : yt.back();
  plot.xs = plot.x1 > plot.x0 ? plot.x1 - plot.x0 : 1.0;
  plot.ys = plot.y1 > plot.y0 ? plot.y1 - plot.y0 : 1.0;

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\"";
  if (!spec.id.empty()) svg << " id=\"" << core::xml_escape(spec.id) << "\"";
  // The plot area and its x range, for the page's scripts (the replay's time cursor).
  svg << " data-plot=\"" << kLeft << ' ' << kTop << ' ' << num(plot.right) << ' '
      << num(plot.bottom) << ' ' << num(plot.x0) << ' ' << num(plot.x1) << '"';
  svg << " viewBox=\"0 0 " << W << ' ' << H << "\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  draw_axes(svg, spec, plot, xt, yt);
  draw_series(svg, spec, plot);
  draw_markers(svg, spec, plot);
  if (spec.legend) draw_legend(svg, spec, plot.right);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace stride::opt::report
