// Stride's contact law (the Simbody engine's): compliant contact of the robot's collision
// points and the ball against a soft grass layer over solid ground, with a stick-slip
// Coulomb friction spring per point, and the ball against the robot's spheres and boxes.
//
// Normal force per point, depth d below the grass top (thickness T):
//   fn = max(0, k_g min(d, T) - c_g vz + [d > T] (k_s (d - T) - c_s vz))
// Tangential: a spring stretched by the slip of the body's material point at the contact (the
// stretch s starts at 0 at touchdown and grows by v h per step of length h, v the material
// point's horizontal velocity) and a damper, f_t = -k_t s - c_t v, clipped to the cone
// |f_t| <= mu fn; when clipped the stretch is cut to the cone, so the point slides at the
// Coulomb force. A body that rolls without slipping (the ball; a foot rocking onto its edge)
// stretches nothing: the spring follows material slip, not the lowest point of a sphere, which
// moves with a rolling ball's centre (issue 29: that slowed a rolling ball to 0.976 m/s where
// v0 / (1 + I / (m r^2)) is 1.201). Figures are the
// seed's Gazebo grass (ContactOptions in world_options.hpp; sim_hal/models/README.md).
#pragma once

#include <Simbody.h>

#include <vector>

#include "stride/sim_hal/physics_engine.hpp"
#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim::simbody {

/// One collision point and its contact memory.
struct ContactPoint {
  int link = -1;  ///< model link index; -1 for the ball
  SimTK::Vec3 station{0};
  SimTK::Real radius = 0.0;
  int foot = 0;  ///< 0 none, 1 left, 2 right
  bool touching = false;
  SimTK::Real stretch_x = 0.0, stretch_y = 0.0;  ///< tangential spring stretch [m]
};

/// A sphere or box of a link, for the ball against the robot.
struct LinkShape {
  int link = -1;
  bool is_box = false;
  SimTK::Transform pose;  ///< shape frame in link frame
  SimTK::Vec3 half{0};    ///< box half extents
  SimTK::Real radius = 0.0;
};

class ContactLaw {
 public:
  /// Collision points and shapes of `model`; the feet are reported apart.
  void configure(const RobotModel& model, const ContactOptions& options, int left_foot,
                 int right_foot);
  /// Forgets every contact (at a reset); the ball's point gets `ball_radius`.
  void clear(SimTK::Real ball_radius);

  const std::vector<ContactPoint>& points() const { return points_; }
  std::vector<ContactPoint>& points() { return points_; }
  ContactPoint& ball_point() { return ball_point_; }
  const ContactPoint& ball_point() const { return ball_point_; }
  const std::vector<LinkShape>& shapes() const { return shapes_; }
  /// Farthest reach of a link's collision points from its origin [m] (plus 1 mm).
  SimTK::Real reach(std::size_t link) const { return reach_[link]; }
  SimTK::Real grass_top() const { return options_.grass_thickness_m; }

  /// Force of the field on `point` of a body at pose `x` moving at `v` (spatial velocity of
  /// the body origin), added to `out` about the body origin; counted in `report`.
  /// `h` is the step [s] over which the stretch grows (one call per step).
  void ground(ContactPoint& point, const SimTK::Transform& x, const SimTK::SpatialVec& v,
              SimTK::Real friction, SimTK::Real h, SimTK::SpatialVec& out,
              ContactReport& report) const;
  /// Ball (radius, pose xb, velocity vb) against every link shape near it; the forces are
  /// added to `ball_force` and to `link_force` (per link, about the link origin).
  void ball_robot(SimTK::Real radius, const SimTK::Transform& xb, const SimTK::SpatialVec& vb,
                  const std::vector<SimTK::Transform>& link_x,
                  const std::vector<SimTK::SpatialVec>& link_v, SimTK::SpatialVec& ball_force,
                  std::vector<SimTK::SpatialVec>& link_force) const;

 private:
  ContactOptions options_;
  std::vector<ContactPoint> points_;
  ContactPoint ball_point_;
  std::vector<LinkShape> shapes_;
  std::vector<SimTK::Real> reach_;
};

}  // namespace stride::sim::simbody
