// PhysicsEngine on Simbody (see simbody_engine.hpp).
#include "simbody_engine.hpp"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contact_law.hpp"
#include "semi_explicit_euler.hpp"
#include "simbody_convert.hpp"

namespace stride::sim::simbody {

using SimTK::Real;
using SimTK::SpatialVec;
using SimTK::Stage;
using SimTK::Transform;
using SimTK::Vec3;

namespace {

/// Inertia about the body origin with reflected rotor inertia J about `axis` added. Simbody
/// checks that an inertia is physically realisable (triangle inequality); a rotor inertia
/// reflected through a gearbox is not, so the smallest perpendicular inertia that keeps the
/// sum valid is added with it (zero for most links).
SimTK::Inertia add_rotor_inertia(const SimTK::Inertia& body, const Vec3& axis, Real j) {
  if (j <= 0.0) return body;
  const SimTK::Mat33 aat = SimTK::outer(axis, axis);
  const SimTK::Mat33 perp = SimTK::Mat33(1) - aat;
  const SimTK::Mat33 base = body.toMat33();
  for (Real p = 0.0;; p = p == 0.0 ? j / 64 : p * 2) {
    const SimTK::Mat33 sum = base + j * aat + p * perp;
    const SimTK::SymMat33 sym(sum(0, 0), sum(1, 0), sum(1, 1), sum(2, 0), sum(2, 1), sum(2, 2));
    if (SimTK::Inertia::isValidInertiaMatrix(sym)) return SimTK::Inertia(sym);
    if (p > 4 * j) return body;  // cannot happen for a valid body inertia
  }
}

class SimbodyEngine;

// A Force that applies what SimbodyEngine::compute_forces() computed for this step.
class AppliedForces final : public SimTK::Force::Custom::Implementation {
 public:
  explicit AppliedForces(const SimbodyEngine* engine) : engine_(engine) {}
  void calcForce(const SimTK::State& state, SimTK::Vector_<SpatialVec>& body_forces,
                 SimTK::Vector_<Vec3>&, SimTK::Vector& mobility_forces) const override;
  Real calcPotentialEnergy(const SimTK::State&) const override { return 0.0; }

 private:
  const SimbodyEngine* engine_;
};

class SimbodyEngine final : public PhysicsEngine {
 public:
  Status build(const EngineModel& model) override;
  Status start(const EngineStart& start) override;
  double joint_angle(std::size_t joint) const override { return q_data()[joint_q_[joint]]; }
  double joint_speed(std::size_t joint) const override { return u_data()[joint_u_[joint]]; }
  WorldStatus step(const std::vector<double>& joint_torque, std::string& reason) override;
  double time_s() const override { return state_.getTime(); }
  Eigen::Isometry3d link_pose(std::size_t link) const override;
  Eigen::Vector3d torso_velocity() const override;
  Eigen::Vector3d torso_angular_velocity() const override;
  Eigen::Vector3d torso_acceleration() const override { return to_eigen(torso_accel_); }
  Eigen::Vector3d robot_center_of_mass() const override;
  Eigen::Vector3d ball_position() const override;
  Eigen::Vector3d ball_velocity() const override;
  ContactReport contacts() const override { return report_; }
  std::uint64_t hash(std::uint64_t seed) const override;
  void set_joint_speed(std::size_t joint, double speed) override;
  void set_torso_force(const Eigen::Vector3d& force) override { torso_force_ = to_vec3(force); }

 private:
  friend class AppliedForces;
  const Real* q_data() const { return matter_->getQ(state_).getContiguousScalarData(); }
  const Real* u_data() const { return matter_->getU(state_).getContiguousScalarData(); }
  void realize(Stage stage) const { system_->realize(state_, stage); }
  void compute_forces();

  EngineModel model_;
  std::unique_ptr<SimTK::MultibodySystem> system_;
  std::unique_ptr<SimTK::SimbodyMatterSubsystem> matter_;
  std::vector<SimTK::MobilizedBody> bodies_;  ///< per model link
  SimTK::MobilizedBody ball_;
  bool has_ball_ = false;
  mutable SimTK::State state_;          ///< realized lazily by the const queries
  std::vector<int> joint_q_, joint_u_;  ///< per model joint: index into q and u
  std::vector<int> body_index_;         ///< per model link: its MobilizedBodyIndex
  int ball_index_ = 0;
  SemiExplicitEuler integrator_;
  std::int64_t steps_ = 0;

  ContactLaw contact_;
  const std::vector<double>* torque_ = nullptr;  ///< this step's joint torques
  std::vector<SpatialVec> body_force_;           ///< per link, accumulated each step
  std::vector<Real> link_mass_;                  ///< after randomisation [kg]
  std::vector<Vec3> link_com_;                   ///< link frame [m]
  std::vector<Transform> link_x_;                ///< per step: link poses
  std::vector<SpatialVec> link_v_;               ///< per step: link velocities
  SpatialVec ball_force_{Vec3(0), Vec3(0)};
  ContactReport report_;
  Vec3 torso_accel_{0};
  Vec3 torso_force_{0};  ///< external push on the root link's centre of mass (world frame)
};

void AppliedForces::calcForce(const SimTK::State&, SimTK::Vector_<SpatialVec>& body_forces,
                              SimTK::Vector_<Vec3>&, SimTK::Vector& mobility_forces) const {
  const SimbodyEngine& e = *engine_;
  if (e.torque_)
    for (std::size_t j = 0; j < e.joint_u_.size(); ++j)
      mobility_forces[e.joint_u_[j]] += (*e.torque_)[j];
  for (std::size_t l = 0; l < e.body_index_.size(); ++l)
    body_forces[e.body_index_[l]] += e.body_force_[l];
  if (e.has_ball_) body_forces[e.ball_index_] += e.ball_force_;
}

Status SimbodyEngine::build(const EngineModel& model) {
  if (!model.robot) return Status::error("simbody: no robot model");
  model_ = model;
  const RobotModel& robot = *model.robot;
  try {
    bodies_.clear();
    ball_ = SimTK::MobilizedBody();
    matter_.reset();
    system_ = std::make_unique<SimTK::MultibodySystem>();
    matter_ = std::make_unique<SimTK::SimbodyMatterSubsystem>(*system_);
    SimTK::GeneralForceSubsystem forces(*system_);
    SimTK::Force::Custom(forces, new AppliedForces(this));
    link_mass_.assign(robot.links().size(), 0.0);
    link_com_.assign(robot.links().size(), Vec3(0));
    for (std::size_t l = 0; l < robot.links().size(); ++l) {
      const LinkSpec& link = robot.links()[l];
      const Real scale = model.link_mass_scale.at(l);
      const Real mass = scale * link.mass;
      const Vec3 com =
          to_vec3(l == 0 ? Eigen::Vector3d(link.com + model.root_com_shift) : link.com);
      link_mass_[l] = mass;
      link_com_[l] = com;
      SimTK::Mat33 inertia;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) inertia(r, c) = scale * link.inertia(r, c);
      SimTK::Inertia about_origin = SimTK::Inertia(inertia).shiftFromMassCenter(com, mass);
      if (link.parent_joint < 0) {
        SimTK::Body::Rigid body(SimTK::MassProperties(mass, com, about_origin));
        bodies_.push_back(
            SimTK::MobilizedBody::Free(matter_->Ground(), Transform(), body, Transform()));
        continue;
      }
      const auto j = static_cast<std::size_t>(link.parent_joint);
      const JointSpec& joint = robot.joints()[j];
      const Vec3 axis = to_vec3(joint.axis);
      about_origin = add_rotor_inertia(about_origin, axis, model.joint_armature.at(j));
      SimTK::Body::Rigid body(SimTK::MassProperties(mass, com, about_origin));
      const SimTK::Rotation z_to_axis(SimTK::UnitVec3(axis), SimTK::ZAxis);
      const Transform inboard(to_rotation(joint.origin.linear()) * z_to_axis,
                              to_vec3(joint.origin.translation()));
      const Transform outboard(z_to_axis, Vec3(0));
      bodies_.push_back(SimTK::MobilizedBody::Pin(
          bodies_[static_cast<std::size_t>(joint.parent_link)], inboard, body, outboard));
    }
    has_ball_ = model.ball.present;
    if (has_ball_) {
      const BallOptions& b = model.ball;
      SimTK::Body::Rigid body(
          SimTK::MassProperties(b.mass_kg, Vec3(0), SimTK::Inertia(b.inertia_kg_m2)));
      ball_ = SimTK::MobilizedBody::Free(matter_->Ground(), Transform(), body, Transform());
    }
    system_->realizeTopology();
    state_ = system_->getDefaultState();
    system_->realizeModel(state_);
  } catch (const std::exception& e) {
    return Status::error(std::string("building the Simbody system failed: ") + e.what());
  }
  joint_q_.clear();
  joint_u_.clear();
  body_index_.clear();
  for (const SimTK::MobilizedBody& b : bodies_)
    body_index_.push_back(static_cast<int>(b.getMobilizedBodyIndex()));
  if (has_ball_) ball_index_ = static_cast<int>(ball_.getMobilizedBodyIndex());
  for (const JointSpec& j : robot.joints()) {
    const SimTK::MobilizedBody& mb = bodies_[static_cast<std::size_t>(j.child_link)];
    joint_q_.push_back(static_cast<int>(mb.getFirstQIndex(state_)));
    joint_u_.push_back(static_cast<int>(mb.getFirstUIndex(state_)));
  }
  std::vector<int> quaternion_q{static_cast<int>(bodies_[0].getFirstQIndex(state_))};
  if (has_ball_) quaternion_q.push_back(static_cast<int>(ball_.getFirstQIndex(state_)));
  integrator_.configure(state_, std::move(quaternion_q));
  contact_.configure(robot, model.contact, model.left_foot, model.right_foot);
  body_force_.assign(robot.links().size(), SpatialVec(Vec3(0), Vec3(0)));
  link_x_.assign(robot.links().size(), Transform());
  link_v_.assign(robot.links().size(), SpatialVec(Vec3(0), Vec3(0)));
  return Status::ok();
}

Status SimbodyEngine::start(const EngineStart& start) {
  const RobotModel& robot = *model_.robot;
  if (start.joint_angles.size() != robot.joints().size())
    return Status::error("simbody: start needs one angle per joint");
  SimTK::State& s = state_;
  s.updQ() = 0.0;
  s.updU() = 0.0;
  for (std::size_t j = 0; j < robot.joints().size(); ++j)
    bodies_[static_cast<std::size_t>(robot.joints()[j].child_link)].setOneQ(s, 0,
                                                                            start.joint_angles[j]);
  if (start.joint_speeds.size() == robot.joints().size())
    for (std::size_t j = 0; j < robot.joints().size(); ++j)
      bodies_[static_cast<std::size_t>(robot.joints()[j].child_link)].setOneU(
          s, 0, start.joint_speeds[j]);
  const Eigen::Quaterniond& o = start.torso_orientation;
  SimTK::Rotation rot(SimTK::Quaternion(o.w(), o.x(), o.y(), o.z()));
  if (start.tilt_angle != 0.0)
    rot = SimTK::Rotation(start.tilt_angle, SimTK::UnitVec3(to_vec3(start.tilt_axis))) * rot;
  bodies_[0].setQToFitTransform(s, Transform(rot, to_vec3(start.torso_position)));
  bodies_[0].setUToFitAngularVelocity(s, to_vec3(start.torso_angular_velocity));
  bodies_[0].setUToFitLinearVelocity(s, to_vec3(start.torso_velocity));
  if (has_ball_) {
    ball_.setQToFitTransform(s, Transform(to_vec3(start.ball_position)));
    ball_.setUToFitLinearVelocity(s, to_vec3(start.ball_velocity));
  }
  contact_.clear(model_.ball.radius_m);
  report_ = {};
  torso_accel_ = Vec3(0);
  torso_force_ = Vec3(0);
  torque_ = nullptr;
  steps_ = 0;
  s.updTime() = 0.0;
  try {
    realize(Stage::Velocity);
  } catch (const std::exception& e) {
    return Status::error(std::string("simbody: placing the robot failed: ") + e.what());
  }
  return Status::ok();
}

void SimbodyEngine::compute_forces() {
  report_ = {};
  // Body kinematics fetched once per link; links far above the grass are skipped whole.
  for (std::size_t l = 0; l < bodies_.size(); ++l) {
    link_x_[l] = bodies_[l].getBodyTransform(state_);
    link_v_[l] = bodies_[l].getBodyVelocity(state_);
  }
  // Gravity at each centre of mass (applied here rather than by Force::Gravity, whose cache
  // crashed on this Simbody build when driven by the fixed-step loop).
  const Real g = model_.gravity_mps2;
  for (std::size_t l = 0; l < body_force_.size(); ++l) {
    const Vec3 weight(0, 0, -g * link_mass_[l]);
    const Vec3 r = link_x_[l].R() * link_com_[l];
    body_force_[l] = SpatialVec(r % weight, weight);
  }
  if (torso_force_ != Vec3(0)) {  // a push (SimWorld's TorsoPush) at the trunk's centre of mass
    body_force_[0][0] += (link_x_[0].R() * link_com_[0]) % torso_force_;
    body_force_[0][1] += torso_force_;
  }
  ball_force_ = SpatialVec(Vec3(0), Vec3(0, 0, has_ball_ ? -g * model_.ball.mass_kg : 0.0));
  for (ContactPoint& point : contact_.points()) {
    const auto l = static_cast<std::size_t>(point.link);
    if (link_x_[l].p()[2] - contact_.reach(l) > contact_.grass_top()) {
      point.touching = false;
      continue;
    }
    contact_.ground(point, link_x_[l], link_v_[l], model_.friction, model_.step_s, body_force_[l],
                    report_);
  }
  if (has_ball_) {
    const SpatialVec& vb = ball_.getBodyVelocity(state_);
    const Transform& xb = ball_.getBodyTransform(state_);
    ContactReport ball_report;  // the ball's own field contact is not the robot's
    contact_.ground(contact_.ball_point(), xb, vb, model_.friction, model_.step_s, ball_force_,
                    ball_report);
    ball_force_[0] -= model_.ball.rolling_damping * vb[0];
    contact_.ball_robot(model_.ball.radius_m, xb, vb, link_x_, link_v_, ball_force_, body_force_);
  }
}

WorldStatus SimbodyEngine::step(const std::vector<double>& joint_torque, std::string& reason) {
  try {
    realize(Stage::Velocity);
    torque_ = &joint_torque;
    compute_forces();
    realize(Stage::Acceleration);
    torso_accel_ = bodies_[0].getBodyOriginAcceleration(state_);
    integrator_.step(*matter_, state_, model_.step_s, steps_);
    torque_ = nullptr;
  } catch (const std::exception& e) {
    torque_ = nullptr;
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    reason =
        "Simbody failed at t=" + std::to_string(state_.getTime()) + " s: " + what.substr(0, 200);
    return WorldStatus::kIntegratorFailure;
  }
  ++steps_;
  return check_state(q_data(), static_cast<std::size_t>(state_.getNQ()), u_data(),
                     static_cast<std::size_t>(state_.getNU()), model_.max_speed, state_.getTime(),
                     reason);
}

Eigen::Isometry3d SimbodyEngine::link_pose(std::size_t link) const {
  realize(Stage::Position);
  return to_isometry(bodies_[link].getBodyTransform(state_));
}

Eigen::Vector3d SimbodyEngine::torso_velocity() const {
  realize(Stage::Velocity);
  return to_eigen(bodies_[0].getBodyOriginVelocity(state_));
}

Eigen::Vector3d SimbodyEngine::torso_angular_velocity() const {
  realize(Stage::Velocity);
  return to_eigen(bodies_[0].getBodyAngularVelocity(state_));
}

Eigen::Vector3d SimbodyEngine::robot_center_of_mass() const {
  realize(Stage::Position);
  Eigen::Vector3d com = to_eigen(matter_->calcSystemMassCenterLocationInGround(state_));
  if (!has_ball_) return com;
  // calcSystemMassCenter includes the ball: take the robot alone.
  const Real mb = model_.ball.mass_kg;
  Real mt = 0.0;
  for (Real m : link_mass_) mt += m;
  return (com * (mt + mb) - ball_position() * mb) / mt;
}

Eigen::Vector3d SimbodyEngine::ball_position() const {
  if (!has_ball_) return Eigen::Vector3d::Zero();
  realize(Stage::Position);
  return to_eigen(ball_.getBodyOriginLocation(state_));
}

Eigen::Vector3d SimbodyEngine::ball_velocity() const {
  if (!has_ball_) return Eigen::Vector3d::Zero();
  realize(Stage::Velocity);
  return to_eigen(ball_.getBodyOriginVelocity(state_));
}

std::uint64_t SimbodyEngine::hash(std::uint64_t h) const {
  const Real t = state_.getTime();
  h = fnv1a(h, &t, sizeof t);
  h = fnv1a(h, q_data(), sizeof(Real) * static_cast<std::size_t>(state_.getNQ()));
  h = fnv1a(h, u_data(), sizeof(Real) * static_cast<std::size_t>(state_.getNU()));
  auto fold = [&h](const ContactPoint& p) {
    const unsigned char touching = p.touching ? 1 : 0;
    h = fnv1a(h, &touching, 1);
    h = fnv1a(h, &p.stretch_x, sizeof(Real));
    h = fnv1a(h, &p.stretch_y, sizeof(Real));
  };
  for (const ContactPoint& p : contact_.points()) fold(p);
  fold(contact_.ball_point());
  return h;
}

void SimbodyEngine::set_joint_speed(std::size_t joint, double speed) {
  const RobotModel& robot = *model_.robot;
  if (joint >= robot.joints().size()) return;
  bodies_[static_cast<std::size_t>(robot.joints()[joint].child_link)].setOneU(state_, 0, speed);
}

}  // namespace

std::unique_ptr<PhysicsEngine> make_simbody_engine() {
  return std::make_unique<SimbodyEngine>();
}

}  // namespace stride::sim::simbody
