// sim_hal/models/make_variants.py: the robots that differ from the model as real ones do
// (issue 20) load, and each differs in exactly what its name says.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "robot_variants.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

TEST(RobotVariants, EachDiffersFromTheModelInWhatItsNameSays) {
  test::TempDir tmp;
  int code = -1;
  const std::string out = test::write_robot_variants(tmp.path(), code);
  ASSERT_EQ(code, 0) << out;
  RobotModel base;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), base));
  std::map<std::string, RobotModel> robots;
  for (const char* name : test::kRobotVariants) {
    const Status s =
        RobotModel::load_file(tmp.path() / (std::string(name) + ".urdf"), robots[name]);
    ASSERT_TRUE(s) << s.message();
  }
  const int trunk = base.link_index("trunk_link");
  const LinkSpec& t = base.links()[static_cast<std::size_t>(trunk)];
  auto trunk_of = [&](const char* name) -> const LinkSpec& {
    return robots.at(name).links()[static_cast<std::size_t>(trunk)];
  };
  EXPECT_NEAR(trunk_of("trunk_mass_plus_10pct").mass, 1.1 * t.mass, 1e-12);
  EXPECT_NEAR(trunk_of("trunk_mass_minus_10pct").mass, 0.9 * t.mass, 1e-12);
  EXPECT_NEAR(trunk_of("trunk_mass_plus_10pct").inertia(0, 0), 1.1 * t.inertia(0, 0), 1e-12);
  EXPECT_NEAR(trunk_of("trunk_com_1cm_forward").com.x() - t.com.x(), 0.01, 1e-12);
  EXPECT_NEAR(trunk_of("trunk_com_1cm_backward").com.x() - t.com.x(), -0.01, 1e-12);
  EXPECT_NEAR(trunk_of("trunk_com_1cm_left").com.y() - t.com.y(), 0.01, 1e-12);
  EXPECT_NEAR(trunk_of("trunk_com_1cm_right").com.y() - t.com.y(), -0.01, 1e-12);
  EXPECT_NEAR(robots.at("trunk_com_1cm_left").total_mass(), base.total_mass(), 1e-12);
  // One side's six leg links 5 % heavier, the other side and the rest untouched.
  for (const char* side : {"left", "right"}) {
    const RobotModel& r = robots.at(std::string(side) + "_leg_plus_5pct");
    int heavier = 0;
    for (std::size_t l = 0; l < base.links().size(); ++l) {
      const std::string& name = base.links()[l].name;
      const bool leg = name.rfind(side, 0) == 0 && name.find("arm") == std::string::npos &&
                       name.find("shoulder") == std::string::npos;
      EXPECT_NEAR(r.links()[l].mass, (leg ? 1.05 : 1.0) * base.links()[l].mass, 1e-12) << name;
      heavier += leg ? 1 : 0;
    }
    EXPECT_EQ(heavier, 6) << side;
  }
}

}  // namespace
}  // namespace stride::sim
