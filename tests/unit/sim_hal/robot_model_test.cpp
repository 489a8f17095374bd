// Tests of the URDF loader and the igus model's figures (igus.md section 1).
#include <gtest/gtest.h>

#include <cmath>

#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim {
namespace {

TEST(RobotModel, IgusModelHas20RevoluteJointsAndTheDocumentedMass) {
  RobotModel model;
  const Status s = RobotModel::load_file(RobotModel::igus_path(), model);
  ASSERT_TRUE(s) << s.message();
  EXPECT_EQ(model.joints().size(), 20U);
  EXPECT_EQ(model.links().size(), 21U);
  EXPECT_EQ(model.links()[0].name, "trunk_link");
  // igus.md 1.2: total mass 6.4601 kg computed from the URDF; within 1 %.
  EXPECT_NEAR(model.total_mass(), 6.4601, 0.01 * 6.4601);
  for (const JointSpec& j : model.joints()) {
    EXPECT_TRUE(j.limited) << j.name;
    EXPECT_LT(j.lower, j.upper) << j.name;
    EXPECT_GT(j.effort, 0.0) << j.name;
    EXPECT_GT(j.velocity, 0.0) << j.name;
  }
}

TEST(RobotModel, EachSoleHasFourStudsEighteenMillimetresBelowTheSole) {
  RobotModel model;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), model));
  for (const char* foot : {"left_foot_link", "right_foot_link"}) {
    const int index = model.link_index(foot);
    ASSERT_GE(index, 0);
    const LinkSpec& link = model.links()[static_cast<std::size_t>(index)];
    int studs = 0;
    for (const CollisionSphere& s : link.spheres) {
      if (s.name.rfind("stud", 0) != 0) continue;
      ++studs;
      EXPECT_NEAR(s.center.z() - s.radius, -0.0565, 1e-6);  // stud tip (igus.md 1.3)
    }
    EXPECT_EQ(studs, 4) << foot;
    ASSERT_EQ(link.boxes.size(), 1U);
    const double sole = link.boxes[0].pose.translation().z() - link.boxes[0].size.z() / 2;
    EXPECT_NEAR(sole, -0.0383, 1e-6);
  }
}

TEST(RobotModel, ZeroPoseCentreOfMassMatchesTheFigure) {
  RobotModel model;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), model));
  // Forward kinematics at zero angles (every joint frame = origin transform).
  std::vector<Eigen::Isometry3d> pose(model.links().size(), Eigen::Isometry3d::Identity());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const JointSpec& j : model.joints())
    pose[static_cast<std::size_t>(j.child_link)] =
        pose[static_cast<std::size_t>(j.parent_link)] * j.origin;
  for (std::size_t l = 0; l < model.links().size(); ++l)
    sum += model.links()[l].mass * (pose[l] * model.links()[l].com);
  const Eigen::Vector3d com = sum / model.total_mass();
  // igus.md 1.2: (-0.0096, 0, -0.1377) m in the trunk frame, 0.424 m above the flat sole.
  EXPECT_NEAR(com.x(), -0.0096, 0.001);
  EXPECT_NEAR(com.y(), 0.0, 0.001);
  EXPECT_NEAR(com.z(), -0.1377, 0.001);
  const int foot = model.link_index("left_foot_link");
  const double sole_z = pose[static_cast<std::size_t>(foot)].translation().z() - 0.0383;
  EXPECT_NEAR(com.z() - sole_z, 0.424, 0.003);
}

const char* kTwoLink = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="plate"><inertial><origin xyz="0 0 0.1"/><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="arm"><inertial><mass value="0.2"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.02"/></geometry></collision></link>
  <joint name="weld" type="fixed"><parent link="base"/><child link="plate"/><origin xyz="0 0 0.2"/></joint>
  <joint name="hinge" type="continuous"><parent link="plate"/><child link="arm"/><origin xyz="0 0 0.1"/><axis xyz="0 0 2"/></joint>
</robot>)";

TEST(RobotModel, LoadsAnyRevoluteTreeAndMergesFixedJoints) {
  RobotModel model;
  const Status s = RobotModel::load_string(kTwoLink, "two_link", model);
  ASSERT_TRUE(s) << s.message();
  ASSERT_EQ(model.links().size(), 2U);
  ASSERT_EQ(model.joints().size(), 1U);
  EXPECT_NEAR(model.links()[0].mass, 1.5, 1e-12);
  EXPECT_NEAR(model.links()[0].com.z(), 0.5 * 0.3 / 1.5, 1e-12);
  EXPECT_NEAR(model.joints()[0].origin.translation().z(), 0.3, 1e-12);  // through the weld
  EXPECT_NEAR(model.joints()[0].axis.norm(), 1.0, 1e-12);
  EXPECT_FALSE(model.joints()[0].limited);
}

TEST(RobotModel, RejectsBrokenFilesWithAClearError) {
  RobotModel model;
  Status s = RobotModel::load_string("<robot name='x'><link name='a'>", "broken.urdf", model);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("broken.urdf"), std::string::npos);

  std::string prismatic = kTwoLink;
  prismatic.replace(prismatic.find("continuous"), 10, "floating");
  s = RobotModel::load_string(prismatic, "p.urdf", model);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("hinge"), std::string::npos) << s.message();

  std::string negative = kTwoLink;
  negative.replace(negative.find("value=\"0.2\""), 11, "value=\"-1\"");
  s = RobotModel::load_string(negative, "m.urdf", model);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("mass"), std::string::npos) << s.message();

  s = RobotModel::load_file("/nonexistent/robot.urdf", model);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("/nonexistent/robot.urdf"), std::string::npos);
}

}  // namespace
}  // namespace stride::sim
