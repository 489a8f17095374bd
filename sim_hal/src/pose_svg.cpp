// Pose pictures: side and front stick figures of link frames as SVG.
#include "stride/sim_hal/pose_svg.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "stride/sim_hal/stick_figure.hpp"

namespace stride::sim {
namespace {

constexpr double kScale = 320.0;  // px per metre
constexpr double kPanelW = 300.0;
constexpr double kPanelH = 360.0;
constexpr double kGroundY = 330.0;  // px of z = 0 within a panel

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", v);
  return text;
}

struct View {
  double x0, y0;     // panel origin in px
  int horizontal;    // 0: world x, 1: world y
  double reference;  // world coordinate drawn at the panel centre
  double px(const Eigen::Vector3d& p) const {
    return x0 + kPanelW / 2 + kScale * (p[horizontal] - reference);
  }
  double py(const Eigen::Vector3d& p) const { return y0 + kGroundY - kScale * p.z(); }
};

void line(std::string& svg, const View& v, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
          const char* colour, double width) {
  svg += "<line x1=\"" + num(v.px(a)) + "\" y1=\"" + num(v.py(a)) + "\" x2=\"" + num(v.px(b)) +
         "\" y2=\"" + num(v.py(b)) + "\" stroke=\"" + colour + "\" stroke-width=\"" + num(width) +
         "\" stroke-linecap=\"round\"/>\n";
}

void draw_robot(std::string& svg, const View& v, const RobotModel& model, const PoseSnapshot& s,
                double grass, double ball_radius) {
  // Field: solid ground and grass top.
  const double left = v.x0, right = v.x0 + kPanelW;
  svg += "<rect x=\"" + num(left) + "\" y=\"" + num(v.y0 + kGroundY - kScale * grass) +
         "\" width=\"" + num(kPanelW) + "\" height=\"" + num(kScale * grass) +
         "\" fill=\"#b7e3a1\"/>\n";
  svg += "<line x1=\"" + num(left) + "\" y1=\"" + num(v.y0 + kGroundY) + "\" x2=\"" + num(right) +
         "\" y2=\"" + num(v.y0 + kGroundY) + "\" stroke=\"#6b4f2a\" stroke-width=\"2\"/>\n";
  const std::vector<Eigen::Vector3d> points = stick_points(model, s.links);
  if (!points.empty()) {
    const StickFigure figure = stick_figure(model);
    for (const StickStroke& k : figure.strokes)
      line(svg, v, points[static_cast<std::size_t>(k.a)], points[static_cast<std::size_t>(k.b)],
           stick_colour(k.side), k.sole ? 3.0 : 4.0);
    for (const StickCircle& c : figure.circles) {
      const Eigen::Vector3d& p = points[static_cast<std::size_t>(c.centre)];
      svg += "<circle cx=\"" + num(v.px(p)) + "\" cy=\"" + num(v.py(p)) + "\" r=\"" +
             num(kScale * c.radius_m) +
             "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"2\"/>\n";
    }
  }
  if (ball_radius > 0) {
    const double cx = v.px(s.ball);
    if (cx > left - 40 && cx < right + 40)
      svg += "<circle cx=\"" + num(cx) + "\" cy=\"" + num(v.py(s.ball)) + "\" r=\"" +
             num(kScale * ball_radius) +
             "\" fill=\"#ffffff\" fill-opacity=\"0.3\" stroke=\"#000000\" stroke-width=\"1.5\"/>\n";
  }
}

}  // namespace

std::string render_pose_svg(const RobotModel& model, const std::vector<PoseSnapshot>& snapshots,
                            double grass_thickness_m, double ball_radius_m) {
  const double width = kPanelW * static_cast<double>(std::max<std::size_t>(1, snapshots.size()));
  const double height = 2 * kPanelH + 30;
  std::string svg =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
      "width=\"" +
      num(width) + "\" height=\"" + num(height) + "\" viewBox=\"0 0 " + num(width) + " " +
      num(height) + "\">\n<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  for (std::size_t i = 0; i < snapshots.size(); ++i) {
    const PoseSnapshot& s = snapshots[i];
    const double x0 = kPanelW * static_cast<double>(i);
    Eigen::Vector3d torso = Eigen::Vector3d::Zero();
    if (!s.links.empty()) torso = s.links[0].translation();
    const View side{x0, 30, 0, torso.x()};
    const View front{x0, 30 + kPanelH, 1, torso.y()};
    draw_robot(svg, side, model, s, grass_thickness_m, ball_radius_m);
    draw_robot(svg, front, model, s, grass_thickness_m, ball_radius_m);
    char label[160];
    std::snprintf(label, sizeof label, "t = %.2f s  torso (%.3f, %.3f, %.3f) m", s.time_s,
                  torso.x(), torso.y(), torso.z());
    svg += "<text x=\"" + num(x0 + 6) + "\" y=\"20\" font-family=\"sans-serif\" font-size=\"12\">" +
           label + "</text>\n";
    svg += "<text x=\"" + num(x0 + 6) +
           "\" y=\"46\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#666666\">side (x "
           "right)</text>\n";
    svg += "<text x=\"" + num(x0 + 6) + "\" y=\"" + num(46 + kPanelH) +
           "\" font-family=\"sans-serif\" font-size=\"11\" fill=\"#666666\">front (robot's left on "
           "the right)</text>\n";
    svg += "<line x1=\"" + num(x0) + "\" y1=\"0\" x2=\"" + num(x0) + "\" y2=\"" + num(height) +
           "\" stroke=\"#dddddd\"/>\n";
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace stride::sim
