// Stride's compliant grass contact and ball-robot contact (see contact_law.hpp).
#include "contact_law.hpp"

#include <algorithm>
#include <cmath>

#include "simbody_convert.hpp"
#include "stride/sim_hal/collision_points.hpp"

namespace stride::sim::simbody {

using SimTK::Real;
using SimTK::SpatialVec;
using SimTK::Transform;
using SimTK::Vec3;

void ContactLaw::configure(const RobotModel& model, const ContactOptions& options, int left_foot,
                           int right_foot) {
  options_ = options;
  points_.clear();
  shapes_.clear();
  for (const CollisionPoint& p : collision_points(model)) {
    const int foot = p.link == left_foot ? 1 : p.link == right_foot ? 2 : 0;
    points_.push_back({p.link, to_vec3(p.station), p.radius, foot});
  }
  for (std::size_t l = 0; l < model.links().size(); ++l) {
    const LinkSpec& link = model.links()[l];
    for (const CollisionSphere& s : link.spheres)
      shapes_.push_back(
          {static_cast<int>(l), false, Transform(Vec3(to_vec3(s.center))), Vec3(0), s.radius});
    for (const CollisionBox& b : link.boxes)
      shapes_.push_back(
          {static_cast<int>(l), true, to_transform(b.pose), to_vec3(b.size) / 2, 0.0});
  }
  reach_.assign(model.links().size(), 0.0);
  for (const ContactPoint& p : points_) {
    const auto l = static_cast<std::size_t>(p.link);
    reach_[l] = std::max(reach_[l], p.station.norm() + p.radius + 1e-3);
  }
}

void ContactLaw::clear(Real ball_radius) {
  for (ContactPoint& p : points_) p.touching = false;
  ball_point_ = ContactPoint{-1, Vec3(0), ball_radius, 0};
}

void ContactLaw::ground(ContactPoint& point, const Transform& x, const SpatialVec& v, Real friction,
                        Real h, SpatialVec& out, ContactReport& report) const {
  const ContactOptions& c = options_;
  const Vec3 centre = x * point.station;
  const Vec3 at(centre[0], centre[1], centre[2] - point.radius);  // lowest point of the sphere
  const Real depth = grass_top() - at[2];
  if (depth <= 0.0) {
    point.touching = false;
    return;
  }
  const Vec3 r = at - x.p();
  const Vec3 vel = v[1] + (v[0] % r);
  const Real thick = c.grass_thickness_m;
  Real fn = c.grass_stiffness_n_m * std::min(depth, thick) - c.grass_damping_n_s_m * vel[2];
  if (depth > thick)
    fn += c.ground_stiffness_n_m * (depth - thick) - c.ground_damping_n_s_m * vel[2];
  fn = std::max<Real>(0.0, fn);
  if (!point.touching) {
    point.touching = true;
    point.stretch_x = 0.0;
    point.stretch_y = 0.0;
  }
  point.stretch_x += vel[0] * h;  // the material point's slip over this step
  point.stretch_y += vel[1] * h;
  Real fx = -c.tangential_stiffness_n_m * point.stretch_x - c.tangential_damping_n_s_m * vel[0];
  Real fy = -c.tangential_stiffness_n_m * point.stretch_y - c.tangential_damping_n_s_m * vel[1];
  const Real ft = std::sqrt(fx * fx + fy * fy);
  const Real max_ft = friction * fn;
  if (ft > max_ft) {  // sliding: scale to the cone and cut the stretch to it
    const Real s = ft > 0 ? max_ft / ft : 0.0;
    fx *= s;
    fy *= s;
    point.stretch_x = -fx / c.tangential_stiffness_n_m;
    point.stretch_y = -fy / c.tangential_stiffness_n_m;
  }
  const Vec3 force(fx, fy, fn);
  out[0] += r % force;
  out[1] += force;
  if (point.foot == 1) {
    ++report.left.points_in_contact;
    report.left.force += to_eigen(force);
  } else if (point.foot == 2) {
    ++report.right.points_in_contact;
    report.right.force += to_eigen(force);
  } else if (point.link >= 0) {
    ++report.other_contacts;
  }
}

void ContactLaw::ball_robot(Real radius, const Transform& xb, const SpatialVec& vb,
                            const std::vector<Transform>& link_x,
                            const std::vector<SpatialVec>& link_v, SpatialVec& ball_force,
                            std::vector<SpatialVec>& link_force) const {
  const ContactOptions& c = options_;
  if ((xb.p() - link_x[0].p()).normSqr() > 1.2 * 1.2) return;  // far from the robot
  for (const LinkShape& shape : shapes_) {
    const auto l = static_cast<std::size_t>(shape.link);
    const Transform& xl = link_x[l];
    if ((xb.p() - xl.p()).normSqr() > 0.5 * 0.5) continue;
    const Transform x_shape = xl * shape.pose;
    const Vec3 local = ~x_shape * xb.p();  // ball centre in the shape frame
    Vec3 closest = local;
    Real reach = radius;
    if (shape.is_box) {
      for (int k = 0; k < 3; ++k) closest[k] = std::clamp(local[k], -shape.half[k], shape.half[k]);
    } else {
      closest = Vec3(0);
      reach += shape.radius;
    }
    const Vec3 gap = local - closest;
    const Real dist = gap.norm();
    if (dist >= reach) continue;
    if (dist < 1e-9) continue;  // centre inside the box: no defined normal, skip
    const Vec3 normal = x_shape.R() * (gap / dist);  // from link to ball, world frame
    const Vec3 at = x_shape * closest + (shape.is_box ? Vec3(0) : normal * shape.radius);
    const Vec3 v_ball = vb[1] + (vb[0] % (at - xb.p()));
    const SpatialVec& vl = link_v[l];
    const Vec3 v_link = vl[1] + (vl[0] % (at - xl.p()));
    const Real approach = ~(v_ball - v_link) * normal;
    const Real fn = std::max<Real>(
        0.0, c.ball_robot_stiffness_n_m * (reach - dist) - c.ball_robot_damping_n_s_m * approach);
    const Vec3 force = fn * normal;  // on the ball
    ball_force[0] += (at - xb.p()) % force;
    ball_force[1] += force;
    link_force[l][0] -= (at - xl.p()) % force;
    link_force[l][1] -= force;
  }
}

}  // namespace stride::sim::simbody
