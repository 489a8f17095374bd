// SimWorld: Simbody multibody system, servo/contact/IMU models and the fixed-step integrator.
#include "stride/sim_hal/sim_world.hpp"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "stride/sim_hal/physics_engine.hpp"
#include "stride/sim_hal/world_rng.hpp"

namespace stride::sim {

using SimTK::Real;
using SimTK::SpatialVec;
using SimTK::Stage;
using SimTK::Transform;
using SimTK::Vec3;

namespace {

Vec3 to_vec3(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}
Eigen::Vector3d to_eigen(const Vec3& v) {
  return {v[0], v[1], v[2]};
}

SimTK::Rotation to_rotation(const Eigen::Matrix3d& m) {
  SimTK::Mat33 mat;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) mat(r, c) = m(r, c);
  return SimTK::Rotation(mat, true);
}

Eigen::Isometry3d to_isometry(const Transform& x) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out.linear()(r, c) = x.R().asMat33()(r, c);
  out.translation() = to_eigen(x.p());
  return out;
}

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

struct ContactPoint {
  int link = -1;  ///< model link index; -1 for the ball
  Vec3 station{0};
  Real radius = 0.0;
  int foot = 0;  ///< 0 none, 1 left, 2 right
  bool touching = false;
  Real anchor_x = 0.0, anchor_y = 0.0;
};

struct LinkShape {  ///< for ball-robot contact
  int link = -1;
  bool is_box = false;
  Transform pose;  ///< shape frame in link frame
  Vec3 half{0};    ///< box half extents
  Real radius = 0.0;
};

}  // namespace

// ----------------------------------------------------------------------------------------------
struct SimWorld::Impl {
  WorldOptions options;
  RobotModel model;
  WorldRng rng;

  // Simbody system (rebuilt by build()).
  std::unique_ptr<SimTK::MultibodySystem> system;
  std::unique_ptr<SimTK::SimbodyMatterSubsystem> matter;
  std::vector<SimTK::MobilizedBody> bodies;  ///< per model link
  SimTK::MobilizedBody ball;
  bool has_ball = false;
  SimTK::State state;
  SimTK::Vector u_next, qdot;
  std::vector<int> quaternion_q;  ///< first q index of each free body's quaternion
  std::vector<int> joint_q, joint_u;
  std::vector<int> body_index;  ///< per model link: its MobilizedBodyIndex
  int ball_index = 0;           ///< per model joint: index into the matter's q and u

  // Per model joint.
  std::vector<int> joint_servo;  ///< servo index or -1
  std::vector<Real> joint_tau;
  // Per servo.
  std::array<int, hal::kServoCount> servo_joint{};
  std::array<ServoModel, hal::kServoCount> servos{};
  std::array<MxServo, hal::kServoCount> mx_servos{};  ///< ServoLaw::kIdentified
  bool identified = false;
  /// Identified law: last step's joint torque, for the external torque estimate.
  std::array<Real, hal::kServoCount> last_torque{};
  std::array<fw::ServoModel, hal::kServoCount> servo_models{};
  std::array<hal::ServoCommand, hal::kServoCount> written{};
  std::array<hal::ServoCommand, hal::kServoCount> delayed{};
  bool torque_enable = true;

  // Contact.
  std::vector<ContactPoint> points;
  ContactPoint ball_point;  ///< the ball against the field
  std::vector<LinkShape> shapes;
  std::vector<SpatialVec> body_force;  ///< per model link, accumulated each step
  std::vector<Real> link_mass;         ///< after randomisation [kg]
  std::vector<Vec3> link_com;          ///< link frame [m]
  std::vector<Real> link_reach;        ///< farthest contact point from the link origin [m]
  std::vector<Transform> link_x;       ///< per step: link poses
  std::vector<SpatialVec> link_v;      ///< per step: link velocities
  std::vector<char> link_near;         ///< per step: link may touch the field
  SpatialVec ball_force{Vec3(0), Vec3(0)};
  int left_foot = -1, right_foot = -1;
  FootContact left_contact, right_contact;
  int other_contacts = 0;

  // Randomised per reset.
  Real friction = 1.0;
  std::vector<Real> mass_scale;
  std::array<Real, hal::kServoCount> strength{};
  bool latency = false;
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero(), gyro_bias = Eigen::Vector3d::Zero();

  // Time and status.
  Real h = 0.002;
  int steps_per_period = 5;
  std::int64_t steps = 0;
  std::int64_t periods = 0;
  WorldStatus status = WorldStatus::kRunning;
  std::string reason;
  Vec3 torso_accel{0};  ///< acceleration of the torso origin at the last step [m/s^2]
  ImuReading imu;
  ImuModel imu_model;  ///< used unless options.imu.chain is ideal
  bool imu_chain = false;

  Status configure();
  void build();
  void compute_forces();
  void ground_contact(ContactPoint& point, const Transform& x, const SpatialVec& v,
                      SpatialVec& out_force);
  void ball_robot_contact();
  bool step_once();
  void sample_imu();
  void feed_imu();
  void fail(WorldStatus why, std::string text) {
    status = why;
    reason = std::move(text);
  }
  Real grass_top() const { return options.contact.grass_thickness_m; }
};

// A Force that applies what Impl::compute_forces() computed for this step.
class AppliedForces final : public SimTK::Force::Custom::Implementation {
 public:
  explicit AppliedForces(const SimWorld::Impl* world) : world_(world) {}
  void calcForce(const SimTK::State& state, SimTK::Vector_<SpatialVec>& body_forces,
                 SimTK::Vector_<Vec3>&, SimTK::Vector& mobility_forces) const override {
    const SimWorld::Impl& w = *world_;
    (void)state;
    for (std::size_t j = 0; j < w.joint_u.size(); ++j)
      mobility_forces[w.joint_u[j]] += w.joint_tau[j];
    for (std::size_t l = 0; l < w.body_index.size(); ++l)
      body_forces[w.body_index[l]] += w.body_force[l];
    if (w.has_ball) body_forces[w.ball_index] += w.ball_force;
  }
  Real calcPotentialEnergy(const SimTK::State&) const override { return 0.0; }

 private:
  const SimWorld::Impl* world_;
};

Status SimWorld::Impl::configure() {
  const WorldOptions& o = options;
  if (o.physics_step_ns <= 0 || o.control_period_ns <= 0 ||
      o.control_period_ns % o.physics_step_ns != 0)
    return Status::error("physics step must be positive and divide the control period (step " +
                         std::to_string(o.physics_step_ns) + " ns, period " +
                         std::to_string(o.control_period_ns) + " ns)");
  if (!(o.battery_voltage_v > 0.0) || !(o.max_speed > 0.0))
    return Status::error("battery voltage and max speed must be positive");
  if (!(o.contact.grass_thickness_m >= 0.0) || !(o.contact.grass_stiffness_n_m > 0.0) ||
      !(o.contact.ground_stiffness_n_m > 0.0) || !(o.contact.friction >= 0.0) ||
      !(o.contact.tangential_stiffness_n_m > 0.0) || !(o.contact.grass_damping_n_s_m >= 0.0) ||
      !(o.contact.ground_damping_n_s_m >= 0.0) || !(o.contact.tangential_damping_n_s_m >= 0.0))
    return Status::error("contact: thickness, damping and friction must be >= 0, stiffness > 0");
  h = static_cast<Real>(o.physics_step_ns) * 1e-9;
  steps_per_period = static_cast<int>(o.control_period_ns / o.physics_step_ns);
  if (o.model) {
    model = *o.model;
  } else if (Status s = RobotModel::load_file(o.urdf, model); !s) {
    return s;
  }
  joint_servo.assign(model.joints().size(), -1);
  joint_tau.assign(model.joints().size(), 0.0);
  const fw::ServoTable* table = o.servo_models_from_table ? &fw::ServoTable::defaults() : nullptr;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const int j = model.joint_index(o.servo_joints[i]);
    if (j < 0)
      return Status::error(o.urdf.string() + ": no joint '" + o.servo_joints[i] + "' for servo " +
                           std::to_string(i + 1));
    if (joint_servo[static_cast<std::size_t>(j)] >= 0)
      return Status::error("joint '" + o.servo_joints[i] + "' is mapped to two servos");
    joint_servo[static_cast<std::size_t>(j)] = static_cast<int>(i);
    servo_joint[i] = j;
    servo_models[i] = table ? (*table)[i].model : o.servo_models[i];
  }
  left_foot = model.link_index("left_foot_link");
  right_foot = model.link_index("right_foot_link");
  // Contact points: spheres are points with a radius, boxes their eight corners.
  shapes.clear();
  points.clear();
  for (std::size_t l = 0; l < model.links().size(); ++l) {
    const LinkSpec& link = model.links()[l];
    const int foot = static_cast<int>(l) == left_foot    ? 1
                     : static_cast<int>(l) == right_foot ? 2
                                                         : 0;
    for (const CollisionSphere& s : link.spheres) {
      points.push_back({static_cast<int>(l), to_vec3(s.center), s.radius, foot});
      shapes.push_back(
          {static_cast<int>(l), false, Transform(Vec3(to_vec3(s.center))), Vec3(0), s.radius});
    }
    for (const CollisionBox& b : link.boxes) {
      const Transform pose(to_rotation(b.pose.linear()), to_vec3(b.pose.translation()));
      const Vec3 half = to_vec3(b.size) / 2;
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1 ? 1 : -1) * half[0], (c & 2 ? 1 : -1) * half[1],
                          (c & 4 ? 1 : -1) * half[2]);
        points.push_back({static_cast<int>(l), pose * corner, 0.0, foot});
      }
      shapes.push_back({static_cast<int>(l), true, pose, half, 0.0});
    }
  }
  body_force.assign(model.links().size(), SpatialVec(Vec3(0), Vec3(0)));
  link_reach.assign(model.links().size(), 0.0);
  for (const ContactPoint& p : points) {
    const auto l = static_cast<std::size_t>(p.link);
    link_reach[l] = std::max(link_reach[l], p.station.norm() + p.radius + 1e-3);
  }
  link_x.assign(model.links().size(), Transform());
  link_v.assign(model.links().size(), SpatialVec(Vec3(0), Vec3(0)));
  link_near.assign(model.links().size(), 0);
  mass_scale.assign(model.links().size(), 1.0);
  strength.fill(1.0);
  return Status::ok();
}

void SimWorld::Impl::build() {
  bodies.clear();
  ball = SimTK::MobilizedBody();
  matter.reset();
  system = std::make_unique<SimTK::MultibodySystem>();
  matter = std::make_unique<SimTK::SimbodyMatterSubsystem>(*system);
  SimTK::GeneralForceSubsystem forces(*system);
  SimTK::Force::Custom(forces, new AppliedForces(this));
  bodies.clear();
  link_mass.assign(model.links().size(), 0.0);
  link_com.assign(model.links().size(), Vec3(0));
  for (std::size_t l = 0; l < model.links().size(); ++l) {
    const LinkSpec& link = model.links()[l];
    const Real scale = mass_scale[l];
    link_mass[l] = scale * link.mass;
    link_com[l] = to_vec3(link.com);
    SimTK::Mat33 inertia;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) inertia(r, c) = scale * link.inertia(r, c);
    const Real mass = scale * link.mass;
    const Vec3 com = to_vec3(link.com);
    SimTK::Inertia about_origin = SimTK::Inertia(inertia).shiftFromMassCenter(com, mass);
    if (link.parent_joint < 0) {
      SimTK::Body::Rigid body(SimTK::MassProperties(mass, com, about_origin));
      bodies.push_back(
          SimTK::MobilizedBody::Free(matter->Ground(), Transform(), body, Transform()));
      continue;
    }
    const JointSpec& joint = model.joints()[static_cast<std::size_t>(link.parent_joint)];
    const Vec3 axis = to_vec3(joint.axis);
    const int servo = joint_servo[static_cast<std::size_t>(link.parent_joint)];
    if (servo >= 0) {
      const fw::ServoModel servo_model = servo_models[static_cast<std::size_t>(servo)];
      const MotorCurve curve = motor_curve(servo_model, options.battery_voltage_v);
      const Real reflected =
          options.servo.law == ServoLaw::kIdentified
              ? mx_servo_params(servo_model, options.battery_voltage_v,
                                options.servo.friction_model)
                    .armature_kg_m2
              : options.servo.rotor_inertia_kg_m2 * curve.gear_ratio * curve.gear_ratio;
      about_origin = add_rotor_inertia(about_origin, axis, reflected);
    }
    SimTK::Body::Rigid body(SimTK::MassProperties(mass, com, about_origin));
    const SimTK::Rotation z_to_axis(SimTK::UnitVec3(axis), SimTK::ZAxis);
    const Transform inboard(to_rotation(joint.origin.linear()) * z_to_axis,
                            to_vec3(joint.origin.translation()));
    const Transform outboard(z_to_axis, Vec3(0));
    bodies.push_back(SimTK::MobilizedBody::Pin(bodies[static_cast<std::size_t>(joint.parent_link)],
                                               inboard, body, outboard));
  }
  has_ball = options.ball.present;
  if (has_ball) {
    const BallOptions& b = options.ball;
    SimTK::Body::Rigid body(
        SimTK::MassProperties(b.mass_kg, Vec3(0), SimTK::Inertia(b.inertia_kg_m2)));
    ball = SimTK::MobilizedBody::Free(matter->Ground(), Transform(), body, Transform());
  }
  system->realizeTopology();
  state = system->getDefaultState();
  system->realizeModel(state);
  joint_q.clear();
  joint_u.clear();
  body_index.clear();
  for (const SimTK::MobilizedBody& b : bodies)
    body_index.push_back(static_cast<int>(b.getMobilizedBodyIndex()));
  if (has_ball) ball_index = static_cast<int>(ball.getMobilizedBodyIndex());
  for (const JointSpec& j : model.joints()) {
    const SimTK::MobilizedBody& mb = bodies[static_cast<std::size_t>(j.child_link)];
    joint_q.push_back(static_cast<int>(mb.getFirstQIndex(state)));
    joint_u.push_back(static_cast<int>(mb.getFirstUIndex(state)));
  }
  quaternion_q.clear();
  quaternion_q.push_back(static_cast<int>(bodies[0].getFirstQIndex(state)));
  if (has_ball) quaternion_q.push_back(static_cast<int>(ball.getFirstQIndex(state)));
  u_next.resize(state.getNU());
  qdot.resize(state.getNQ());
}

void SimWorld::Impl::ground_contact(ContactPoint& point, const Transform& x, const SpatialVec& v,
                                    SpatialVec& out_force) {
  const ContactOptions& c = options.contact;
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
    point.anchor_x = at[0];
    point.anchor_y = at[1];
  }
  Real fx =
      -c.tangential_stiffness_n_m * (at[0] - point.anchor_x) - c.tangential_damping_n_s_m * vel[0];
  Real fy =
      -c.tangential_stiffness_n_m * (at[1] - point.anchor_y) - c.tangential_damping_n_s_m * vel[1];
  const Real ft = std::sqrt(fx * fx + fy * fy);
  const Real max_ft = friction * fn;
  if (ft > max_ft) {  // sliding: scale to the cone and drag the anchor along
    const Real s = ft > 0 ? max_ft / ft : 0.0;
    fx *= s;
    fy *= s;
    point.anchor_x = at[0] + fx / c.tangential_stiffness_n_m;
    point.anchor_y = at[1] + fy / c.tangential_stiffness_n_m;
  }
  const Vec3 force(fx, fy, fn);
  out_force[0] += r % force;
  out_force[1] += force;
  if (point.foot == 1) {
    ++left_contact.points_in_contact;
    left_contact.force += to_eigen(force);
  } else if (point.foot == 2) {
    ++right_contact.points_in_contact;
    right_contact.force += to_eigen(force);
  } else if (point.link >= 0) {
    ++other_contacts;
  }
}

void SimWorld::Impl::ball_robot_contact() {
  const ContactOptions& c = options.contact;
  const Real radius = options.ball.radius_m;
  const Transform& xb = ball.getBodyTransform(state);
  if ((xb.p() - link_x[0].p()).normSqr() > 1.2 * 1.2) return;  // far from the robot
  const SpatialVec& vb = ball.getBodyVelocity(state);
  for (const LinkShape& shape : shapes) {
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
    Vec3 gap = local - closest;
    Real dist = gap.norm();
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
    body_force[l][0] -= (at - xl.p()) % force;
    body_force[l][1] -= force;
  }
}

void SimWorld::Impl::compute_forces() {
  // Servo and passive joint torques.
  const SimTK::Vector& q_all = matter->getQ(state);
  const SimTK::Vector& u_all = matter->getU(state);
  for (std::size_t j = 0; j < model.joints().size(); ++j) {
    const Real q = q_all[joint_q[j]];
    const Real w = u_all[joint_u[j]];
    const int servo = joint_servo[j];
    if (servo >= 0 && identified) {
      // External torque on the joint: quasi-static, what balanced the servo's torque over the
      // last step. (A finite-difference estimate, J dw/h - tau, adds the step-to-step noise
      // of w to the friction's stopping torque and drove a 1/(2h) limit cycle of the whole
      // body: 0.5 m/s^2 of torso chatter standing still, at any step size.)
      const auto i = static_cast<std::size_t>(servo);
      joint_tau[j] = mx_servos[i].step(q, w, -last_torque[i], h);
      last_torque[i] = joint_tau[j];
    } else if (servo >= 0) {
      joint_tau[j] = servos[static_cast<std::size_t>(servo)].step(q, w, h);
    } else {
      const JointSpec& spec = model.joints()[j];
      joint_tau[j] =
          -spec.damping * w - std::copysign(std::min(spec.friction, 1e-3 * std::abs(w) / h), w);
    }
  }
  // Contact.
  left_contact = {};
  right_contact = {};
  other_contacts = 0;
  // Body kinematics fetched once per link; links far above the grass are skipped whole.
  for (std::size_t l = 0; l < bodies.size(); ++l) {
    link_x[l] = bodies[l].getBodyTransform(state);
    link_v[l] = bodies[l].getBodyVelocity(state);
    link_near[l] = link_x[l].p()[2] - link_reach[l] <= grass_top();
  }
  // Gravity at each centre of mass (applied here rather than by Force::Gravity, whose cache
  // crashed on this Simbody build when driven by the fixed-step loop).
  const Real g = options.gravity_mps2;
  for (std::size_t l = 0; l < body_force.size(); ++l) {
    const Vec3 weight(0, 0, -g * link_mass[l]);
    const Vec3 r = link_x[l].R() * link_com[l];
    body_force[l] = SpatialVec(r % weight, weight);
  }
  ball_force = SpatialVec(Vec3(0), Vec3(0, 0, has_ball ? -g * options.ball.mass_kg : 0.0));
  for (ContactPoint& point : points) {
    const auto l = static_cast<std::size_t>(point.link);
    if (!link_near[l]) {
      point.touching = false;
      continue;
    }
    ground_contact(point, link_x[l], link_v[l], body_force[l]);
  }
  if (has_ball) {
    const SpatialVec& vb = ball.getBodyVelocity(state);
    ground_contact(ball_point, ball.getBodyTransform(state), vb, ball_force);
    ball_force[0] -= options.ball.rolling_damping * vb[0];
    ball_robot_contact();
  }
}

bool SimWorld::Impl::step_once() {
  if (status != WorldStatus::kRunning) return false;
  try {
    system->realize(state, Stage::Velocity);
    compute_forces();
    system->realize(state, Stage::Acceleration);
    torso_accel = bodies[0].getBodyOriginAcceleration(state);
    if (imu_chain) feed_imu();
    // Semi-explicit Euler: u' = u + h udot, q' = q + h N(q) u'. The loops run over the state's
    // contiguous storage (Simbody's element access is a virtual call per element, and `h *
    // udot` a temporary vector); the arithmetic is the same, element by element.
    const SimTK::Vector& udot = matter->getUDot(state);
    const SimTK::Vector& u = matter->getU(state);
    if (!udot.hasContiguousData() || !u.hasContiguousData() || !u_next.hasContiguousData() ||
        !qdot.hasContiguousData() || !matter->getQ(state).hasContiguousData())
      throw std::logic_error("state vectors are not contiguous");
    const Real* udot_data = udot.getContiguousScalarData();
    const Real* u_data = u.getContiguousScalarData();
    Real* u_next_data = u_next.updContiguousScalarData();
    for (int i = 0; i < u_next.size(); ++i) u_next_data[i] = u_data[i] + h * udot_data[i];
    matter->multiplyByN(state, false, u_next, qdot);
    Real* q = matter->updQ(state).updContiguousScalarData();
    const Real* qdot_data = qdot.getContiguousScalarData();
    for (int i = 0; i < qdot.size(); ++i) q[i] += h * qdot_data[i];
    for (int first : quaternion_q) {  // keep the free bodies' quaternions unit length
      Real norm = 0.0;
      for (int k = 0; k < 4; ++k) norm += q[first + k] * q[first + k];
      norm = std::sqrt(norm);
      for (int k = 0; k < 4; ++k) q[first + k] /= norm;
    }
    matter->updU(state) = u_next;
    state.updTime() = static_cast<Real>(steps + 1) * h;  // no round-off drift
  } catch (const std::exception& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    fail(WorldStatus::kIntegratorFailure,
         "Simbody failed at t=" + std::to_string(state.getTime()) + " s: " + what.substr(0, 200));
    return false;
  }
  ++steps;
  const SimTK::Vector& q_all = matter->getQ(state);
  const SimTK::Vector& u_all = matter->getU(state);
  const Real* q = q_all.getContiguousScalarData();
  const Real* u = u_all.getContiguousScalarData();
  for (int i = 0; i < q_all.size(); ++i)
    if (!std::isfinite(q[i])) {
      fail(WorldStatus::kNonFinite, "non-finite coordinate q[" + std::to_string(i) +
                                        "] at t=" + std::to_string(state.getTime()) + " s");
      return false;
    }
  for (int i = 0; i < u_all.size(); ++i) {
    if (!std::isfinite(u[i])) {
      fail(WorldStatus::kNonFinite, "non-finite speed u[" + std::to_string(i) +
                                        "] at t=" + std::to_string(state.getTime()) + " s");
      return false;
    }
    if (std::abs(u[i]) > options.max_speed) {
      fail(WorldStatus::kExploded, "exploding state: |u[" + std::to_string(i) +
                                       "]| = " + std::to_string(std::abs(u[i])) + " > " +
                                       std::to_string(options.max_speed) +
                                       " at t=" + std::to_string(state.getTime()) + " s");
      return false;
    }
  }
  return true;
}

/// True specific force and rate in the torso frame, this step, into the IMU chain.
void SimWorld::Impl::feed_imu() {
  const SimTK::Rotation& r = bodies[0].getBodyTransform(state).R();
  const Vec3 accel_b = ~r * (torso_accel + Vec3(0, 0, options.gravity_mps2));
  const Vec3 gyro_b = ~r * bodies[0].getBodyAngularVelocity(state);
  imu_model.step(to_eigen(accel_b), to_eigen(gyro_b), h, rng);
}

void SimWorld::Impl::sample_imu() {
  if (imu_chain) {
    imu.accel = imu_model.accel();
    imu.gyro = imu_model.gyro();
    return;
  }
  // Always six draws per sample, so the random stream does not depend on the options.
  Eigen::Vector3d accel_noise, gyro_noise;
  for (int k = 0; k < 3; ++k) accel_noise[k] = rng.normal();
  for (int k = 0; k < 3; ++k) gyro_noise[k] = rng.normal();
  if (status != WorldStatus::kRunning) return;
  system->realize(state, Stage::Velocity);
  const Transform& x = bodies[0].getBodyTransform(state);
  const Vec3 specific_force_g = torso_accel + Vec3(0, 0, options.gravity_mps2);
  const Vec3 accel_b = ~x.R() * specific_force_g;
  const Vec3 gyro_b = ~x.R() * bodies[0].getBodyAngularVelocity(state);
  imu.accel = to_eigen(accel_b) + accel_bias + options.imu.accel_noise_std * accel_noise;
  imu.gyro = to_eigen(gyro_b) + gyro_bias + options.imu.gyro_noise_std * gyro_noise;
}

// ----------------------------------------------------------------------------------------------
SimWorld::SimWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SimWorld::~SimWorld() = default;

Status SimWorld::create(const WorldOptions& options, std::unique_ptr<SimWorld>& out) {
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->rng.reseed(options.seed);
  if (Status s = impl->configure(); !s) return s;
  // reset() builds the Simbody system (with the masses it draws) and reports a failure.
  std::unique_ptr<SimWorld> world(new SimWorld(std::move(impl)));
  if (Status s = world->reset(ResetSpec::standing()); !s) return s;
  out = std::move(world);
  return Status::ok();
}

void SimWorld::reseed(std::uint64_t seed) {
  impl_->rng.reseed(seed);
}

Status SimWorld::reset(const ResetSpec& spec) {
  Impl& w = *impl_;
  for (double a : spec.joint_angles)
    if (!std::isfinite(a)) return Status::error("reset: non-finite joint angle");
  if (!std::isfinite(spec.torso_position.x()) || !std::isfinite(spec.torso_position.y()) ||
      !spec.torso_orientation.coeffs().allFinite() || !std::isfinite(spec.ball_position.x()) ||
      !std::isfinite(spec.ball_position.y()) || !spec.ball_velocity.allFinite())
    return Status::error("reset: non-finite torso or ball pose");
  // Randomisation: a fixed number of draws whatever the ranges.
  const Randomisation& r = w.options.randomise;
  w.friction = w.options.contact.friction * (1.0 + r.friction_range * w.rng.uniform(-1.0, 1.0));
  for (Real& s : w.mass_scale) s = 1.0 + r.mass_range * w.rng.uniform(-1.0, 1.0);
  for (Real& s : w.strength) s = 1.0 + r.strength_range * w.rng.uniform(-1.0, 1.0);
  w.latency = w.rng.uniform() < r.latency_probability;
  for (int k = 0; k < 3; ++k)
    w.accel_bias[k] = w.options.imu.accel_bias[k] + w.options.imu.accel_bias_std * w.rng.normal();
  for (int k = 0; k < 3; ++k)
    w.gyro_bias[k] = w.options.imu.gyro_bias[k] + w.options.imu.gyro_bias_std * w.rng.normal();
  try {
    w.build();
  } catch (const std::exception& e) {
    return Status::error(std::string("reset: building the Simbody system failed: ") + e.what());
  }
  // Servo parameters.
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const MotorCurve curve = motor_curve(w.servo_models[i], w.options.battery_voltage_v);
    const JointSpec& joint = w.model.joints()[static_cast<std::size_t>(w.servo_joint[i])];
    ServoParams p;
    p.stall_torque_nm = curve.stall_torque_nm * w.strength[i];
    p.no_load_speed_rad_s = curve.no_load_speed_rad_s;
    p.kp_per_register = w.options.servo.kp_per_register;
    p.viscous_friction = w.options.servo.viscous_friction;
    p.coulomb_friction = w.options.servo.coulomb_friction;
    p.reflected_inertia = w.options.servo.rotor_inertia_kg_m2 * curve.gear_ratio * curve.gear_ratio;
    p.limited = joint.limited;
    p.lower = joint.lower;
    p.upper = joint.upper;
    w.servos[i].configure(p);
    w.servos[i].reset(spec.joint_angles[i]);
    MxServoParams mx = mx_servo_params(w.servo_models[i], w.options.battery_voltage_v,
                                       w.options.servo.friction_model);
    mx.strength = w.strength[i];
    mx.backlash_rad = w.options.servo.backlash_rad;
    mx.driver_drop_v = w.options.servo.driver_drop_v;
    mx.limited = joint.limited;
    mx.lower = joint.lower;
    mx.upper = joint.upper;
    w.mx_servos[i].configure(mx);
    w.mx_servos[i].reset(spec.joint_angles[i]);
    w.last_torque[i] = 0.0;
    hal::ServoCommand hold;
    hold.position_rad = spec.joint_angles[i];
    hold.p_gain = 32.0;
    hold.torque_enable = true;
    w.written[i] = hold;
    w.delayed[i] = hold;
    w.servos[i].set_input({hold.position_rad, 0.0, hold.p_gain, hold.torque_limit, true});
    w.mx_servos[i].set_input({hold.position_rad, 0.0, hold.p_gain, hold.torque_limit, true});
  }
  w.identified = w.options.servo.law == ServoLaw::kIdentified;
  w.torque_enable = true;
  // Pose.
  SimTK::State& s = w.state;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const auto link = static_cast<std::size_t>(
        w.model.joints()[static_cast<std::size_t>(w.servo_joint[i])].child_link);
    w.bodies[link].setOneQ(s, 0, spec.joint_angles[i]);
  }
  const Eigen::Quaterniond qt = spec.torso_orientation.normalized();
  SimTK::Rotation rot(SimTK::Quaternion(qt.w(), qt.x(), qt.y(), qt.z()));
  Vec3 torso(spec.torso_position.x(), spec.torso_position.y(), 0.0);
  w.bodies[0].setQToFitTransform(s, Transform(rot, torso));
  w.system->realize(s, Stage::Position);
  if (spec.level_feet && w.left_foot >= 0 && w.right_foot >= 0) {
    const Vec3 up = w.bodies[static_cast<std::size_t>(w.left_foot)].getBodyRotation(s).z() +
                    w.bodies[static_cast<std::size_t>(w.right_foot)].getBodyRotation(s).z();
    const SimTK::UnitVec3 n(up);
    const Vec3 axis = n % Vec3(0, 0, 1);
    const Real angle = std::atan2(axis.norm(), n[2]);
    if (axis.norm() > 1e-12) {
      rot = SimTK::Rotation(angle, SimTK::UnitVec3(axis)) * rot;
      w.bodies[0].setQToFitTransform(s, Transform(rot, torso));
      w.system->realize(s, Stage::Position);
    }
  }
  if (std::isfinite(spec.torso_position.z())) {
    torso[2] = spec.torso_position.z();
  } else {
    Real lowest = std::numeric_limits<Real>::infinity();
    for (const ContactPoint& p : w.points) {
      const Vec3 at = w.bodies[static_cast<std::size_t>(p.link)].getBodyTransform(s) * p.station;
      lowest = std::min(lowest, at[2] - p.radius);
    }
    torso[2] = w.grass_top() - lowest;
  }
  w.bodies[0].setQToFitTransform(s, Transform(rot, torso));
  if (w.has_ball) {
    const Real z = std::isfinite(spec.ball_position.z()) ? spec.ball_position.z()
                                                         : w.grass_top() + w.options.ball.radius_m;
    w.ball.setQToFitTransform(s,
                              Transform(Vec3(spec.ball_position.x(), spec.ball_position.y(), z)));
    w.ball.setUToFitLinearVelocity(s, to_vec3(spec.ball_velocity));
  }
  for (ContactPoint& p : w.points) p.touching = false;
  w.ball_point = ContactPoint{-1, Vec3(0), w.options.ball.radius_m, 0};
  s.updTime() = 0.0;
  w.steps = 0;
  w.periods = 0;
  w.status = WorldStatus::kRunning;
  w.reason.clear();
  w.torso_accel = Vec3(0);
  w.imu_chain = !w.options.imu.chain.is_ideal();
  if (w.imu_chain) {
    w.system->realize(w.state, Stage::Velocity);
    const SimTK::Rotation& torso_r = w.bodies[0].getBodyTransform(w.state).R();
    w.imu_model.configure(w.options.imu.chain);
    w.imu_model.reset(to_eigen(~torso_r * Vec3(0, 0, w.options.gravity_mps2)),
                      Eigen::Vector3d::Zero(), w.accel_bias, w.gyro_bias);
  }
  w.sample_imu();
  return Status::ok();
}

void SimWorld::set_servo_command(std::size_t index, const hal::ServoCommand& command) {
  if (index < hal::kServoCount) impl_->written[index] = command;
}

void SimWorld::set_torque_enable(bool enabled) {
  impl_->torque_enable = enabled;
}

hal::ServoState SimWorld::servo_state(std::size_t index) const {
  hal::ServoState out;
  if (index >= hal::kServoCount) return out;
  const Impl& w = *impl_;
  const SimTK::MobilizedBody& mb = w.bodies[static_cast<std::size_t>(
      w.model.joints()[static_cast<std::size_t>(w.servo_joint[index])].child_link)];
  const ServoModel& servo = w.servos[index];
  const MxServo& mx = w.mx_servos[index];
  const hal::ServoCommand& cmd = w.written[index];
  constexpr double kSpeedUnit = 0.114 * 2.0 * M_PI / 60.0;  // present speed register unit
  out.position_rad = quantise_encoder(mb.getOneQ(w.state, 0));
  out.speed_rad_s = std::round(mb.getOneU(w.state, 0) / kSpeedUnit) * kSpeedUnit;
  out.load = w.identified ? mx.load() : servo.load();
  out.voltage_v = w.options.battery_voltage_v;
  out.temperature_c = std::round(w.identified ? mx.temperature_c() : servo.temperature_c());
  out.goal_position_rad = cmd.position_rad;
  out.p_gain = cmd.p_gain;
  out.i_gain = cmd.i_gain;
  out.d_gain = cmd.d_gain;
  out.torque_limit = cmd.torque_limit;
  out.torque_enabled = cmd.torque_enable && w.torque_enable;
  out.error_flags = 0;
  out.health = hal::DeviceHealth::kOk;
  return out;
}

const ImuReading& SimWorld::imu() const {
  return impl_->imu;
}

bool SimWorld::step() {
  return impl_->step_once();
}

bool SimWorld::advance_period() {
  Impl& w = *impl_;
  if (w.status != WorldStatus::kRunning) return false;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const hal::ServoCommand& c = w.latency ? w.delayed[i] : w.written[i];
    w.servos[i].set_input({c.position_rad, c.moving_speed_rad_s, c.p_gain, c.torque_limit,
                           c.torque_enable && w.torque_enable});
    w.mx_servos[i].set_input({c.position_rad, c.moving_speed_rad_s, c.p_gain, c.torque_limit,
                              c.torque_enable && w.torque_enable});
    w.delayed[i] = w.written[i];
  }
  for (int k = 0; k < w.steps_per_period; ++k)
    if (!w.step_once()) break;
  ++w.periods;
  w.sample_imu();
  return w.status == WorldStatus::kRunning;
}

WorldStatus SimWorld::status() const {
  return impl_->status;
}
const std::string& SimWorld::failure_reason() const {
  return impl_->reason;
}
double SimWorld::time_s() const {
  return impl_->state.getTime();
}
std::int64_t SimWorld::period_count() const {
  return impl_->periods;
}
const WorldOptions& SimWorld::options() const {
  return impl_->options;
}
const RobotModel& SimWorld::model() const {
  return impl_->model;
}
double SimWorld::battery_voltage() const {
  return impl_->options.battery_voltage_v;
}

GroundTruth SimWorld::ground_truth() const {
  Impl& w = *impl_;
  GroundTruth g;
  g.time_s = w.state.getTime();
  g.left_contact = w.left_contact;
  g.right_contact = w.right_contact;
  g.other_contacts = w.other_contacts;
  if (w.status == WorldStatus::kNonFinite) return g;
  w.system->realize(w.state, Stage::Velocity);
  g.torso = to_isometry(w.bodies[0].getBodyTransform(w.state));
  g.torso_linear_velocity = to_eigen(w.bodies[0].getBodyOriginVelocity(w.state));
  g.torso_angular_velocity = to_eigen(w.bodies[0].getBodyAngularVelocity(w.state));
  g.torso_linear_acceleration = to_eigen(w.torso_accel);
  g.center_of_mass = to_eigen(w.matter->calcSystemMassCenterLocationInGround(w.state));
  if (w.has_ball) {
    // calcSystemMassCenter includes the ball: take the robot alone.
    const Real mb = w.options.ball.mass_kg;
    Real mt = 0.0;
    for (std::size_t l = 0; l < w.model.links().size(); ++l)
      mt += w.mass_scale[l] * w.model.links()[l].mass;
    const Vec3 ball_p = w.ball.getBodyOriginLocation(w.state);
    g.center_of_mass = (g.center_of_mass * (mt + mb) - to_eigen(ball_p) * mb) / mt;
    g.ball_position = to_eigen(ball_p);
    g.ball_velocity = to_eigen(w.ball.getBodyOriginVelocity(w.state));
  }
  if (w.left_foot >= 0)
    g.left_foot =
        to_isometry(w.bodies[static_cast<std::size_t>(w.left_foot)].getBodyTransform(w.state));
  if (w.right_foot >= 0)
    g.right_foot =
        to_isometry(w.bodies[static_cast<std::size_t>(w.right_foot)].getBodyTransform(w.state));
  return g;
}

Eigen::Isometry3d SimWorld::torso_pose() const {
  Impl& w = *impl_;
  if (w.status == WorldStatus::kNonFinite) return Eigen::Isometry3d::Identity();
  w.system->realize(w.state, Stage::Position);
  return to_isometry(w.bodies[0].getBodyTransform(w.state));
}

std::uint64_t SimWorld::state_hash() const {
  const Impl& w = *impl_;
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  const Real t = w.state.getTime();
  hash = fnv1a(hash, &t, sizeof t);
  const SimTK::Vector& q = w.matter->getQ(w.state);
  const SimTK::Vector& u = w.matter->getU(w.state);
  for (int i = 0; i < q.size(); ++i) hash = fnv1a(hash, &q[i], sizeof(Real));
  for (int i = 0; i < u.size(); ++i) hash = fnv1a(hash, &u[i], sizeof(Real));
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const double sp = w.identified ? w.mx_servos[i].setpoint() : w.servos[i].setpoint();
    hash = fnv1a(hash, &sp, sizeof sp);
    if (w.identified) {
      const double gap = w.mx_servos[i].backlash_gap();
      hash = fnv1a(hash, &gap, sizeof gap);
    }
  }
  std::vector<const ContactPoint*> all;
  for (const ContactPoint& p : w.points) all.push_back(&p);
  all.push_back(&w.ball_point);
  for (const ContactPoint* pp : all) {
    const ContactPoint& p = *pp;
    const unsigned char touching = p.touching ? 1 : 0;
    hash = fnv1a(hash, &touching, 1);
    hash = fnv1a(hash, &p.anchor_x, sizeof(Real));
    hash = fnv1a(hash, &p.anchor_y, sizeof(Real));
  }
  return hash;
}

std::vector<Eigen::Isometry3d> SimWorld::link_poses() const {
  Impl& w = *impl_;
  std::vector<Eigen::Isometry3d> out;
  if (w.status == WorldStatus::kNonFinite) return out;
  w.system->realize(w.state, Stage::Position);
  for (const SimTK::MobilizedBody& b : w.bodies)
    out.push_back(to_isometry(b.getBodyTransform(w.state)));
  return out;
}

std::vector<double> SimWorld::joint_angles() const {
  const Impl& w = *impl_;
  std::vector<double> out;
  for (const JointSpec& j : w.model.joints())
    out.push_back(w.bodies[static_cast<std::size_t>(j.child_link)].getOneQ(w.state, 0));
  return out;
}

double SimWorld::servo_joint_angle(std::size_t index) const {
  const Impl& w = *impl_;
  if (index >= hal::kServoCount) return 0.0;
  const auto link = static_cast<std::size_t>(
      w.model.joints()[static_cast<std::size_t>(w.servo_joint[index])].child_link);
  return w.bodies[link].getOneQ(w.state, 0);
}

void SimWorld::set_joint_speed(std::size_t joint, double speed) {
  Impl& w = *impl_;
  if (joint >= w.model.joints().size()) return;
  w.bodies[static_cast<std::size_t>(w.model.joints()[joint].child_link)].setOneU(w.state, 0, speed);
}

const char* to_string(WorldStatus status) {
  switch (status) {
    case WorldStatus::kRunning:
      return "running";
    case WorldStatus::kNonFinite:
      return "non-finite state";
    case WorldStatus::kExploded:
      return "exploded";
    case WorldStatus::kIntegratorFailure:
      return "integrator failure";
  }
  return "unknown";
}

}  // namespace stride::sim
