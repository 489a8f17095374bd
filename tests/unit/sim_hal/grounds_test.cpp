// The named grounds and the ground drawn per reset (issue 41 point 1; grounds.hpp): soft and
// hard are names of --contact and of a task config's contact; the draw moves the world's ground
// towards hard or soft on a log scale, draws nothing at range 0, and a world's draws follow its
// seed; a bad --contact-range is one message naming the flag.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "stride/sim_hal/grounds.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::sim {
namespace {

Status parse_flags(const std::vector<const char*>& words, WorldOptions& out) {
  core::CliArgs args;
  declare_world_options(args);
  std::vector<const char*> argv = {"stride"};
  argv.insert(argv.end(), words.begin(), words.end());
  if (Status s = args.parse(static_cast<int>(argv.size()), argv.data()); !s) return s;
  return read_world_options(args, out);
}

TEST(Grounds, SoftAndHardAreNamedGroundsEitherSideOfTurf) {
  for (const char* name : {"seed", "turf", "soft", "hard"}) {
    ContactOptions c;
    ASSERT_TRUE(parse_contact_kind(name, c)) << name;
    EXPECT_STREQ(contact_kind_name(c), name);
  }
  ContactOptions mud;
  EXPECT_FALSE(parse_contact_kind("mud", mud));
  const ContactOptions turf = ContactOptions::turf(), soft = ContactOptions::soft(),
                       hard = ContactOptions::hard();
  // Per point: hard stiffer than turf, soft between; soft deeper and more damped.
  EXPECT_GT(hard.grass_stiffness_n_m, soft.grass_stiffness_n_m);
  EXPECT_GT(soft.grass_stiffness_n_m, turf.grass_stiffness_n_m);
  EXPECT_GT(soft.grass_thickness_m, turf.grass_thickness_m);
  EXPECT_LT(hard.grass_thickness_m, turf.grass_thickness_m);
  EXPECT_GT(soft.grass_damping_n_s_m, turf.grass_damping_n_s_m);
  // A standing robot (6.46 kg on eight studs): hard under 1 mm, soft 3 mm or more, in its layer.
  const double per_stud = 6.4601 * 9.81 / 8.0;
  EXPECT_LT(per_stud / hard.grass_stiffness_n_m, 1e-3);
  EXPECT_GE(per_stud / soft.grass_stiffness_n_m, 3e-3);
  EXPECT_LT(2.0 * per_stud / soft.grass_stiffness_n_m, soft.grass_thickness_m);
  for (const ContactOptions& c : {soft, hard}) {
    EXPECT_TRUE(c.mujoco_solid_ground);
    EXPECT_EQ(c.friction, turf.friction);
    EXPECT_EQ(c.ground_stiffness_n_m, turf.ground_stiffness_n_m);
  }
  ContactOptions custom = turf;
  custom.grass_stiffness_n_m += 1.0;
  EXPECT_STREQ(contact_kind_name(custom), "custom");
  custom = turf;
  custom.friction = 0.6;  // the friction is not the ground's kind
  EXPECT_STREQ(contact_kind_name(custom), "turf");
}

TEST(Grounds, ADrawMovesTheWorldsGroundTowardsHardOrSoftOnALogScale) {
  const ContactOptions turf = ContactOptions::turf(), soft = ContactOptions::soft(),
                       hard = ContactOptions::hard();
  EXPECT_STREQ(contact_kind_name(ground_between(turf, 0.0)), "turf");
  const ContactOptions to_soft = ground_between(turf, 1.0), to_hard = ground_between(turf, -1.0);
  EXPECT_DOUBLE_EQ(to_soft.grass_stiffness_n_m, soft.grass_stiffness_n_m);
  EXPECT_DOUBLE_EQ(to_soft.grass_thickness_m, soft.grass_thickness_m);
  EXPECT_DOUBLE_EQ(to_soft.grass_damping_n_s_m, soft.grass_damping_n_s_m);
  EXPECT_DOUBLE_EQ(to_soft.tangential_stiffness_n_m, soft.tangential_stiffness_n_m);
  EXPECT_DOUBLE_EQ(to_hard.grass_stiffness_n_m, hard.grass_stiffness_n_m);
  EXPECT_DOUBLE_EQ(to_hard.grass_thickness_m, hard.grass_thickness_m);
  EXPECT_DOUBLE_EQ(to_hard.grass_damping_n_s_m, hard.grass_damping_n_s_m);
  // Half way on a log scale: the geometric mean.
  const ContactOptions half = ground_between(turf, -0.5);
  EXPECT_NEAR(half.grass_stiffness_n_m,
              std::sqrt(turf.grass_stiffness_n_m * hard.grass_stiffness_n_m), 1e-9);
  EXPECT_NEAR(half.grass_thickness_m, std::sqrt(turf.grass_thickness_m * hard.grass_thickness_m),
              1e-12);
  // What the grounds share stays the world's.
  for (const ContactOptions& c : {to_soft, to_hard, half}) {
    EXPECT_EQ(c.friction, turf.friction);
    EXPECT_EQ(c.ground_stiffness_n_m, turf.ground_stiffness_n_m);
    EXPECT_EQ(c.ground_damping_n_s_m, turf.ground_damping_n_s_m);
    EXPECT_EQ(c.mujoco_solid_ground, turf.mujoco_solid_ground);
  }
}

TEST(Grounds, RangeZeroDrawsNothingAndADrawFollowsTheSeed) {
  WorldRng a(7), b(7);
  const ContactOptions same = draw_ground(ContactOptions::turf(), 0.0, a);
  EXPECT_STREQ(contact_kind_name(same), "turf");
  EXPECT_EQ(a.next_u64(), b.next_u64());  // no draw was taken
  WorldRng c(11), d(11);
  std::vector<double> stiffness;
  for (int i = 0; i < 20; ++i) {
    const ContactOptions g = draw_ground(ContactOptions::turf(), 1.0, c);
    EXPECT_EQ(g.grass_stiffness_n_m,
              draw_ground(ContactOptions::turf(), 1.0, d).grass_stiffness_n_m);
    EXPECT_GE(g.grass_stiffness_n_m, ContactOptions::turf().grass_stiffness_n_m * (1 - 1e-12));
    EXPECT_LE(g.grass_stiffness_n_m, ContactOptions::hard().grass_stiffness_n_m * (1 + 1e-12));
    stiffness.push_back(g.grass_stiffness_n_m);
  }
  // Both sides of turf are drawn: softer (thicker layer) and harder.
  int thicker = 0, thinner = 0;
  WorldRng e(11);
  for (int i = 0; i < 20; ++i) {
    const ContactOptions g = draw_ground(ContactOptions::turf(), 1.0, e);
    thicker += g.grass_thickness_m > ContactOptions::turf().grass_thickness_m;
    thinner += g.grass_thickness_m < ContactOptions::turf().grass_thickness_m;
  }
  EXPECT_GT(thicker, 3);
  EXPECT_GT(thinner, 3);
}

TEST(Grounds, TheFlagsNameTheGroundAndItsRange) {
  WorldOptions o;
  ASSERT_TRUE(parse_flags({"--contact", "soft", "--contact-range", "0.5"}, o));
  EXPECT_STREQ(contact_kind_name(o.contact), "soft");
  EXPECT_EQ(o.randomise.contact_range, 0.5);
  ASSERT_TRUE(parse_flags({"--contact", "hard"}, o));
  EXPECT_STREQ(contact_kind_name(o.contact), "hard");
  EXPECT_EQ(o.randomise.contact_range, 0.0);
  EXPECT_NE(describe_world(o).find("hard ground"), std::string::npos) << describe_world(o);
  EXPECT_EQ(parse_flags({"--contact", "mud"}, o).message(),
            "--contact: expected seed, turf, soft or hard, got 'mud'");
  EXPECT_EQ(parse_flags({"--contact-range", "-0.1"}, o).message(),
            "--contact-range: must be in 0..1, got -0.1");
  EXPECT_EQ(parse_flags({"--contact-range", "1.5"}, o).message(),
            "--contact-range: must be in 0..1, got 1.5");
  WorldSpec spec;
  ASSERT_TRUE(spec.set("contact_range", "0.25", "contact_range"));
  EXPECT_TRUE(spec.is_set("contact_range"));
  EXPECT_EQ(to_json(spec).at("contact_range"), 0.25);
}

}  // namespace
}  // namespace stride::sim
