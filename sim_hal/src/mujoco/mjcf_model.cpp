// MJCF writer for the MuJoCo engine (see mjcf_model.hpp for the model's choices).
#include "mjcf_model.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace stride::sim::mujoco {
namespace {

/// Full-precision number (round-trips exactly).
std::string num(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string vec(const Eigen::Vector3d& v) {
  return num(v.x()) + " " + num(v.y()) + " " + num(v.z());
}

/// MuJoCo's quaternion order: w x y z.
std::string quat(const Eigen::Matrix3d& rotation) {
  const Eigen::Quaterniond q(rotation);
  return num(q.w()) + " " + num(q.x()) + " " + num(q.y()) + " " + num(q.z());
}

// Contact bits (see the header): robot-field and ball-field, never robot-robot.
constexpr const char* kRobotBits = R"( contype="1" conaffinity="2")";
constexpr const char* kFieldBits = R"( contype="2" conaffinity="1")";
constexpr const char* kBallBits = R"( contype="0" conaffinity="2")";

struct Writer {
  const EngineModel& m;
  const RobotModel& robot;
  std::vector<std::vector<std::size_t>> children;  // per link: child joint indices
  std::string out;
  std::string friction;

  void line(int depth, const std::string& text) {
    out.append(static_cast<std::size_t>(2 * depth), ' ');
    out += text;
    out += '\n';
  }

  void link_contents(std::size_t l, int depth) {
    const LinkSpec& link = robot.links()[l];
    const double s = m.link_mass_scale[l];
    const Eigen::Matrix3d& i = link.inertia;
    const Eigen::Vector3d com = l == 0 ? Eigen::Vector3d(link.com + m.root_com_shift) : link.com;
    line(depth, "<inertial pos=\"" + vec(com) + "\" mass=\"" + num(s * link.mass) +
                    "\" fullinertia=\"" + num(s * i(0, 0)) + " " + num(s * i(1, 1)) + " " +
                    num(s * i(2, 2)) + " " + num(s * i(0, 1)) + " " + num(s * i(0, 2)) + " " +
                    num(s * i(1, 2)) + "\"/>");
    for (std::size_t k = 0; k < link.spheres.size(); ++k) {
      const CollisionSphere& sphere = link.spheres[k];
      line(depth, "<geom name=\"l" + std::to_string(l) + "s" + std::to_string(k) +
                      "\" type=\"sphere\" size=\"" + num(sphere.radius) + "\" pos=\"" +
                      vec(sphere.center) + "\"" + kRobotBits + friction + "/>");
    }
    for (std::size_t k = 0; k < link.boxes.size(); ++k) {
      const CollisionBox& box = link.boxes[k];
      line(depth, "<geom name=\"l" + std::to_string(l) + "b" + std::to_string(k) +
                      "\" type=\"box\" size=\"" + vec(box.size / 2.0) + "\" pos=\"" +
                      vec(box.pose.translation()) + "\" quat=\"" + quat(box.pose.linear()) + "\"" +
                      kRobotBits + friction + "/>");
    }
    for (std::size_t j : children[l]) {
      const JointSpec& joint = robot.joints()[j];
      const auto child = static_cast<std::size_t>(joint.child_link);
      line(depth, "<body name=\"l" + std::to_string(child) + "\" pos=\"" +
                      vec(joint.origin.translation()) + "\" quat=\"" + quat(joint.origin.linear()) +
                      "\">");
      line(depth + 1, "<joint name=\"j" + std::to_string(j) + "\" type=\"hinge\" axis=\"" +
                          vec(joint.axis) + "\" armature=\"" + num(m.joint_armature[j]) +
                          "\" limited=\"false\" damping=\"0\" frictionloss=\"0\"/>");
      link_contents(child, depth + 1);
      line(depth, "</body>");
    }
  }
};

}  // namespace

std::string write_mjcf(const EngineModel& model) {
  const RobotModel& robot = *model.robot;
  Writer w{model, robot, {}, {}, {}};
  w.children.resize(robot.links().size());
  for (std::size_t j = 0; j < robot.joints().size(); ++j)
    w.children[static_cast<std::size_t>(robot.joints()[j].parent_link)].push_back(j);
  const std::string mu = num(model.friction);
  w.friction = " condim=\"3\" friction=\"" + mu + " 0.005 0.0001\"";

  w.line(0, "<mujoco model=\"stride\">");
  w.line(1, R"(<compiler angle="radian" inertiafromgeom="false" boundmass="0" boundinertia="0"/>)");
  w.line(1, "<option timestep=\"" + num(model.step_s) + "\" gravity=\"0 0 " +
                num(-model.gravity_mps2) +
                "\" integrator=\"Euler\" cone=\"elliptic\" solver=\"Newton\" impratio=\"" +
                num(kImpRatio) + "\" iterations=\"100\" tolerance=\"1e-8\"/>");
  // Fixed buffers (2.2 allocates mjData from these). The robot lying on turf with the ball
  // beside it stays far below them; 2.2 keeps an njmax x njmax matrix (efc_AR) that every
  // mj_resetData clears, so they are no larger than that needs (2000 rows took a fifth of a
  // 4 s episode's instructions). A step that fills them ends the episode (mujoco_engine.cpp).
  w.line(1, "<size njmax=\"" + std::to_string(kMaxConstraintRows) + "\" nconmax=\"" +
                std::to_string(kMaxContacts) + "\"/>");
  w.line(1, "<worldbody>");
  // solmix 0: a robot or ball contact with the field takes the other geom's parameters.
  w.line(2, "<geom name=\"grass\" type=\"plane\" size=\"0 0 1\" pos=\"0 0 " +
                num(model.contact.grass_thickness_m) + "\" solmix=\"0\"" + kFieldBits + w.friction +
                "/>");
  if (model.contact.mujoco_solid_ground)  // touched only through the pairs below
    w.line(2, R"(<geom name="ground" type="plane" size="0 0 1" pos="0 0 0" contype="0" )"
              R"(conaffinity="0"/>)");
  w.line(2, "<body name=\"l0\">");
  w.line(3, R"(<freejoint name="root"/>)");
  w.link_contents(0, 3);
  w.line(2, "</body>");
  if (model.ball.present) {
    const BallOptions& b = model.ball;
    w.line(2, "<body name=\"ball\">");
    w.line(3, R"(<freejoint name="ball"/>)");
    w.line(3, "<inertial pos=\"0 0 0\" mass=\"" + num(b.mass_kg) + "\" diaginertia=\"" +
                  num(b.inertia_kg_m2) + " " + num(b.inertia_kg_m2) + " " + num(b.inertia_kg_m2) +
                  "\"/>");
    w.line(3, "<geom name=\"ball\" type=\"sphere\" size=\"" + num(b.radius_m) + "\"" + kBallBits +
                  w.friction + "/>");
    w.line(2, "</body>");
  }
  w.line(1, "</worldbody>");
  // Robot geom names in model order.
  std::vector<std::string> robot_geoms;
  for (std::size_t l = 0; l < robot.links().size(); ++l) {
    const LinkSpec& link = robot.links()[l];
    for (std::size_t k = 0; k < link.spheres.size(); ++k)
      robot_geoms.push_back("l" + std::to_string(l) + "s" + std::to_string(k));
    for (std::size_t k = 0; k < link.boxes.size(); ++k)
      robot_geoms.push_back("l" + std::to_string(l) + "b" + std::to_string(k));
  }
  if (model.ball.present || model.contact.mujoco_solid_ground) {
    w.line(1, "<contact>");
    if (model.ball.present)                        // the ball against every robot geom
      for (const std::string& geom : robot_geoms)  // frictionless, as in Stride's contact law
        w.line(2, "<pair geom1=\"ball\" geom2=\"" + geom + "\" condim=\"1\"/>");
    if (model.contact.mujoco_solid_ground)  // the solid ground under the grass (contact_params)
      for (const std::string& geom : robot_geoms)
        w.line(2, "<pair geom1=\"ground\" geom2=\"" + geom + "\" condim=\"3\" friction=\"" + mu +
                      " " + mu + " 0.005 0.0001 0.0001\"/>");
    w.line(1, "</contact>");
  }
  w.line(0, "</mujoco>");
  return w.out;
}

}  // namespace stride::sim::mujoco
