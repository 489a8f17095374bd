// Closed-form physics through the PhysicsEngine interface, for every engine: a falling box, a
// pendulum (small-amplitude period, large-amplitude energy) and a ball sliding into rolling
// (slowing at mu g while it slides, then rolling at v0 / (1 + I / (m r^2)): its speed and
// where it is after 1 s). No servos: zero torques.
// Tolerances are those of a first-order integrator at the 2 ms step plus the soft contact.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "engine_test_models.hpp"

namespace stride::sim {
namespace {

using engine_test::EngineCase;

class EnginePhysics : public ::testing::TestWithParam<EngineCase> {
 protected:
  std::unique_ptr<PhysicsEngine> build(const EngineModel& model) {
    auto engine = make_physics_engine(GetParam().kind);
    const Status s = engine->build(model);
    EXPECT_TRUE(s) << s.message();
    return engine;
  }
  static void run(PhysicsEngine& engine, double seconds, std::vector<double> torque = {}) {
    std::string reason;
    const auto steps = static_cast<int>(std::lround(seconds / 0.002));
    for (int k = 0; k < steps; ++k)
      ASSERT_EQ(engine.step(torque, reason), WorldStatus::kRunning) << reason;
  }
};

TEST_P(EnginePhysics, ABoxFallsFreelyUntilItTouches) {
  auto robot = engine_test::load_urdf(engine_test::kBoxUrdf);
  const EngineModel model = engine_test::neutral_model(*robot);
  auto engine = build(model);
  EngineStart start;
  start.torso_position = Eigen::Vector3d(0.3, -0.2, 1.0);
  ASSERT_TRUE(engine->start(start));
  const double t = 0.3;  // bottom face at 1 - 0.05 - 0.44 = 0.51 m: still in the air
  run(*engine, t, {});
  const double g = model.gravity_mps2, h = model.step_s;
  const Eigen::Vector3d p = engine->link_pose(0).translation();
  EXPECT_NEAR(engine->time_s(), t, 1e-12);
  EXPECT_NEAR(p.z(), 1.0 - 0.5 * g * t * t, g * h * t);  // first-order integrator: g h t / 2
  EXPECT_NEAR(p.x(), 0.3, 1e-12);
  EXPECT_NEAR(p.y(), -0.2, 1e-12);
  EXPECT_NEAR(engine->torso_velocity().z(), -g * t, 1e-9);
  EXPECT_NEAR(engine->torso_acceleration().z(), -g, 1e-9);
  const ContactReport c = engine->contacts();
  EXPECT_EQ(c.other_contacts, 0);
  // ... then it lands and comes to rest on the grass, upright.
  run(*engine, 2.0, {});
  EXPECT_LT(engine->torso_velocity().norm(), 1e-2);
  EXPECT_GT(engine->link_pose(0).linear()(2, 2), 0.999);
  const double bottom = engine->link_pose(0).translation().z() - 0.05;
  EXPECT_LT(bottom, model.contact.grass_thickness_m);
  EXPECT_GT(bottom, model.contact.grass_thickness_m - 0.01);
  EXPECT_EQ(engine->contacts().other_contacts, 4);  // the four bottom corners
}

// The case Simbody misses today (run on MuJoCo only until it is fixed, then add kSimbody):
// the large swing: Simbody loses 5.7 % of the energy in 3 s (MuJoCo under 3 %).
// (The sliding ball passes on both since issue 29: Stride's contact law anchored the stick
// spring at the sphere's geometric lowest point, which moves with the centre while the ball
// rolls, and the ball rolled on at 0.976 m/s instead of 1.201 m/s; the spring now stretches
// with the material point's slip.)
class EnginePhysicsSimbodyMisses : public EnginePhysics {};

/// The pendulum's energy in the world: the bob's height above its lowest point and the arm's
/// world angular speed (the base tilts and rocks a little on the grass).
double pendulum_energy(const PhysicsEngine& engine, double g) {
  const Eigen::Isometry3d arm = engine.link_pose(1);
  const Eigen::Vector3d bob = arm * Eigen::Vector3d(0, 0, -engine_test::kPendulumLength);
  const double height = bob.z() - arm.translation().z() + engine_test::kPendulumLength;
  const double w = engine.joint_speed(0) + engine.torso_angular_velocity().y();
  return 0.5 * engine_test::kPendulumInertia * w * w + engine_test::kPendulumMass * g * height;
}

TEST_P(EnginePhysics, APendulumSwingsWithItsSmallAmplitudePeriod) {
  auto robot = engine_test::load_urdf(engine_test::kPendulumUrdf);
  const EngineModel model = engine_test::neutral_model(*robot);
  auto engine = build(model);
  EngineStart start;
  start.joint_angles = {0.05};
  start.torso_position = Eigen::Vector3d(0, 0, model.contact.grass_thickness_m + 0.05);
  ASSERT_TRUE(engine->start(start));
  run(*engine, 0.5, {0.0});  // the base settles into the grass
  // Upward zero crossings of the angle over 4 s.
  std::vector<double> crossings;
  double last = engine->joint_angle(0);
  std::string reason;
  for (int k = 0; k < 2000; ++k) {
    ASSERT_EQ(engine->step({0.0}, reason), WorldStatus::kRunning) << reason;
    const double q = engine->joint_angle(0);
    if (last < 0.0 && q >= 0.0)  // linear interpolation of the crossing time
      crossings.push_back(engine->time_s() - model.step_s * q / (q - last));
    last = q;
  }
  ASSERT_GE(crossings.size(), 3U);
  const double period =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double expected =
      2.0 * std::numbers::pi *
      std::sqrt(engine_test::kPendulumInertia /
                (engine_test::kPendulumMass * model.gravity_mps2 * engine_test::kPendulumLength));
  EXPECT_NEAR(period, expected, 0.01 * expected) << "closed form " << expected << " s";
}

TEST_P(EnginePhysicsSimbodyMisses, ALargeSwingKeepsItsEnergy) {
  auto robot = engine_test::load_urdf(engine_test::kPendulumUrdf);
  const EngineModel model = engine_test::neutral_model(*robot);
  auto engine = build(model);
  EngineStart start;
  start.joint_angles = {1.5};  // 86 degrees
  start.torso_position = Eigen::Vector3d(0, 0, model.contact.grass_thickness_m + 0.05);
  ASSERT_TRUE(engine->start(start));
  const double e0 = pendulum_energy(*engine, model.gravity_mps2);
  double highest = 0.0;
  std::string reason;
  for (int k = 0; k < 1500; ++k) {  // 3 s, about 3 swings
    ASSERT_EQ(engine->step({0.0}, reason), WorldStatus::kRunning) << reason;
    if (k > 1000) highest = std::max(highest, std::abs(engine->joint_angle(0)));
  }
  const double e = pendulum_energy(*engine, model.gravity_mps2);
  // The base rocks on the grass, whose damping takes a little energy (Simbody: amplitude
  // 1.469 rad after 2-3 s, MuJoCo 1.48).
  EXPECT_NEAR(e, e0, 0.03 * e0);
  EXPECT_NEAR(highest, 1.5, 0.04);
}

TEST_P(EnginePhysics, ASlidingBallDeceleratesAtMuGThenRolls) {
  auto robot = engine_test::load_urdf(engine_test::kBoxUrdf);
  for (double mu : {0.3, 0.6}) {
    EngineModel model = engine_test::neutral_model(*robot);
    model.friction = mu;
    model.ball.present = true;
    model.ball.rolling_damping = 0.0;
    auto engine = build(model);
    EngineStart start;
    start.torso_position = Eigen::Vector3d(-2, 0, 0.07);  // the box out of the way
    const double r = model.ball.radius_m;
    const double v0 = 2.0;
    // Resting on the grass spring (its sink m g / k) so that it starts in contact.
    start.ball_position = Eigen::Vector3d(
        0, 0,
        model.contact.grass_thickness_m + r -
            model.ball.mass_kg * model.gravity_mps2 / model.contact.grass_stiffness_n_m);
    start.ball_velocity = Eigen::Vector3d(v0, 0, 0);
    ASSERT_TRUE(engine->start(start));
    const double g = model.gravity_mps2;
    // Slides for t* = v0 / (mu g (1 + m r^2 / I)) (0.27 s at mu 0.3, 0.14 s at 0.6), slowing
    // at mu g while friction spins it up, then rolls at v0 / (1 + I / (m r^2)).
    const double ratio = model.ball.inertia_kg_m2 / (model.ball.mass_kg * r * r);
    const double t_roll = v0 / (mu * g * (1.0 + 1.0 / ratio));
    const double rolling = v0 / (1.0 + ratio);
    run(*engine, 1.0, {});
    EXPECT_NEAR(engine->ball_velocity().x(), rolling, 0.02 * rolling) << "mu " << mu;
    // Where it is after 1 s tells the friction's work: 5.4 cm apart for mu 0.3 and 0.6.
    const double x = v0 * t_roll - 0.5 * mu * g * t_roll * t_roll + rolling * (1.0 - t_roll);
    EXPECT_NEAR(engine->ball_position().x(), x, 0.01) << "mu " << mu;
    EXPECT_NEAR(engine->ball_velocity().y(), 0.0, 1e-6);
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, EnginePhysicsSimbodyMisses,
                         ::testing::Values(EngineCase{EngineKind::kMujoco}),
                         [](const ::testing::TestParamInfo<EngineCase>& p) {
                           return std::string(to_string(p.param.kind));
                         });

INSTANTIATE_TEST_SUITE_P(Engines, EnginePhysics,
                         ::testing::Values(EngineCase{EngineKind::kSimbody},
                                           EngineCase{EngineKind::kMujoco}),
                         [](const ::testing::TestParamInfo<EngineCase>& p) {
                           return std::string(to_string(p.param.kind));
                         });

}  // namespace
}  // namespace stride::sim
