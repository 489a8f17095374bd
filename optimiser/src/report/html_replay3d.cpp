// The 3D replay's data (robot description, motion per individual), three.js and the section.
#include "stride/optimiser/report/html_replay3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "assets.hpp"

namespace stride::opt::report {
namespace {

constexpr const char* kDebianThreeJs = "/usr/share/javascript/three/three.min.js";

void put_int16(std::string& bytes, double value) {
  const double v = std::isfinite(value) ? std::clamp(std::round(value), -32767.0, 32767.0) : 0.0;
  const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
  bytes.push_back(static_cast<char>(u & 0xff));
  bytes.push_back(static_cast<char>(u >> 8));
}

// 0.1 mm: enough for drawing, short in the JSON.
double tenth_mm(double metres) {
  return std::round(metres * 1e4) / 1e4;
}

nlohmann::json pose_json(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d p = pose.translation();
  auto r4 = [](double v) { return std::round(v * 1e4) / 1e4; };
  return {tenth_mm(p.x()), tenth_mm(p.y()), tenth_mm(p.z()), r4(q.w()),
          r4(q.x()),       r4(q.y()),       r4(q.z())};
}

}  // namespace

std::string three_js_path() {
  const char* env = std::getenv("STRIDE_THREE_JS");
  return env != nullptr && *env != '\0' ? env : kDebianThreeJs;
}

std::string load_three_js(std::string& problem) {
  const std::string path = three_js_path();
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  const std::string code = text.str();
  if (!in || code.find("REVISION") == std::string::npos) {
    problem = "the 3D replay is unavailable: three.js not found at " + path +
              " (install Debian's libjs-three: toolchain/install-deps.sh)";
    return "";
  }
  return code;
}

nlohmann::json robot3d_model(const sim::RobotModel& model, std::string& problem) {
  if (model.links().empty()) {
    problem = "the 3D replay is unavailable: the robot model could not be loaded";
    return nullptr;
  }
  nlohmann::json links = nlohmann::json::array(), joints = nlohmann::json::array();
  std::size_t shapes = 0;
  for (const sim::LinkSpec& link : model.links()) {
    nlohmann::json boxes = nlohmann::json::array(), spheres = nlohmann::json::array();
    for (const sim::CollisionBox& b : link.boxes) {
      nlohmann::json box = pose_json(b.pose);
      for (int k = 0; k < 3; ++k) box.push_back(tenth_mm(b.size[k]));
      boxes.push_back(box);
    }
    for (const sim::CollisionSphere& s : link.spheres)
      spheres.push_back({tenth_mm(s.center.x()), tenth_mm(s.center.y()), tenth_mm(s.center.z()),
                         tenth_mm(s.radius), s.name.rfind("stud", 0) == 0 ? 1 : 0});
    shapes += link.boxes.size() + link.spheres.size();
    links.push_back({{"name", link.name}, {"boxes", boxes}, {"spheres", spheres}});
  }
  for (const sim::JointSpec& j : model.joints())
    joints.push_back({{"name", j.name},
                      {"parent", j.parent_link},
                      {"child", j.child_link},
                      {"origin", pose_json(j.origin)},
                      {"axis", {j.axis.x(), j.axis.y(), j.axis.z()}}});
  if (shapes == 0) {
    problem = "the 3D replay is unavailable: the robot model (" + model.name() +
              ") has no box or sphere collision geometry to draw";
    return nullptr;
  }
  return {{"name", model.name()},
          {"links", links},
          {"joints", joints},
          {"feet", {model.link_index("left_foot_link"), model.link_index("right_foot_link")}},
          {"values_per_frame", 3 + 4 + model.joints().size() + 6 + 3}};
}

std::string robot3d_motion(const sim::RobotModel& model, const ReplayIndividual& individual,
                           std::string& problem) {
  const auto& frames = individual.capture.frames;
  if (frames.empty()) {
    problem = individual.name + ": no trajectory was recorded";
    return "";
  }
  const std::size_t joints = model.joints().size();
  std::string bytes;
  bytes.reserve(frames.size() * (16 + joints) * 2);
  for (const sim::PoseSnapshot& f : frames) {
    if (f.links.empty() || f.joint_angles.size() != joints) {
      problem = individual.name + ": the trajectory at " + format_number(f.time_s, 3) + " s has " +
                std::to_string(f.joint_angles.size()) + " joint angles, the robot model " +
                std::to_string(joints);
      return "";
    }
    const Eigen::Vector3d p = f.links.front().translation();
    Eigen::Quaterniond q(f.links.front().linear());
    q.normalize();
    for (int k = 0; k < 3; ++k) put_int16(bytes, p[k] * 1000.0);
    for (double v : {q.w(), q.x(), q.y(), q.z()}) put_int16(bytes, v * 1e4);
    for (double a : f.joint_angles) put_int16(bytes, a * 1e4);
    for (int k = 0; k < 3; ++k) put_int16(bytes, f.left_foot_force[k]);
    for (int k = 0; k < 3; ++k) put_int16(bytes, f.right_foot_force[k]);
    for (int k = 0; k < 3; ++k) put_int16(bytes, f.ball[k] * 1000.0);
  }
  return base64(bytes);
}

void add_replay_section(HtmlPage& page, const std::string& note, const sim::RobotModel& model,
                        const std::vector<ReplayIndividual>& individuals, const ReplayScene& scene,
                        std::vector<std::string>& warnings) {
  nlohmann::json data = replay_data(model, individuals, scene);
  std::string problem;
  const std::string three = load_three_js(problem);
  nlohmann::json robot = problem.empty() ? robot3d_model(model, problem) : nlohmann::json();
  std::vector<std::string> broken;
  if (problem.empty()) {
    for (std::size_t i = 0; i < individuals.size(); ++i) {
      std::string why;
      data["individuals"][i]["motion"] = robot3d_motion(model, individuals[i], why);
      data["individuals"][i]["motion_frames"] =
          why.empty() ? individuals[i].capture.frames.size() : 0;
      if (!why.empty()) broken.push_back(why);
    }
    if (individuals.empty())
      problem = "the 3D replay is unavailable: no trajectory was recorded";
    else if (broken.size() == individuals.size())
      problem = "the 3D replay is unavailable: " + broken.front();
    else if (!broken.empty())
      problem = "the 3D replay leaves out " + broken.front() +
                (broken.size() > 1 ? " (and " + std::to_string(broken.size() - 1) + " more)" : "");
  }
  const bool drawable = !three.empty() && !robot.is_null() && broken.size() < individuals.size();
  std::string view;
  if (drawable) {
    data["robot3d"] = robot;
    view =
        "<div id=\"replay3d\" data-state=\"loading\">"
        "<div id=\"replay3d-controls\">"
        "<label>show <select id=\"replay3d-compare\"></select></label>"
        "<label>layout <select id=\"replay3d-layout\"><option value=\"side\" selected>side by "
        "side</option><option value=\"ghost\">ghosted</option></select></label>"
        "<label><input id=\"replay3d-follow\" type=\"checkbox\" checked> follow</label>"
        "<label><input id=\"replay3d-forces\" type=\"checkbox\" checked> contact forces</label>"
        "<button id=\"replay3d-reset\" type=\"button\">reset view</button>"
        "<span class=\"hint\">drag: orbit, wheel: zoom, shift-drag: pan</span></div>"
        "<div id=\"replay3d-view\"></div><div id=\"replay3d-status\"></div>" +
        (broken.empty() ? std::string() : missing_note(problem)) + "</div>\n";
    page.add_script("three-js",
                    "/* three.js r111 (MIT licence), inlined from Debian's libjs-three: " +
                        three_js_path() + " */\n" + three);
    page.add_script("replay3d-js", assets::kReplay3dJs);
  } else {
    view = "<div id=\"replay3d\" data-state=\"unavailable\">" +
           missing_note("The 3D view is unavailable: " + problem.substr(problem.find(": ") + 2) +
                        ".") +
           "</div>\n";
  }
  if (!problem.empty()) warnings.push_back(problem);
  std::string body = replay_section_html();
  body.insert(body.find("<div id=\"replay-cards\">"), view);
  page.add_section("replay", "Replay", note + body);
  page.set_replay_data(data);
}

}  // namespace stride::opt::report
