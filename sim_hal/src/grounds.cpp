// Grounds drawn between hard and soft, and the stud sink (see grounds.hpp).
#include "stride/sim_hal/grounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stride::sim {

namespace {

/// p moved the fraction f in [0, 1] towards `target` on a log scale (p itself when equal).
double towards(double p, double target, double f) {
  if (p == target || f == 0.0 || !(p > 0.0) || !(target > 0.0)) return p;
  return p * std::pow(target / p, f);
}

}  // namespace

ContactOptions ground_between(const ContactOptions& world, double u) {
  if (!(u != 0.0)) return world;
  const ContactOptions target = u < 0.0 ? ContactOptions::hard() : ContactOptions::soft();
  const double f = std::min(std::abs(u), 1.0);
  ContactOptions c = world;
  c.grass_thickness_m = towards(world.grass_thickness_m, target.grass_thickness_m, f);
  c.grass_stiffness_n_m = towards(world.grass_stiffness_n_m, target.grass_stiffness_n_m, f);
  c.grass_damping_n_s_m = towards(world.grass_damping_n_s_m, target.grass_damping_n_s_m, f);
  c.tangential_stiffness_n_m =
      towards(world.tangential_stiffness_n_m, target.tangential_stiffness_n_m, f);
  c.tangential_damping_n_s_m =
      towards(world.tangential_damping_n_s_m, target.tangential_damping_n_s_m, f);
  return c;
}

ContactOptions draw_ground(const ContactOptions& world, double range, WorldRng& rng) {
  if (!(range > 0.0)) return world;
  return ground_between(world, rng.uniform(-range, range));
}

double stud_sink_m(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                   double grass_top) {
  const int feet[] = {model.link_index("left_foot_link"), model.link_index("right_foot_link")};
  double sum = 0.0;
  int count = 0;
  for (const int foot : feet) {
    if (foot < 0 || static_cast<std::size_t>(foot) >= link_poses.size()) continue;
    const Eigen::Isometry3d& pose = link_poses[static_cast<std::size_t>(foot)];
    for (const CollisionSphere& s : model.links()[static_cast<std::size_t>(foot)].spheres) {
      sum += grass_top - ((pose * s.center).z() - s.radius);
      ++count;
    }
  }
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace stride::sim
