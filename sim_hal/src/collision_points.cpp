// The collision points of a RobotModel (see collision_points.hpp).
#include "stride/sim_hal/collision_points.hpp"

namespace stride::sim {

std::vector<CollisionPoint> collision_points(const RobotModel& model) {
  std::vector<CollisionPoint> points;
  for (std::size_t l = 0; l < model.links().size(); ++l) {
    const LinkSpec& link = model.links()[l];
    for (const CollisionSphere& s : link.spheres)
      points.push_back({static_cast<int>(l), s.center, s.radius});
    for (const CollisionBox& b : link.boxes) {
      const Eigen::Vector3d half = b.size / 2;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d corner((c & 1 ? 1 : -1) * half.x(), (c & 2 ? 1 : -1) * half.y(),
                                     (c & 4 ? 1 : -1) * half.z());
        points.push_back({static_cast<int>(l), b.pose * corner, 0.0});
      }
    }
  }
  return points;
}

}  // namespace stride::sim
