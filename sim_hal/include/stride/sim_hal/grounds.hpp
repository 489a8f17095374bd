// The grounds a world stands on beyond the named ones (issue 41 point 1): a ground drawn per
// reset between the hard and the soft ground (Randomisation::contact_range), and the stud sink
// that documents each ground (sim_hal/models/README.md "Grounds").
//
// Distribution (draw_ground): u uniform in [-range, range) from the world's WorldRng, one
// draw, and only when range > 0 (so that a world without it draws exactly what it drew
// before). Each figure p of the contact that differs between the grounds (layer thickness,
// layer stiffness and damping, stick spring and damper) moves the fraction |u| of the way from
// the world's ground towards the hard ground (u < 0) or the soft one (u > 0) on a log scale:
//   p = p_world (p_target / p_world)^|u|.
// Stiffness spans a factor of 10 between the grounds (2000 to 2e4 N/m per point), so a log
// scale spreads the draws evenly over the ratio rather than crowding them near the stiff end.
// With range 1 on turf the draws cover every ground between hard and soft; the solid base
// (2e4 N/m, 100 N s/m), the friction (its own range) and MuJoCo's solid-ground switch stay the
// world's.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "stride/sim_hal/collision_points.hpp"
#include "stride/sim_hal/world_options.hpp"
#include "stride/sim_hal/world_rng.hpp"

namespace stride::sim {

/// Largest contact_range: 1 reaches the hard and the soft ground.
inline constexpr double kMaxContactRange = 1.0;

/// `world` moved the fraction |u| (u in [-1, 1]) towards ContactOptions::hard() (u < 0) or
/// ::soft() (u > 0), as described above. u = 0 returns `world` unchanged, bit for bit.
ContactOptions ground_between(const ContactOptions& world, double u);

/// The ground of one reset: `world` itself when range <= 0 (no draw), else
/// ground_between(world, u) with u = rng.uniform(-range, range).
ContactOptions draw_ground(const ContactOptions& world, double range, WorldRng& rng);

/// Mean depth [m] of the feet's collision spheres (the eight studs) below the ground's top
/// (`grass_top`, ContactOptions::grass_thickness_m), their lowest points read from the link
/// poses: positive when sunk in. NaN if the feet have no spheres.
double stud_sink_m(const RobotModel& model, const std::vector<Eigen::Isometry3d>& link_poses,
                   double grass_top);

}  // namespace stride::sim
