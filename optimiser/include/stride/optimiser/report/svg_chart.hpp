// SVG charts for run reports (the .svg files beside a run and the plots inside report.html).
//
// A chart is a plot area with axes whose ticks fall on 1-2-5 steps (0.5, 1, 2, 5, 10, ...),
// labelled with as many decimals as the step needs; the legend sits in a column to the right
// of the plot area, never over the data. Series are lines and/or markers; every data point and
// named marker may carry a tooltip (an SVG <title>, shown on hover by browsers). Named markers
// (Ind_O, the picks) are drawn on top with their name beside them; a marker outside the axis
// range is drawn on the border, its name saying "off scale" and its values.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace stride::opt::report {

struct ChartPoint {
  double x = 0.0, y = 0.0;
  std::string tip;  ///< tooltip text (empty: none)
};

struct ChartSeries {
  std::string label;  ///< legend text (empty: not in the legend)
  std::string colour = "#1f77b4";
  std::vector<ChartPoint> points;
  bool line = true;         ///< join the points
  double marker_r = 0.0;    ///< marker radius [px] (0: no markers)
  bool hollow = false;      ///< ring markers instead of filled dots
  double line_width = 1.5;  ///< [px]
  std::string css_class;    ///< class of the series' group (for the page's scripts)
};

struct ChartMarker {
  double x = 0.0, y = 0.0;
  std::string label;  ///< drawn beside the marker and in the legend
  std::string colour = "#000000";
  char shape = 's';  ///< 's' square, 'd' diamond, 't' triangle
  std::string tip;
};

struct AxisRange {
  double lo = 0.0, hi = 1.0;
};

struct ChartSpec {
  std::string title, x_label, y_label;
  int width = 780, height = 480;
  std::vector<ChartSeries> series;
  std::vector<ChartMarker> markers;
  std::optional<AxisRange> x_range, y_range;  ///< fixed ranges (else from the data, niced)
  bool legend = true;                         ///< draw the legend (its column is kept anyway)
  std::string id;                             ///< id attribute of the <svg> element
};

/// Ticks on 1-2-5 steps covering [lo, hi] (about `target` of them); the first and last tick
/// enclose the range.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);
/// A tick label with the decimals the step needs (step 0.5 -> "24.5", step 2 -> "24").
std::string tick_label(double value, double step);

/// The chart as a standalone <svg> element (with the xmlns attribute).
std::string render_chart(const ChartSpec& spec);

}  // namespace stride::opt::report
