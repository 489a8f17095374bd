// Stick figure of the robot: point layout and strokes shared by pose_svg and the HTML replay.
#include "stride/sim_hal/stick_figure.hpp"

#include <string>

namespace stride::sim {
namespace {

constexpr double kMinDrawnSphere = 0.03;  // [m]; the 5 mm foot studs are not drawn

StickSide side_of(const std::string& name) {
  if (name.find("left") != std::string::npos) return StickSide::kLeft;
  if (name.find("right") != std::string::npos) return StickSide::kRight;
  return StickSide::kCentre;
}

bool is_foot(const LinkSpec& link) {
  return !link.spheres.empty() && !link.boxes.empty();
}

}  // namespace

const char* stick_colour(StickSide side) {
  switch (side) {
    case StickSide::kLeft:
      return "#1f77b4";
    case StickSide::kRight:
      return "#d62728";
    case StickSide::kCentre:
      break;
  }
  return "#333333";
}

StickFigure stick_figure(const RobotModel& model) {
  StickFigure f;
  const auto& links = model.links();
  int next = static_cast<int>(links.size());
  for (const JointSpec& j : model.joints())
    f.strokes.push_back({j.parent_link, j.child_link, side_of(j.name), false});
  for (const LinkSpec& link : links) {
    if (!is_foot(link)) continue;
    for (std::size_t b = 0; b < link.boxes.size(); ++b) {
      f.strokes.push_back({next, next + 1, side_of(link.name), true});      // heel - toe
      f.strokes.push_back({next + 2, next + 3, side_of(link.name), true});  // inner - outer
      next += 4;
    }
  }
  for (const LinkSpec& link : links)
    for (const CollisionSphere& c : link.spheres)
      if (c.radius >= kMinDrawnSphere) f.circles.push_back({next++, c.radius});
  f.point_count = next;
  return f;
}

std::vector<Eigen::Vector3d> stick_points(const RobotModel& model,
                                          const std::vector<Eigen::Isometry3d>& poses) {
  const auto& links = model.links();
  std::vector<Eigen::Vector3d> out;
  if (poses.size() != links.size()) return out;
  for (const Eigen::Isometry3d& p : poses) out.push_back(p.translation());
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (!is_foot(links[l])) continue;
    for (const CollisionBox& b : links[l].boxes) {
      const Eigen::Vector3d h = b.size / 2;
      for (const Eigen::Vector3d& corner :
           {Eigen::Vector3d(-h.x(), 0, -h.z()), Eigen::Vector3d(h.x(), 0, -h.z()),
            Eigen::Vector3d(0, -h.y(), -h.z()), Eigen::Vector3d(0, h.y(), -h.z())})
        out.push_back(poses[l] * (b.pose * corner));
    }
  }
  for (std::size_t l = 0; l < links.size(); ++l)
    for (const CollisionSphere& c : links[l].spheres)
      if (c.radius >= kMinDrawnSphere) out.push_back(poses[l] * c.center);
  return out;
}

}  // namespace stride::sim
