// MuJoCo engine (what it does: mujoco_engine.hpp; the model: mjcf_model.hpp; the contact
// parameters: contact_params.hpp).
#include "mujoco_engine.hpp"

#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "contact_params.hpp"
#include "episode_values.hpp"
#include "mjcf_model.hpp"

namespace stride::sim {
namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

/// Test and benchmark hooks (mujoco_engine.hpp): compiles so far, the old path, the observer.
std::atomic<std::int64_t> compiles{0};
std::atomic<bool> always_compile{false};
std::atomic<MujocoStepObserver> step_observer{nullptr};
std::atomic<void*> step_observer_context{nullptr};

/// True when two models have the same sizes (mjModel's leading block of counts, nq to nbuffer):
/// an mjData made for one has the layout of one made for the other.
bool same_sizes(const mjModel& a, const mjModel& b) {
  const std::size_t first = offsetof(mjModel, nq), end = offsetof(mjModel, nbuffer) + sizeof(int);
  return std::memcmp(reinterpret_cast<const char*>(&a) + first,
                     reinterpret_cast<const char*>(&b) + first, end - first) == 0;
}

/// MuJoCo's default warning handler prints and appends to MUJOCO_LOG.TXT in the working
/// directory; the engine reads the warning counters instead (step()).
void quiet_warning(const char*) {}

Eigen::Vector3d vec3(const mjtNum* v) {
  return {v[0], v[1], v[2]};
}

Eigen::Matrix3d mat3(const mjtNum* m) {  // MuJoCo: row-major 3x3
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m[3 * r + c];
  return out;
}

class MujocoEngine final : public PhysicsEngine {
 public:
  Status build(const EngineModel& model) override;
  Status start(const EngineStart& start) override;
  double joint_angle(std::size_t joint) const override { return d_->qpos[joint_qpos_[joint]]; }
  double joint_speed(std::size_t joint) const override { return d_->qvel[joint_dof_[joint]]; }
  WorldStatus step(const std::vector<double>& joint_torque, std::string& reason) override;
  double time_s() const override { return d_->time; }
  Eigen::Isometry3d link_pose(std::size_t link) const override;
  Eigen::Vector3d torso_velocity() const override { return vec3(d_->qvel + root_dof_); }
  Eigen::Vector3d torso_angular_velocity() const override {
    // A free joint's angular velocity is in the body frame.
    return mat3(d_->xmat + 9 * link_body_[0]) * vec3(d_->qvel + root_dof_ + 3);
  }
  Eigen::Vector3d torso_acceleration() const override { return torso_acc_; }
  Eigen::Vector3d robot_center_of_mass() const override;
  Eigen::Vector3d ball_position() const override {
    return ball_body_ < 0 ? Eigen::Vector3d::Zero() : vec3(d_->qpos + ball_qpos_);
  }
  Eigen::Vector3d ball_velocity() const override {
    return ball_body_ < 0 ? Eigen::Vector3d::Zero() : vec3(d_->qvel + ball_dof_);
  }
  ContactReport contacts() const override;
  std::uint64_t hash(std::uint64_t seed) const override;
  void set_joint_speed(std::size_t joint, double speed) override {
    d_->qvel[joint_dof_[joint]] = speed;
  }
  void set_torso_force(const Eigen::Vector3d& force) override {
    // xfrc_applied acts at the body's centre of mass, world frame; mj_resetData clears it.
    mjtNum* f = d_->xfrc_applied + 6 * link_body_[0];
    for (int k = 0; k < 3; ++k) f[k] = force[k];
  }

  const mjModel* model() const { return m_.get(); }

 private:
  /// Compiles `xml` into m_ (mjData kept when the sizes allow, unless `fresh_data`) and finds
  /// the bodies, joints and geoms; xml_ is then `xml`, patchable_ false.
  Status compile(std::string xml, bool fresh_data);
  /// The contact parameters and the robot's mass of the model in m_.
  Status finish_build();

  EngineModel model_;
  std::string xml_;         ///< the MJCF m_ was compiled from (empty: none)
  bool patchable_ = false;  ///< xml_ is a nominal model's: m_ takes episode values
  std::unique_ptr<mjModel, ModelDeleter> m_;
  std::unique_ptr<mjData, DataDeleter> d_;
  std::vector<int> link_body_;  // per link: MuJoCo body id
  std::vector<int> joint_qpos_, joint_dof_;
  std::vector<int> geom_link_;  // per geom: robot link, or -1 (field, ball)
  int root_qpos_ = 0, root_dof_ = 0;
  int ball_body_ = -1, ball_qpos_ = 0, ball_dof_ = 0;
  int field_geom_ = -1;
  int ground_geom_ = -1;  ///< the solid ground under the grass (mujoco_solid_ground), or -1
  double robot_mass_ = 0.0;
  std::int64_t steps_ = 0;
  Eigen::Vector3d torso_acc_ = Eigen::Vector3d::Zero();
  std::array<int, 3> bad_warnings_{};  // counts of bad qpos/qvel/qacc at the last check
};

Status MujocoEngine::build(const EngineModel& model) {
  if (model.robot == nullptr) return Status::error("MuJoCo engine: no robot model");
  const RobotModel& robot = *model.robot;
  if (model.link_mass_scale.size() != robot.links().size() ||
      model.joint_armature.size() != robot.joints().size())
    return Status::error("MuJoCo engine: " + std::to_string(model.link_mass_scale.size()) +
                         " link mass scales and " + std::to_string(model.joint_armature.size()) +
                         " armatures for a robot of " + std::to_string(robot.links().size()) +
                         " links and " + std::to_string(robot.joints().size()) + " joints");
  if (!(model.step_s > 0.0) || !std::isfinite(model.step_s))
    return Status::error("MuJoCo engine: the physics step must be positive");
  if (model.ball.present &&
      !(model.ball.radius_m > 0.0 && model.ball.mass_kg > 0.0 && model.ball.inertia_kg_m2 > 0.0))
    return Status::error("MuJoCo engine: the ball needs a positive radius, mass and inertia");
  model_ = model;
  static std::once_flag quiet;  // a global of MuJoCo: set once, whatever the threads
  std::call_once(quiet, [] { mju_user_warning = quiet_warning; });

  // Compiled once per model structure: the MJCF of the model with the values drawn per reset
  // at nominal ones (episode_values.hpp), the episode's values then written into the compiled
  // model exactly as the compiler would have written them from the episode's own text. The
  // contact parameters are set again (they depend on the stiffnesses, which are not in the
  // text, and on the inverse weights, which follow the masses).
  const bool old_path = always_compile.load(std::memory_order_relaxed);
  if (!old_path) {
    std::string key = mujoco::write_mjcf(mujoco::nominal_model(model));
    if (m_ && d_ && patchable_ && key == xml_ &&
        mujoco::write_episode_values(m_.get(), d_.get(), model))
      return finish_build();
    std::string text = mujoco::write_mjcf(model);
    if (m_ && d_ && !patchable_ && text == xml_)  // the last episode's own text again
      return finish_build();
    if (!(patchable_ && key == xml_) && compile(std::move(key), false) &&
        mujoco::write_episode_values(m_.get(), d_.get(), model)) {
      patchable_ = true;
      return finish_build();
    }
    // A value the compiler would refuse or treat otherwise: compile the episode's own text
    // (whose errors name the value).
    if (Status s = compile(std::move(text), false); !s) return s;
    return finish_build();
  }
  // The old path (mujoco_set_always_compile): the episode's text compiled, mjData afresh.
  if (Status s = compile(mujoco::write_mjcf(model), true); !s) return s;
  return finish_build();
}

Status MujocoEngine::finish_build() {
  mujoco::set_contact_params(m_.get(), model_);
  robot_mass_ = 0.0;
  for (int b : link_body_) robot_mass_ += m_->body_mass[b];
  return Status::ok();
}

Status MujocoEngine::compile(std::string xml, bool fresh_data) {
  // Keep the mjData if the new model has the old one's sizes (the layout of mjData's buffer
  // depends on nothing else, and start() clears it all, as mj_makeData does).
  std::unique_ptr<mjModel, ModelDeleter> old_model = std::move(m_);
  std::unique_ptr<mjData, DataDeleter> old_data = std::move(d_);
  if (fresh_data) {
    old_data.reset();
    old_model.reset();
  }
  xml_.clear();
  patchable_ = false;
  const char* file = "stride.xml";
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);  // ~2 MB: not on the stack
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(xml.size())) != 0)
    return Status::error("MuJoCo engine: no room for the model in the virtual file system");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], xml.data(), xml.size());
  char error[1000] = "";
  {
    // mj_loadXML keeps the last model in a global (for mj_saveLastXML): one load at a time.
    static std::mutex loading;
    const std::lock_guard<std::mutex> lock(loading);
    m_.reset(mj_loadXML(file, vfs.get(), error, sizeof error));
  }
  compiles.fetch_add(1, std::memory_order_relaxed);
  if (!m_) {
    std::string text = error;
    for (char& c : text)
      if (c == '\n') c = ' ';
    return Status::error("MuJoCo engine: loading the generated MJCF failed: " + text);
  }
  if (old_data && same_sizes(*old_model, *m_))
    d_ = std::move(old_data);
  else
    d_.reset(mj_makeData(m_.get()));
  old_data.reset();
  old_model.reset();
  if (!d_) {
    m_.reset();
    return Status::error("MuJoCo engine: allocating mjData failed");
  }

  const RobotModel& robot = *model_.robot;
  link_body_.assign(robot.links().size(), -1);
  for (std::size_t l = 0; l < robot.links().size(); ++l)
    link_body_[l] = mj_name2id(m_.get(), mjOBJ_BODY, ("l" + std::to_string(l)).c_str());
  joint_qpos_.assign(robot.joints().size(), 0);
  joint_dof_.assign(robot.joints().size(), 0);
  for (std::size_t j = 0; j < robot.joints().size(); ++j) {
    const int id = mj_name2id(m_.get(), mjOBJ_JOINT, ("j" + std::to_string(j)).c_str());
    joint_qpos_[j] = m_->jnt_qposadr[id];
    joint_dof_[j] = m_->jnt_dofadr[id];
  }
  const int root = mj_name2id(m_.get(), mjOBJ_JOINT, "root");
  root_qpos_ = m_->jnt_qposadr[root];
  root_dof_ = m_->jnt_dofadr[root];
  ball_body_ = model_.ball.present ? mj_name2id(m_.get(), mjOBJ_BODY, "ball") : -1;
  if (ball_body_ >= 0) {
    const int joint = mj_name2id(m_.get(), mjOBJ_JOINT, "ball");
    ball_qpos_ = m_->jnt_qposadr[joint];
    ball_dof_ = m_->jnt_dofadr[joint];
  }
  field_geom_ = mj_name2id(m_.get(), mjOBJ_GEOM, "grass");
  ground_geom_ = mj_name2id(m_.get(), mjOBJ_GEOM, "ground");
  geom_link_.assign(static_cast<std::size_t>(m_->ngeom), -1);
  for (std::size_t l = 0; l < link_body_.size(); ++l)
    for (int g = 0; g < m_->ngeom; ++g)
      if (m_->geom_bodyid[g] == link_body_[l])
        geom_link_[static_cast<std::size_t>(g)] = static_cast<int>(l);
  xml_ = std::move(xml);
  return Status::ok();
}

Status MujocoEngine::start(const EngineStart& start) {
  if (!d_) return Status::error("MuJoCo engine: start() before a successful build()");
  if (start.joint_angles.size() != joint_qpos_.size())
    return Status::error("MuJoCo engine: " + std::to_string(start.joint_angles.size()) +
                         " joint angles for " + std::to_string(joint_qpos_.size()) + " joints");
  mj_resetData(m_.get(), d_.get());
  for (std::size_t j = 0; j < joint_qpos_.size(); ++j)
    d_->qpos[joint_qpos_[j]] = start.joint_angles[j];
  if (start.joint_speeds.size() == joint_dof_.size())
    for (std::size_t j = 0; j < joint_dof_.size(); ++j)
      d_->qvel[joint_dof_[j]] = start.joint_speeds[j];
  const Eigen::Vector3d& p = start.torso_position;
  Eigen::Quaterniond q = start.torso_orientation.normalized();
  if (start.tilt_angle != 0.0)
    q = Eigen::Quaterniond(Eigen::AngleAxisd(start.tilt_angle, start.tilt_axis.normalized())) * q;
  mjtNum* root = d_->qpos + root_qpos_;
  root[0] = p.x();
  root[1] = p.y();
  root[2] = p.z();
  root[3] = q.w();
  root[4] = q.x();
  root[5] = q.y();
  root[6] = q.z();
  mju_normalize4(root + 3);
  // A free joint's speeds: the linear velocity in the world frame, the angular in the body's.
  mjtNum* root_speed = d_->qvel + root_dof_;
  const Eigen::Vector3d body_w = q.normalized().conjugate() * start.torso_angular_velocity;
  for (int k = 0; k < 3; ++k) {
    root_speed[k] = start.torso_velocity[k];
    root_speed[3 + k] = body_w[k];
  }
  if (ball_body_ >= 0) {
    mjtNum* ball = d_->qpos + ball_qpos_;
    for (int k = 0; k < 3; ++k) ball[k] = start.ball_position[k];
    ball[3] = 1.0;
    ball[4] = ball[5] = ball[6] = 0.0;
    for (int k = 0; k < 3; ++k) d_->qvel[ball_dof_ + k] = start.ball_velocity[k];
  }
  d_->time = 0.0;
  steps_ = 0;
  torso_acc_.setZero();
  mj_forward(m_.get(), d_.get());
  for (int k = 0; k < 3; ++k) bad_warnings_[static_cast<std::size_t>(k)] = 0;
  for (int k = 0; k < 3; ++k) d_->warning[mjWARN_BADQPOS + k].number = 0;
  d_->warning[mjWARN_CONTACTFULL].number = 0;
  d_->warning[mjWARN_CNSTRFULL].number = 0;
  return Status::ok();
}

WorldStatus MujocoEngine::step(const std::vector<double>& joint_torque, std::string& reason) {
  mju_zero(d_->qfrc_applied, m_->nv);
  for (std::size_t j = 0; j < joint_dof_.size() && j < joint_torque.size(); ++j)
    d_->qfrc_applied[joint_dof_[j]] = joint_torque[j];
  if (ball_body_ >= 0)  // rolling damping: torque -c w (the ball's w is in its body frame)
    for (int k = 3; k < 6; ++k)
      d_->qfrc_applied[ball_dof_ + k] = -model_.ball.rolling_damping * d_->qvel[ball_dof_ + k];
  const Eigen::Vector3d v_before = vec3(d_->qvel + root_dof_);
  if (const MujocoStepObserver observe = step_observer.load(std::memory_order_relaxed))
    observe(m_.get(), d_.get(), step_observer_context.load(std::memory_order_relaxed));
  mj_step(m_.get(), d_.get());
  ++steps_;
  d_->time = static_cast<double>(steps_) * model_.step_s;  // no round-off drift
  torso_acc_ = (vec3(d_->qvel + root_dof_) - v_before) / model_.step_s;
  // MuJoCo resets the state itself on a bad qpos/qvel/qacc (and warns): that is a failure.
  for (int k = 0; k < 3; ++k)
    if (d_->warning[mjWARN_BADQPOS + k].number != bad_warnings_[static_cast<std::size_t>(k)]) {
      reason = std::string("MuJoCo found a bad ") +
               (k == 0   ? "qpos"
                : k == 1 ? "qvel"
                         : "qacc") +
               " and reset the state at t=" + std::to_string(d_->time) + " s";
      return WorldStatus::kNonFinite;
    }
  // A full contact or constraint buffer drops contacts silently: end the episode instead.
  for (const int w : {static_cast<int>(mjWARN_CONTACTFULL), static_cast<int>(mjWARN_CNSTRFULL)})
    if (d_->warning[w].number > 0) {
      reason =
          std::string("MuJoCo's ") +
          (w == mjWARN_CONTACTFULL ? "contact buffer (" + std::to_string(m_->nconmax) + " contacts)"
                                   : "constraint buffer (" + std::to_string(m_->njmax) + " rows)") +
          " is full at t=" + std::to_string(d_->time) + " s";
      return WorldStatus::kIntegratorFailure;
    }
  const WorldStatus status =
      check_state(d_->qpos, static_cast<std::size_t>(m_->nq), d_->qvel,
                  static_cast<std::size_t>(m_->nv), model_.max_speed, d_->time, reason);
  if (status != WorldStatus::kRunning) return status;
  mj_kinematics(m_.get(), d_.get());  // link poses of the new positions
  return WorldStatus::kRunning;
}

Eigen::Isometry3d MujocoEngine::link_pose(std::size_t link) const {
  const int b = link_body_[link];
  Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
  x.linear() = mat3(d_->xmat + 9 * b);
  x.translation() = vec3(d_->xpos + 3 * b);
  return x;
}

Eigen::Vector3d MujocoEngine::robot_center_of_mass() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int b : link_body_) sum += m_->body_mass[b] * vec3(d_->xipos + 3 * b);
  return sum / robot_mass_;
}

ContactReport MujocoEngine::contacts() const {
  ContactReport out;
  for (int i = 0; i < d_->ncon; ++i) {
    const mjContact& c = d_->contact[i];
    int robot_geom = -1;
    double sign = 1.0;  // the force of geom1 on geom2 acts along +normal
    // A point on the solid ground is in the grass too: its ground contact adds force only.
    const bool ground = ground_geom_ >= 0 && (c.geom1 == ground_geom_ || c.geom2 == ground_geom_);
    const int field = ground ? ground_geom_ : field_geom_;
    if (c.geom1 == field) {
      robot_geom = c.geom2;
    } else if (c.geom2 == field) {
      robot_geom = c.geom1;
      sign = -1.0;
    }
    if (robot_geom < 0) continue;
    const int link = geom_link_[static_cast<std::size_t>(robot_geom)];
    if (link < 0) continue;  // the ball
    FootContact* foot = link == model_.left_foot    ? &out.left
                        : link == model_.right_foot ? &out.right
                                                    : nullptr;
    if (foot == nullptr) {
      if (!ground) ++out.other_contacts;
      continue;
    }
    mjtNum local[6];
    mj_contactForce(m_.get(), d_.get(), i, local);
    Eigen::Vector3d world = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) world += local[k] * vec3(c.frame + 3 * k);
    if (!ground) ++foot->points_in_contact;
    foot->force += sign * world;
  }
  return out;
}

std::uint64_t MujocoEngine::hash(std::uint64_t seed) const {
  std::uint64_t h = fnv1a(seed, &d_->time, sizeof d_->time);
  const auto nq = static_cast<std::size_t>(m_->nq), nv = static_cast<std::size_t>(m_->nv);
  h = fnv1a(h, d_->qpos, nq * sizeof(mjtNum));
  h = fnv1a(h, d_->qvel, nv * sizeof(mjtNum));
  h = fnv1a(h, d_->qacc_warmstart, nv * sizeof(mjtNum));
  if (m_->na > 0) h = fnv1a(h, d_->act, static_cast<std::size_t>(m_->na) * sizeof(mjtNum));
  return h;
}

}  // namespace

std::unique_ptr<PhysicsEngine> make_mujoco_engine() {
  return std::make_unique<MujocoEngine>();
}

const mjModel* mujoco_model_of(const PhysicsEngine& engine) {
  const auto* mujoco = dynamic_cast<const MujocoEngine*>(&engine);
  return mujoco ? mujoco->model() : nullptr;
}

std::int64_t mujoco_compile_count() {
  return compiles.load(std::memory_order_relaxed);
}

void mujoco_set_always_compile(bool on) {
  always_compile.store(on, std::memory_order_relaxed);
}

void mujoco_set_step_observer(MujocoStepObserver observer, void* context) {
  step_observer_context.store(context, std::memory_order_relaxed);
  step_observer.store(observer, std::memory_order_relaxed);
}

}  // namespace stride::sim
