// RobotDescription loading, validation and kinematics (see the header).
#include "stride/firmware/robot_description.hpp"

#include <cmath>
#include <span>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "stride/core/json_file.hpp"
#include "stride/firmware/firmware.hpp"  // data_dir

namespace stride::fw {
namespace {

using nlohmann::json;

Status field_error(const std::string& where, const std::string& what) {
  return Status::error(where + ": " + what);
}

Status read_number(const json& object, const std::string& where, const char* key, double& out) {
  if (!object.contains(key)) return field_error(where + "." + key, "missing");
  const json& v = object[key];
  if (!v.is_number()) return field_error(where + "." + key, "must be a number, got " + v.dump());
  out = v.get<double>();
  if (!std::isfinite(out)) return field_error(where + "." + key, "must be finite");
  return {};
}

Status read_vector(const json& object, const std::string& where, const char* key,
                   Eigen::Vector3d& out) {
  if (!object.contains(key)) return field_error(where + "." + key, "missing");
  const json& v = object[key];
  if (!v.is_array() || v.size() != 3) {
    return field_error(where + "." + key, "must be an array of 3 numbers, got " + v.dump());
  }
  for (std::size_t i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) {
      return field_error(where + "." + key,
                         "must be an array of 3 finite numbers, got " + v.dump());
    }
    out[static_cast<Eigen::Index>(i)] = v[i].get<double>();
  }
  return {};
}

Status read_string(const json& object, const std::string& where, const char* key,
                   std::string& out) {
  if (!object.contains(key) || !object[key].is_string()) {
    return field_error(where + "." + key, "missing or not a string");
  }
  out = object[key].get<std::string>();
  return {};
}

Eigen::Matrix3d rpy_rotation(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

/// A joint's "parent": null (the root, -1) or the name of a joint listed before it (its index).
Status read_parent(const json& entry, const std::string& at,
                   std::span<const RobotDescription::Joint> before, int& parent) {
  if (!entry.contains("parent")) return field_error(at + ".parent", "missing");
  if (entry["parent"].is_null()) {
    parent = -1;
    return {};
  }
  if (!entry["parent"].is_string())
    return field_error(at + ".parent", "must be a joint name or null (the root)");
  const std::string name = entry["parent"].get<std::string>();
  for (std::size_t k = before.size(); k-- > 0;) {  // the latest of that name
    if (before[k].name == name) {
      parent = static_cast<int>(k);
      return {};
    }
  }
  return field_error(at + ".parent", "'" + name + "' is not a joint listed before this one");
}

/// A joint's origin (xyz, rpy), unit axis, and its child link's mass and centre of mass.
Status read_joint_body(const json& entry, const std::string& at, RobotDescription::Joint& joint) {
  Eigen::Vector3d rpy;
  if (Status s = read_vector(entry, at, "xyz", joint.origin_position); !s) return s;
  if (Status s = read_vector(entry, at, "rpy", rpy); !s) return s;
  joint.origin_rotation = rpy_rotation(rpy);
  if (Status s = read_vector(entry, at, "axis", joint.axis); !s) return s;
  if (std::abs(joint.axis.norm() - 1.0) > 1e-6) {
    return field_error(at + ".axis", "must be a unit vector");
  }
  if (Status s = read_number(entry, at, "mass", joint.mass); !s) return s;
  if (!(joint.mass > 0.0)) return field_error(at + ".mass", "must be > 0");
  return read_vector(entry, at, "com", joint.com);
}

}  // namespace

Status RobotDescription::load(const std::filesystem::path& path, const ServoTable& servos,
                              RobotDescription& out) {
  std::string text;  // the text itself, not only its JSON: the description's hash is of the text
  if (Status s = core::read_text_file(path, text); !s) return s;
  return parse(text, path.filename().string(), servos, out);
}

Status RobotDescription::parse(const std::string& text, const std::string& where,
                               const ServoTable& servos, RobotDescription& out) {
  json doc;
  if (Status s = core::parse_json_text(text, where, doc); !s) return s;
  if (!doc.is_object()) return Status::error(where + ": must be a JSON object");
  RobotDescription d;
  d.hash_ = fnv1a(text);
  if (!doc.contains("root") || !doc["root"].is_object()) {
    return field_error(where + ".root", "missing or not an object");
  }
  const json& root = doc["root"];
  if (Status s = read_number(root, where + ".root", "mass", d.root_mass_); !s) return s;
  if (!(d.root_mass_ > 0.0)) return field_error(where + ".root.mass", "must be > 0");
  if (Status s = read_vector(root, where + ".root", "com", d.root_com_); !s) return s;
  if (!doc.contains("joints") || !doc["joints"].is_array()) {
    return field_error(where + ".joints", "missing or not an array");
  }
  const json& joints = doc["joints"];
  if (joints.size() != kJoints) {
    return field_error(where + ".joints", "must list the " + std::to_string(kJoints) +
                                              " servo joints, got " +
                                              std::to_string(joints.size()));
  }
  std::array<bool, hal::kServoCount> seen{};
  d.total_mass_ = d.root_mass_;
  for (std::size_t j = 0; j < kJoints; ++j) {
    const std::string at = where + ".joints[" + std::to_string(j) + "]";
    const json& entry = joints[j];
    if (!entry.is_object()) return field_error(at, "must be an object");
    Joint& joint = d.joints_[j];
    if (Status s = read_string(entry, at, "name", joint.name); !s) return s;
    if (Status s = read_string(entry, at, "link", joint.link); !s) return s;
    std::string servo;
    if (Status s = read_string(entry, at, "servo", servo); !s) return s;
    const auto index = servos.index_of(servo);
    if (!index) {
      return field_error(at + ".servo", "'" + servo + "' is not in the servo table");
    }
    if (seen[*index]) return field_error(at + ".servo", "'" + servo + "' is listed twice");
    seen[*index] = true;
    joint.servo = *index;
    d.joint_of_servo_[*index] = j;
    if (Status s = read_parent(entry, at, std::span(d.joints_.data(), j), joint.parent); !s)
      return s;
    if (Status s = read_joint_body(entry, at, joint); !s) return s;
    d.total_mass_ += joint.mass;
    d.ancestor_mask_[j] =
        (joint.parent >= 0 ? d.ancestor_mask_[static_cast<std::size_t>(joint.parent)] : 0U) |
        (1U << j);
  }
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    if (!seen[i]) {
      return field_error(where + ".joints",
                         "servo '" + servos[i].name + "' of the servo table has no joint");
    }
  }
  out = std::move(d);
  return {};
}

std::filesystem::path RobotDescription::default_path() {
  return data_dir() / "config" / "robot_description.json";
}

const RobotDescription& RobotDescription::defaults() {
  static const RobotDescription description = [] {
    RobotDescription d;
    if (Status s = load(default_path(), ServoTable::defaults(), d); !s) {
      throw std::runtime_error(s.message());
    }
    return d;
  }();
  return description;
}

void RobotDescription::compute_frames(const std::array<double, hal::kServoCount>& q,
                                      Frames& out) const noexcept {
  for (std::size_t j = 0; j < kJoints; ++j) {
    const Joint& joint = joints_[j];
    const bool at_root = joint.parent < 0;
    const auto parent = static_cast<std::size_t>(at_root ? 0 : joint.parent);
    const Eigen::Matrix3d parent_rotation =
        at_root ? Eigen::Matrix3d::Identity() : out.rotation[parent];
    const Eigen::Vector3d parent_position =
        at_root ? Eigen::Vector3d::Zero() : out.position[parent];
    const Eigen::Matrix3d joint_frame = parent_rotation * joint.origin_rotation;
    const double angle = std::isfinite(q[joint.servo]) ? q[joint.servo] : 0.0;
    out.position[j] = parent_position + parent_rotation * joint.origin_position;
    out.axis[j] = joint_frame * joint.axis;
    out.rotation[j] = joint_frame * Eigen::AngleAxisd(angle, joint.axis).toRotationMatrix();
    out.com[j] = out.position[j] + out.rotation[j] * joint.com;
  }
}

Eigen::Vector3d RobotDescription::center_of_mass(const Frames& frames) const noexcept {
  Eigen::Vector3d sum = root_mass_ * root_com_;
  for (std::size_t j = 0; j < kJoints; ++j) sum += joints_[j].mass * frames.com[j];
  return sum / total_mass_;
}

}  // namespace stride::fw
