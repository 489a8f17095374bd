// Stride's contact law (the Simbody engine's, sim_hal/src/simbody/contact_law.hpp), issue 29
// point 1: a stud grazing the grass carries tangential force in proportion to its own normal
// force, the stick spring never exceeds mu N of that stud and stretches only with the stud's
// slip (a rolling stud stretches nothing), and the layer's depth is where the solid ground
// starts.
#include <gtest/gtest.h>

#include <cmath>

#include "simbody/contact_law.hpp"
#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim::simbody {
namespace {

struct Stud {
  ContactLaw law;
  ContactPoint point;
  RobotModel model;

  explicit Stud(const ContactOptions& options) {
    EXPECT_TRUE(RobotModel::load_file(RobotModel::igus_path(), model));
    law.configure(model, options, -1, -1);
    point.link = 1;
    point.radius = 0.005;
    point.foot = 1;
  }
  static constexpr double kStep = 0.001;  ///< [s]
  /// Force on the stud with its lowest point `depth` below the grass top at x = `x`, its
  /// centre moving at (vx, 0, vz) and spinning at `spin_y` rad/s about y, over one step kStep.
  SimTK::Vec3 force(double depth, double x, double vx, double vz = 0.0, double spin_y = 0.0) {
    const SimTK::Transform pose(SimTK::Vec3(x, 0.0, law.grass_top() - depth + point.radius));
    const SimTK::SpatialVec velocity(SimTK::Vec3(0, spin_y, 0), SimTK::Vec3(vx, 0.0, vz));
    SimTK::SpatialVec out(SimTK::Vec3(0), SimTK::Vec3(0));
    ContactReport report;
    law.ground(point, pose, velocity, 1.0, kStep, out, report);
    return out[1];
  }
};

TEST(ContactLaw, AGrazingStudSlidesAtMuTimesItsOwnNormalForce) {
  for (const ContactOptions& options : {ContactOptions::seed(), ContactOptions::turf()}) {
    Stud stud(options);
    // Touches down 1 mm deep and is dragged 2 cm at 0.3 m/s: the stick spring would pull
    // back with k_t x, but never with more than mu N = 1.5 N of this stud.
    double x = 0.0;
    for (int k = 0; k <= 66; ++k, x += 0.3 * Stud::kStep) {
      const SimTK::Vec3 f = stud.force(0.001, x, 0.3);
      EXPECT_NEAR(f[2], options.grass_stiffness_n_m * 0.001, 1e-9);
      const double tangential = std::hypot(f[0], f[1]);
      EXPECT_LE(tangential, 1.0 * f[2] + 1e-9) << "step " << k;
      if (k > 15) {  // sliding by now (k_t x reaches mu N within 5 mm)
        EXPECT_NEAR(tangential, f[2], 1e-9) << "step " << k;
      }
    }
    // Lifted out of the grass: no force, and the contact forgets its stretch.
    EXPECT_EQ(stud.force(-0.001, x, 0.3).norm(), 0.0);
    EXPECT_FALSE(stud.point.touching);
    // A stud barely in the grass carries almost nothing however far it is dragged.
    stud.force(1e-5, 0.0, 0.0);
    for (int k = 0; k < 100; ++k) stud.force(1e-5, 0.0003 * k, 0.3);
    const SimTK::Vec3 f = stud.force(1e-5, 0.03, 0.3);
    EXPECT_LE(std::hypot(f[0], f[1]), options.grass_stiffness_n_m * 1e-5 + 1e-12);
  }
}

TEST(ContactLaw, AStickingStudHoldsWithItsStickSpring) {
  for (const ContactOptions& options : {ContactOptions::seed(), ContactOptions::turf()}) {
    Stud stud(options);
    stud.force(0.005, 0.0, 0.0);  // touches down at x = 0
    // Slips at 0.1 m/s for one 1 ms step: stretched 0.1 mm, and damped.
    SimTK::Vec3 f = stud.force(0.005, 1e-4, 0.1);
    EXPECT_NEAR(f[0],
                -options.tangential_stiffness_n_m * 1e-4 - options.tangential_damping_n_s_m * 0.1,
                1e-9);
    f = stud.force(0.005, 1e-4, 0.0);  // at rest: the spring holds it
    EXPECT_NEAR(f[0], -options.tangential_stiffness_n_m * 1e-4, 1e-9);
  }
}

TEST(ContactLaw, ARollingStudStretchesNothing) {
  for (const ContactOptions& options : {ContactOptions::seed(), ContactOptions::turf()}) {
    Stud stud(options);
    // Rolls without slipping at 0.5 m/s for 50 ms (spin v / r): its contact point does not
    // slip, so however far its centre moves the spring stays slack. The slipping stud beside
    // it, moved as far, is held back by mu N.
    const double v = 0.5, spin = v / stud.point.radius;
    Stud sliding(options);
    for (int k = 0; k < 50; ++k) {
      const double x = v * Stud::kStep * k;
      EXPECT_NEAR(stud.force(0.002, x, v, 0.0, spin)[0], 0.0, 1e-12) << "step " << k;
      if (k > 20)
        EXPECT_NEAR(sliding.force(0.002, x, v)[0], -options.grass_stiffness_n_m * 0.002, 1e-9);
      else
        sliding.force(0.002, x, v);
    }
  }
}

TEST(ContactLaw, TheSolidGroundStartsAtTheLayersDepth) {
  for (const ContactOptions& options : {ContactOptions::seed(), ContactOptions::turf()}) {
    Stud stud(options);
    const double t = options.grass_thickness_m;
    EXPECT_NEAR(stud.force(t, 0, 0)[2], options.grass_stiffness_n_m * t, 1e-9);
    EXPECT_NEAR(stud.force(t + 0.001, 0, 0)[2],
                options.grass_stiffness_n_m * t + options.ground_stiffness_n_m * 0.001, 1e-9);
  }
  // Turf: a foot in single support (a quarter of the robot's 63.4 N on each stud) stands on the
  // solid ground 5.4 mm deep; on the seed's grass it sinks 10.6 mm.
  const double per_stud = 6.4601 * 9.81 / 4;
  const ContactOptions turf = ContactOptions::turf(), seed = ContactOptions::seed();
  const double turf_depth =
      turf.grass_thickness_m +
      (per_stud - turf.grass_stiffness_n_m * turf.grass_thickness_m) / turf.ground_stiffness_n_m;
  EXPECT_NEAR(turf_depth, 0.0054, 0.0001);
  EXPECT_NEAR(per_stud / seed.grass_stiffness_n_m, 0.0106, 0.0001);
}

}  // namespace
}  // namespace stride::sim::simbody
