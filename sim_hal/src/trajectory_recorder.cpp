// TrajectoryRecorder: JSON-lines trajectory of an episode.
#include "stride/sim_hal/trajectory_recorder.hpp"

#include <nlohmann/json.hpp>

#include "stride/core/atomic_file.hpp"

namespace stride::sim {
namespace {

nlohmann::json vec(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

void TrajectoryRecorder::record(hal::Tick tick, const SimWorld& world,
                                const hal::SensorFrame& sensors,
                                const hal::CommandFrame& commands) {
  if (tick % every_ != 0) return;
  if (lines_ == 0) {
    nlohmann::json header = {
        {"format", "stride-trajectory"},
        {"version", 1},
        {"period_s", static_cast<double>(world.options().control_period_ns) * 1e-9},
        {"joints", world.options().servo_joints}};
    text_ += header.dump() + "\n";
  }
  const GroundTruth g = world.ground_truth();
  const Eigen::Quaterniond q(g.torso.linear());
  nlohmann::json joints = nlohmann::json::array();
  nlohmann::json goals = nlohmann::json::array();
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    joints.push_back(world.servo_joint_angle(i));
    goals.push_back(commands.servos[i].position_rad);
  }
  auto contact = [](const FootContact& c) {
    return nlohmann::json{{"points", c.points_in_contact}, {"force", vec(c.force)}};
  };
  const auto& a = sensors.cm730.accel_mps2;
  const auto& w = sensors.cm730.gyro_rad_s;
  nlohmann::json line = {{"tick", tick},
                         {"t", g.time_s},
                         {"torso",
                          {{"p", vec(g.torso.translation())},
                           {"q", {q.w(), q.x(), q.y(), q.z()}},
                           {"v", vec(g.torso_linear_velocity)},
                           {"w", vec(g.torso_angular_velocity)}}},
                         {"com", vec(g.center_of_mass)},
                         {"joints", joints},
                         {"goals", goals},
                         {"imu", {{"acc", {a[0], a[1], a[2]}}, {"gyro", {w[0], w[1], w[2]}}}},
                         {"contacts",
                          {{"left", contact(g.left_contact)},
                           {"right", contact(g.right_contact)},
                           {"other", g.other_contacts}}},
                         {"ball", {{"p", vec(g.ball_position)}, {"v", vec(g.ball_velocity)}}}};
  if (sensors.cm730.has_magnetometer) {
    const auto& m = sensors.cm730.mag_gauss;
    line["imu"]["mag"] = {m[0], m[1], m[2]};
  }
  text_ += line.dump() + "\n";
  ++lines_;
}

Status TrajectoryRecorder::save(const std::filesystem::path& path) const {
  return core::write_file_atomically(path, text_);
}

}  // namespace stride::sim
