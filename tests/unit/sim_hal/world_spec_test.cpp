// The world option table and WorldSpec (issue 31 point 1, issue 44 point 2): one table drives
// the flags, the JSON reader and the help, each row bound to its field; the options are
// independent of their order; every kind of value gets one message naming the option as
// given; a spec survives its JSON; the default world is one world wherever it is asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "same_world.hpp"
#include "stride/firmware/parameter_store.hpp"
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

TEST(WorldSpec, EveryTableOptionIsAFlagWithItsHelp) {
  core::CliArgs args;
  declare_world_options(args);
  const std::string help = args.help();
  for (const WorldOptionInfo& o : world_option_table())
    EXPECT_NE(help.find(world_option_cli_flag(o.key)), std::string::npos) << o.key;
  EXPECT_NE(help.find("--world"), std::string::npos);
  EXPECT_NE(help.find("[us]"), std::string::npos);  // the step's unit
}

TEST(WorldSpec, FlagsReachTheWorldInAnyOrder) {
  WorldOptions a, b;
  ASSERT_TRUE(parse_flags({"--servo-law",
                           "seed",
                           "--world",
                           "faithful",
                           "--friction",
                           "0.5",
                           "--mass-range",
                           "0.1",
                           "--latency-ticks",
                           "1",
                           "--latency-probability",
                           "0.25",
                           "--push",
                           "1,left,2",
                           "--push",
                           "2.5,-45,1",
                           "--seed",
                           "7",
                           "--noise",
                           "off",
                           "--physics-step-us",
                           "500"},
                          a));
  ASSERT_TRUE(parse_flags({"--push",
                           "1,left,2",
                           "--physics-step-us",
                           "500",
                           "--noise",
                           "off",
                           "--seed",
                           "7",
                           "--latency-probability",
                           "0.25",
                           "--latency-ticks",
                           "1",
                           "--mass-range",
                           "0.1",
                           "--friction",
                           "0.5",
                           "--push",
                           "2.5,-45,1",
                           "--world",
                           "faithful",
                           "--servo-law",
                           "seed"},
                          b));
  for (const WorldOptions* o : {&a, &b}) {
    EXPECT_EQ(o->servo.law, ServoLaw::kSeed);  // overrides the named world in either order
    EXPECT_FALSE(o->imu.chain.is_ideal());     // the faithful world's
    EXPECT_EQ(o->contact.friction, 0.5);
    EXPECT_EQ(o->randomise.mass_range, 0.1);
    EXPECT_EQ(o->randomise.latency_probability, 0.25);
    EXPECT_EQ(o->robot.latency_ticks, 1);
    EXPECT_EQ(o->seed, 7u);
    EXPECT_EQ(o->imu.gyro_noise_std, 0.0);
    EXPECT_EQ(o->physics_step_ns, 500'000);
    ASSERT_EQ(o->pushes.size(), 2u);
    EXPECT_DOUBLE_EQ(o->pushes[0].direction_rad, std::numbers::pi / 2);
    EXPECT_DOUBLE_EQ(o->pushes[1].direction_rad, -std::numbers::pi / 4);
  }
  // Nothing given: the faithful world with noise on, as WorldOptions' defaults.
  WorldOptions d;
  ASSERT_TRUE(parse_flags({}, d));
  EXPECT_EQ(d.servo.law, ServoLaw::kIdentified);
  EXPECT_GT(d.imu.gyro_noise_std, 0.0);
  EXPECT_EQ(d.contact.friction, ContactOptions::turf().friction);
  EXPECT_TRUE(d.pushes.empty());
}

TEST(WorldSpec, EachKindOfBadValueIsNamedOnce) {
  WorldOptions o;
  const auto error = [&o](std::vector<const char*> words) {
    const Status s = parse_flags(words, o);
    return s ? std::string("ok") : s.message();
  };
  EXPECT_EQ(error({"--contact", "lawn"}),
            "--contact: expected seed, turf, soft or hard, got 'lawn'");
  EXPECT_EQ(error({"--world", "moon"}),
            "--world: expected faithful, seed or a world file (.json), got 'moon'");
  EXPECT_EQ(error({"--latency-ticks", "4"}), "--latency-ticks: must be in 0..3, got 4");
  EXPECT_EQ(error({"--latency-ticks", "1.5"}), "--latency-ticks: expected an integer, got '1.5'");
  EXPECT_EQ(error({"--physics-step-us", "2e9"}),
            "--physics-step-us: must be in 1..20000 us, got 2e9");
  EXPECT_EQ(error({"--friction-range", "x"}), "--friction-range: expected a number, got 'x'");
  EXPECT_EQ(error({"--urdf", "/nonexistent.urdf"}), "--urdf: no such file '/nonexistent.urdf'");
  EXPECT_EQ(error({"--push", "1,left"}),
            "--push: expected three comma-separated fields in '1,left' (expected "
            "T,DIR,IMPULSE, e.g. 5.2,forward,1.5)");
  WorldSpec spec;
  EXPECT_EQ(spec.set("gravity", "3.7", "world.gravity").message(),
            "world.gravity: unknown world option (known: " + world_option_keys() + ")");
}

TEST(WorldSpec, ASpecSurvivesItsJson) {
  WorldSpec spec;
  ASSERT_TRUE(spec.set("base", "seed", "base"));
  ASSERT_TRUE(spec.set("contact", "turf", "contact"));
  ASSERT_TRUE(spec.set("friction", "0.8", "friction"));
  ASSERT_TRUE(spec.set("strength_range", "0.15", "strength_range"));
  ASSERT_TRUE(spec.set("latency_ticks", "2", "latency_ticks"));
  ASSERT_TRUE(spec.set("push", "4,12.5,1.25", "push"));
  ASSERT_TRUE(spec.set("noise", "off", "noise"));
  const nlohmann::json j = to_json(spec);
  EXPECT_EQ(j["base"], "seed");
  EXPECT_EQ(j["push"][0], "4,12.5,1.25");
  WorldSpec back;
  ASSERT_TRUE(read_world_spec(j, "world", back));
  EXPECT_EQ(to_json(back), j);
  const WorldOptions a = spec.to_options(), b = back.to_options();
  EXPECT_EQ(a.servo.law, b.servo.law);
  EXPECT_EQ(a.contact.grass_thickness_m, b.contact.grass_thickness_m);
  EXPECT_EQ(a.contact.friction, 0.8);
  EXPECT_EQ(b.randomise.strength_range, 0.15);
  EXPECT_EQ(b.robot.latency_ticks, 2);
  EXPECT_EQ(a.pushes[0].direction_rad, b.pushes[0].direction_rad);
  // A bad value in an object leaves the spec as it was.
  EXPECT_EQ(read_world_spec({{"friction", 0.3}, {"imu", "gps"}}, "world", back).message(),
            "world.imu: expected ideal, cm730 or cm730-nimbro, got 'gps'");
  EXPECT_EQ(to_json(back), j);
  EXPECT_EQ(read_world_spec({{"push", "1,left,1"}}, "world", back).message(),
            "world.push: must be a list of \"T,DIR,IMPULSE\" strings");
}

/// A value of `o` other than its default: the last name, the middle of the range, a file.
std::string other_value(const WorldOptionInfo& o) {
  switch (o.value) {
    case WorldValue::kWorld:
    case WorldValue::kName:
      return std::string(o.choices.back());
    case WorldValue::kInteger:
    case WorldValue::kNumber: {
      double v = o.min + 0.5 * (o.max - o.min);
      if (o.value == WorldValue::kInteger) v = std::floor(v);
      char text[40];
      std::snprintf(text, sizeof text, "%.17g", v);
      return text;
    }
    case WorldValue::kPath:
      return RobotModel::igus_path().string();
    case WorldValue::kPushes:
      return "1,left,2";
  }
  return "";
}

// Every row is bound to its field: a value set by its name is set, written to JSON, read back
// from it and equal, so that a row whose binding is missing or reaches another field fails.
TEST(WorldSpec, EveryRowRoundTripsThroughItsField) {
  const WorldSpec defaults;
  for (const WorldOptionInfo& o : world_option_table()) {
    SCOPED_TRACE(std::string(o.key));
    ASSERT_NE(o.set, nullptr);
    ASSERT_NE(o.get, nullptr);
    if (o.value == WorldValue::kPushes) {
      ASSERT_NE(o.clear, nullptr);
    }
    EXPECT_FALSE(defaults.is_set(o.key));
    WorldSpec spec;
    ASSERT_TRUE(spec.set(o.key, other_value(o), std::string(o.key)));
    EXPECT_TRUE(spec.is_set(o.key));
    for (const WorldOptionInfo& other : world_option_table())  // and no other field
      if (other.key != o.key) {
        EXPECT_FALSE(spec.is_set(other.key)) << other.key;
      }
    const nlohmann::json j = to_json(spec);
    ASSERT_TRUE(j.contains(std::string(o.key)));
    WorldSpec back;
    ASSERT_TRUE(read_world_spec(j, "world", back));
    EXPECT_TRUE(back.is_set(o.key));
    EXPECT_EQ(o.get(back), o.get(spec));
    EXPECT_EQ(to_json(back), j);
  }
  // A default spec writes the options written always and nothing else.
  const nlohmann::json written = to_json(defaults);
  for (const auto& [key, value] : written.items())
    EXPECT_TRUE(find_world_option(key)->always_written) << key;
}

// The help's default is the value a default spec holds, not a second copy of it.
TEST(WorldSpec, TheHelpShowsTheDefaultsTheCodeUses) {
  const WorldSpec defaults;
  for (const WorldOptionInfo& o : world_option_table()) {
    const nlohmann::json v = o.get(defaults);
    if (v.is_null()) continue;
    const std::string text =
        v.is_string() ? v.get<std::string>() : fw::format_number(v.get<double>());
    EXPECT_EQ(o.default_text, text) << o.key;
  }
  EXPECT_EQ(find_world_option("physics_step_us")->default_text,
            std::to_string(kDefaultPhysicsStepUs));
  EXPECT_EQ(find_world_option("noise")->default_text, "on");
}

// One default world: the command line's with no flags is WorldSpec{}'s, and a bare
// WorldOptions{} is that world with the sensor noise off (its one documented difference).
TEST(WorldSpec, TheDefaultWorldIsOneWorld) {
  WorldOptions flags;
  ASSERT_TRUE(parse_flags({}, flags));
  const WorldOptions spec = WorldSpec{}.to_options();
  expect_same_world(flags, spec);
  EXPECT_GT(spec.imu.gyro_noise_std, 0.0);  // --noise defaults to on
  WorldOptions bare;
  EXPECT_EQ(bare.imu.gyro_noise_std, 0.0);
  bare.imu.set_noise(true);
  expect_same_world(bare, spec);
  WorldSpec quiet;
  ASSERT_TRUE(quiet.set("noise", "off", "noise"));
  expect_same_world(WorldOptions{}, quiet.to_options());
  // The faithful preset is the member initialisers' world: applying it restores them.
  WorldOptions back;
  back.apply(WorldPreset::kSeed);
  back.apply(WorldPreset::kFaithful);
  expect_same_world(back, WorldOptions{});
}

}  // namespace
}  // namespace stride::sim
