// RobotDescription: the shipped file loads and matches the servo table; its kinematics agree
// with the walk's closed-form leg kinematics; a file that does not match the servo table, or is
// broken, is one error naming the field.
#include "stride/firmware/robot_description.hpp"

#include <fstream>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/firmware/walk/leg_kinematics.hpp"

namespace stride::fw {
namespace {

nlohmann::json shipped() {
  std::ifstream in(RobotDescription::default_path());
  return nlohmann::json::parse(in);
}

std::string parse_error(const nlohmann::json& doc) {
  RobotDescription d;
  const Status s = RobotDescription::parse(doc.dump(), "robot.json", ServoTable::defaults(), d);
  EXPECT_FALSE(s.is_ok());
  return s.message();
}

TEST(RobotDescription, TheShippedFileLoadsWithTheUrdfsMass) {
  const RobotDescription& d = RobotDescription::defaults();
  EXPECT_NEAR(d.total_mass(), 6.460126, 1e-6);  // igus_op.urdf's links summed
  EXPECT_NEAR(d.root_mass(), 1.8051, 1e-9);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    EXPECT_EQ(d.joints()[d.joint_of_servo(i)].servo, i);
  }
}

TEST(RobotDescription, LegFramesAgreeWithTheWalksLegKinematics) {
  const RobotDescription& d = RobotDescription::defaults();
  const ServoTable& servos = ServoTable::defaults();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-0.6, 0.6);
  std::uniform_real_distribution<double> knee(0.0, 1.8);
  for (int trial = 0; trial < 50; ++trial) {
    for (const auto side : {walk::LegSide::kLeft, walk::LegSide::kRight}) {
      const std::string p = side == walk::LegSide::kLeft ? "l_" : "r_";
      const walk::LegJoints q{angle(rng), angle(rng), angle(rng),
                              knee(rng),  angle(rng), angle(rng)};
      std::array<double, hal::kServoCount> pose{};
      const double values[] = {q.hip_yaw, q.hip_roll,    q.hip_pitch,
                               q.knee,    q.ankle_pitch, q.ankle_roll};
      const char* names[] = {"hip_yaw", "hip_roll",    "hip_pitch",
                             "knee",    "ankle_pitch", "ankle_roll"};
      for (int k = 0; k < 6; ++k) pose[*servos.index_of(p + names[k])] = values[k];
      RobotDescription::Frames frames;
      d.compute_frames(pose, frames);
      const std::size_t foot = d.joint_of_servo(*servos.index_of(p + "ankle_roll"));
      const walk::Pose3 expected = walk::LegKinematics(side).forward(q);
      EXPECT_LT((frames.position[foot] - expected.position).norm(), 1e-9) << trial;
      EXPECT_LT((frames.rotation[foot] - expected.rotation).norm(), 1e-9) << trial;
    }
  }
}

TEST(RobotDescription, AncestorsFollowTheTree) {
  const RobotDescription& d = RobotDescription::defaults();
  const ServoTable& servos = ServoTable::defaults();
  auto joint = [&](const char* name) { return d.joint_of_servo(*servos.index_of(name)); };
  EXPECT_TRUE(d.is_ancestor(joint("l_hip_yaw"), joint("l_ankle_roll")));
  EXPECT_TRUE(d.is_ancestor(joint("l_knee"), joint("l_knee")));
  EXPECT_FALSE(d.is_ancestor(joint("l_knee"), joint("l_hip_pitch")));
  EXPECT_FALSE(d.is_ancestor(joint("r_hip_yaw"), joint("l_ankle_roll")));
}

TEST(RobotDescription, AFileThatDoesNotMatchTheServoTableIsOneErrorNamingTheField) {
  auto doc = shipped();
  doc["joints"][3]["servo"] = "l_tail";
  EXPECT_EQ(parse_error(doc), "robot.json.joints[3].servo: 'l_tail' is not in the servo table");
  doc = shipped();
  doc["joints"][3]["servo"] = doc["joints"][2]["servo"];
  EXPECT_NE(parse_error(doc).find("joints[3].servo: "), std::string::npos);
  doc = shipped();
  doc["joints"].erase(doc["joints"].size() - 1);
  EXPECT_NE(parse_error(doc).find("must list the 20 servo joints, got 19"), std::string::npos);
}

TEST(RobotDescription, BrokenValuesAreOneErrorNamingTheField) {
  auto doc = shipped();
  doc["joints"][0]["mass"] = -1.0;
  EXPECT_EQ(parse_error(doc), "robot.json.joints[0].mass: must be > 0");
  doc = shipped();
  doc["joints"][1]["axis"] = {0.0, 2.0, 0.0};
  EXPECT_EQ(parse_error(doc), "robot.json.joints[1].axis: must be a unit vector");
  doc = shipped();
  doc["joints"][0]["parent"] = "left_knee_pitch";
  EXPECT_NE(parse_error(doc).find("joints[0].parent: 'left_knee_pitch' is not a joint listed"),
            std::string::npos);
  doc = shipped();
  doc["root"]["com"] = {0.0, 1.0};
  EXPECT_NE(parse_error(doc).find("robot.json.root.com: must be an array of 3"), std::string::npos);
  RobotDescription d;
  const Status s = RobotDescription::parse("{\"root\": ", "robot.json", ServoTable::defaults(), d);
  EXPECT_NE(s.message().find("robot.json: not valid JSON"), std::string::npos);
  EXPECT_FALSE(RobotDescription::load("/nonexistent/robot.json", ServoTable::defaults(), d));
}

}  // namespace
}  // namespace stride::fw
