// RobotModel: URDF loading (urdfdom) and validation into plain link/joint data.
#include "stride/sim_hal/robot_model.hpp"

#include <console_bridge/console.h>

#include <Eigen/Eigenvalues>

#include <urdf_parser/urdf_parser.h>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace stride::sim {
namespace {

Eigen::Isometry3d to_isometry(const urdf::Pose& pose) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  double qx = 0, qy = 0, qz = 0, qw = 1;
  pose.rotation.getQuaternion(qx, qy, qz, qw);
  out.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
  out.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return out;
}

bool finite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

bool valid_inertia(const Eigen::Matrix3d& inertia) {
  if (!inertia.allFinite()) return false;
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > 1e-12) return false;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  const Eigen::Vector3d m = solver.eigenvalues();
  const double tol = 1e-9 * std::max(1e-12, m.cwiseAbs().maxCoeff());
  if (m.minCoeff() < -tol) return false;
  return m(0) + m(1) >= m(2) - tol && m(0) + m(2) >= m(1) - tol && m(1) + m(2) >= m(0) - tol;
}

/// Adds `child` (a body rigidly attached at `pose` in the parent frame) into `parent`.
void merge_into(LinkSpec& parent, const LinkSpec& child, const Eigen::Isometry3d& pose) {
  const double m = parent.mass + child.mass;
  const Eigen::Vector3d child_com = pose * child.com;
  const Eigen::Vector3d com =
      m > 0 ? Eigen::Vector3d((parent.mass * parent.com + child.mass * child_com) / m)
            : Eigen::Vector3d::Zero();
  auto shift = [](double mass, const Eigen::Vector3d& d) {
    return mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  };
  const Eigen::Matrix3d child_inertia = pose.linear() * child.inertia * pose.linear().transpose();
  parent.inertia = parent.inertia + shift(parent.mass, parent.com - com) + child_inertia +
                   shift(child.mass, child_com - com);
  parent.mass = m;
  parent.com = com;
  for (CollisionSphere s : child.spheres) {
    s.center = pose * s.center;
    parent.spheres.push_back(s);
  }
  for (CollisionBox b : child.boxes) {
    b.pose = pose * b.pose;
    parent.boxes.push_back(b);
  }
}

class Builder {
 public:
  Builder(const urdf::ModelInterface& urdf, std::string source)
      : urdf_(urdf), source_(std::move(source)) {}

  Status build(std::vector<LinkSpec>& links, std::vector<JointSpec>& joints) {
    const urdf::LinkConstSharedPtr root = urdf_.getRoot();
    if (!root) return error("no root link");
    LinkSpec root_spec;
    if (Status s = read_link(*root, root_spec); !s) return s;
    links.push_back(root_spec);
    return add_children(*root, 0, Eigen::Isometry3d::Identity(), links, joints);
  }

 private:
  Status error(const std::string& what) const { return Status::error(source_ + ": " + what); }

  Status read_link(const urdf::Link& link, LinkSpec& out) const {
    out.name = link.name;
    if (link.inertial) {
      const urdf::Inertial& in = *link.inertial;
      out.mass = in.mass;
      const Eigen::Isometry3d frame = to_isometry(in.origin);
      out.com = frame.translation();
      Eigen::Matrix3d inertia;
      inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      out.inertia = frame.linear() * inertia * frame.linear().transpose();
      if (!std::isfinite(out.mass) || out.mass <= 0.0)
        return error("link '" + link.name + "': mass must be positive and finite");
      if (!finite(out.com)) return error("link '" + link.name + "': non-finite inertial origin");
      if (!valid_inertia(out.inertia))
        return error("link '" + link.name +
                     "': inertia is not physically valid (symmetric, positive, triangle "
                     "inequality)");
    }
    for (const urdf::CollisionSharedPtr& c : link.collision_array) {
      if (!c || !c->geometry) continue;
      const Eigen::Isometry3d pose = to_isometry(c->origin);
      if (c->geometry->type == urdf::Geometry::SPHERE) {
        const auto& sphere = static_cast<const urdf::Sphere&>(*c->geometry);
        if (!std::isfinite(sphere.radius) || sphere.radius < 0.0)
          return error("link '" + link.name + "': bad collision sphere radius");
        out.spheres.push_back({c->name, pose.translation(), sphere.radius});
      } else if (c->geometry->type == urdf::Geometry::BOX) {
        const auto& box = static_cast<const urdf::Box&>(*c->geometry);
        const Eigen::Vector3d size(box.dim.x, box.dim.y, box.dim.z);
        if (!finite(size) || size.minCoeff() <= 0.0)
          return error("link '" + link.name + "': bad collision box size");
        out.boxes.push_back({pose, size});
      } else {
        return error("link '" + link.name +
                     "': only sphere and box collision geometry is supported");
      }
    }
    return Status::ok();
  }

  Status add_children(const urdf::Link& link, int body, const Eigen::Isometry3d& link_in_body,
                      std::vector<LinkSpec>& links, std::vector<JointSpec>& joints) {
    std::vector<urdf::JointSharedPtr> children = link.child_joints;
    std::sort(children.begin(), children.end(),
              [](const auto& a, const auto& b) { return a->name < b->name; });
    for (const urdf::JointSharedPtr& joint : children) {
      const urdf::LinkConstSharedPtr child = urdf_.getLink(joint->child_link_name);
      if (!child) return error("joint '" + joint->name + "': missing child link");
      const Eigen::Isometry3d origin =
          link_in_body * to_isometry(joint->parent_to_joint_origin_transform);
      if (!finite(origin.translation()) || !origin.linear().allFinite())
        return error("joint '" + joint->name + "': non-finite origin");
      LinkSpec child_spec;
      if (Status s = read_link(*child, child_spec); !s) return s;
      if (joint->type == urdf::Joint::FIXED) {
        merge_into(links[static_cast<std::size_t>(body)], child_spec, origin);
        if (Status s = add_children(*child, body, origin, links, joints); !s) return s;
        continue;
      }
      if (joint->type != urdf::Joint::REVOLUTE && joint->type != urdf::Joint::CONTINUOUS)
        return error("joint '" + joint->name +
                     "': only revolute, continuous and fixed joints are supported");
      if (child_spec.mass <= 0.0)
        return error("link '" + child->name + "': a moving link needs an <inertial> mass");
      JointSpec spec;
      spec.name = joint->name;
      spec.parent_link = body;
      spec.origin = origin;
      spec.axis = Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z);
      if (!finite(spec.axis) || spec.axis.norm() < 1e-9)
        return error("joint '" + joint->name + "': axis must be a non-zero finite vector");
      spec.axis.normalize();
      if (joint->limits) {
        spec.effort = joint->limits->effort;
        spec.velocity = joint->limits->velocity;
        if (joint->type == urdf::Joint::REVOLUTE) {
          spec.limited = true;
          spec.lower = joint->limits->lower;
          spec.upper = joint->limits->upper;
          if (!std::isfinite(spec.lower) || !std::isfinite(spec.upper) || spec.lower >= spec.upper)
            return error("joint '" + joint->name + "': limit lower must be below upper");
        }
        if (!std::isfinite(spec.effort) || spec.effort < 0 || !std::isfinite(spec.velocity) ||
            spec.velocity < 0)
          return error("joint '" + joint->name + "': effort and velocity must be >= 0");
      } else if (joint->type == urdf::Joint::REVOLUTE) {
        return error("joint '" + joint->name + "': a revolute joint needs <limit>");
      }
      if (joint->dynamics) {
        spec.damping = joint->dynamics->damping;
        spec.friction = joint->dynamics->friction;
        if (!std::isfinite(spec.damping) || spec.damping < 0 || !std::isfinite(spec.friction) ||
            spec.friction < 0)
          return error("joint '" + joint->name + "': damping and friction must be >= 0");
      }
      spec.child_link = static_cast<int>(links.size());
      child_spec.parent_joint = static_cast<int>(joints.size());
      links.push_back(child_spec);
      joints.push_back(spec);
      if (Status s =
              add_children(*child, spec.child_link, Eigen::Isometry3d::Identity(), links, joints);
          !s)
        return s;
    }
    return Status::ok();
  }

  const urdf::ModelInterface& urdf_;
  std::string source_;
};

}  // namespace

Status RobotModel::load_string(const std::string& urdf_text, const std::string& source,
                               RobotModel& out) {
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  urdf::ModelInterfaceSharedPtr urdf;
  try {
    urdf = urdf::parseURDF(urdf_text);
  } catch (const std::exception& e) {
    return Status::error(source + ": URDF parse error: " + e.what());
  }
  if (!urdf)
    return Status::error(source +
                         ": not a valid URDF (malformed XML, missing element or broken tree)");
  RobotModel model;
  model.name_ = urdf->getName();
  Builder builder(*urdf, source);
  if (Status s = builder.build(model.links_, model.joints_); !s) return s;
  if (model.links_[0].mass <= 0.0)
    return Status::error(source + ": root link '" + model.links_[0].name + "' needs a mass");
  out = std::move(model);
  return Status::ok();
}

Status RobotModel::load_file(const std::filesystem::path& path, RobotModel& out) {
  std::ifstream in(path);
  if (!in) return Status::error(path.string() + ": cannot open URDF file");
  std::stringstream text;
  text << in.rdbuf();
  return load_string(text.str(), path.string(), out);
}

std::filesystem::path RobotModel::igus_path() {
  return std::filesystem::path(STRIDE_SIM_MODEL_DIR) / "igus_op.urdf";
}

int RobotModel::link_index(const std::string& name) const {
  for (std::size_t i = 0; i < links_.size(); ++i)
    if (links_[i].name == name) return static_cast<int>(i);
  return -1;
}

int RobotModel::joint_index(const std::string& name) const {
  for (std::size_t i = 0; i < joints_.size(); ++i)
    if (joints_[i].name == name) return static_cast<int>(i);
  return -1;
}

double RobotModel::total_mass() const {
  double m = 0.0;
  for (const LinkSpec& l : links_) m += l.mass;
  return m;
}

void RobotModel::adjust_link(std::size_t link, double mass_scale,
                             const Eigen::Vector3d& com_shift) {
  LinkSpec& l = links_.at(link);
  l.mass *= mass_scale;
  l.inertia *= mass_scale;
  l.com += com_shift;
}

}  // namespace stride::sim
