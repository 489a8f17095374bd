// Task configs and their worlds: the ground range and every randomisation range of the world
// option table, the robot and world fields, a world object of
// the table's options, base parameters and a world file reach every trial world, and a bad value
// names its field.
#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>

#include "minimal_task_config.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

nlohmann::json minimal() {
  return minimal_task_config();
}

std::string error_of(const nlohmann::json& doc) {
  return parse_error_of(doc);
}

TEST(TaskConfig, TheContactRangeReachesTheTrialsAndNamesTheFieldOnError) {
  auto d = minimal();
  d["contact"] = "soft";
  d["trials"] = 3;
  d["randomisation"] = {{"contact_range", 0.5}};
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(d, c));
  EXPECT_EQ(c.randomisation.contact_range, 0.5);
  for (int k = 0; k < 3; ++k) {
    const sim::WorldOptions w = RobotTask(c).world_options(k);
    EXPECT_EQ(w.randomise.contact_range, 0.5);
    EXPECT_STREQ(sim::contact_kind_name(w.contact), "soft");
  }
  TaskConfig back;
  ASSERT_TRUE(parse_task_config(to_json(c), back));
  EXPECT_EQ(back.randomisation.contact_range, 0.5);
  d["trials"] = 1;  // the nominal world: no randomisation
  ASSERT_TRUE(parse_task_config(d, c));
  EXPECT_EQ(RobotTask(c).world_options(0).randomise.contact_range, 0.0);
  EXPECT_EQ(TrialRandomisation{}.contact_range, 0.0);  // off unless asked for
  d["randomisation"] = {{"contact_range", 1.5}};
  EXPECT_EQ(error_of(d), "randomisation.contact_range: must be in 0..1, got 1.5");
  d["randomisation"] = {{"contact_range", -0.2}};
  EXPECT_EQ(error_of(d), "randomisation.contact_range: must be in 0..1, got -0.2");
  d.erase("randomisation");
  d.erase("contact");
  d["world"] = {{"contact", "hard"}, {"contact_range", 0.5}};
  EXPECT_EQ(error_of(d),
            "world.contact_range: set per trial by the task (trial_seed, randomisation), not in "
            "world");
}

// The trials' randomisation is the world option table's randomisation rows: every range the
// table has reaches each trial world (the command latency too) and survives run.json, whose
// record of a run without the later ranges stays as it was.
TEST(TaskConfig, EveryRandomisationRangeOfTheTableReachesTheTrials) {
  auto d = minimal();
  d["trials"] = 2;
  // The servo and supply draws are [min, max] pairs (issue 54's off-nominal robot); the other
  // ranges distinct small values.
  const nlohmann::json pairs = {{"servo_friction_min", 0.8}, {"servo_friction_max", 1.6},
                                {"servo_torque_min", 0.8},   {"servo_torque_max", 1.05},
                                {"supply_min", 12.0},        {"supply_max", 16.8}};
  nlohmann::json ranges = nlohmann::json::object();
  double value = 0.0;
  for (const sim::WorldOptionInfo& o : sim::world_option_table())
    if (o.randomisation)
      ranges[std::string(o.key)] =
          pairs.contains(o.key) ? pairs[std::string(o.key)].get<double>() : value += 0.005;
  ASSERT_EQ(ranges.size(), 12u);
  d["randomisation"] = ranges;
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(d, c));
  sim::WorldSpec trial;
  trial.randomise = RobotTask(c).world_options(1).randomise;
  TaskConfig back;
  ASSERT_TRUE(parse_task_config(to_json(c), back));
  sim::WorldSpec read_back;
  read_back.randomise = back.randomisation;
  for (const auto& [key, v] : ranges.items()) {
    EXPECT_EQ(sim::find_world_option(key)->get(trial), v) << key;
    EXPECT_EQ(sim::find_world_option(key)->get(read_back), v) << key;
  }
  const nlohmann::json record = to_json(TaskConfig{})["randomisation"];
  EXPECT_EQ(record, (nlohmann::json{{"imu_noise", true},
                                    {"friction_range", 0.2},
                                    {"mass_range", 0.05},
                                    {"strength_range", 0.1},
                                    {"contact_range", 0.0}}));
  d["randomisation"] = {{"latency_probability", 2}};
  EXPECT_EQ(error_of(d), "randomisation.latency_probability: must be in 0..1, got 2");
  d["randomisation"] = {{"servo_torque_min", 0.05}};
  EXPECT_EQ(error_of(d), "randomisation.servo_torque_min: must be in 0.1..3, got 0.05");
  d["randomisation"] = {{"supply_min", 16.8}, {"supply_max", 12}};
  EXPECT_EQ(error_of(d),
            "randomisation.supply_min and _max: need 6 <= min <= max <= 20 V, got 16.8 and 12");
}

TEST(TaskConfig, RobotFieldsReachTheWorldsAndNameTheFieldOnError) {
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(minimal(), c));
  EXPECT_TRUE(c.world.urdf.empty());
  EXPECT_EQ(RobotTask(c).world_options(0).servo.law, sim::ServoLaw::kIdentified);
  EXPECT_FALSE(RobotTask(c).world_options(0).imu.chain.is_ideal());
  EXPECT_FALSE(RobotTask(c).world_options(0).imu.chain.noise);  // one trial: no noise
  // The trials' step in the faithful world: the task's (2.5 ms for a walk; the get-up 2 ms),
  // unless the config gives one.
  EXPECT_EQ(c.task, "walk");
  EXPECT_EQ(RobotTask(c).world_options(0).physics_step_ns, 2'500'000);
  EXPECT_EQ(sim::to_json(c.world).at("physics_step_us"), 2500);  // run.json holds it
  auto stepped = minimal();
  stepped["physics_step_us"] = 2000;
  ASSERT_TRUE(parse_task_config(stepped, c));
  EXPECT_EQ(RobotTask(c).world_options(0).physics_step_ns, 2'000'000);
  stepped = minimal();
  stepped["world"] = {{"physics_step_us", 1000}};
  ASSERT_TRUE(parse_task_config(stepped, c));
  EXPECT_EQ(RobotTask(c).world_options(0).physics_step_ns, 1'000'000);
  stepped = minimal();
  stepped["task"] = "getup";
  ASSERT_TRUE(parse_task_config(stepped, c));
  EXPECT_EQ(RobotTask(c).world_options(0).physics_step_ns, 2'000'000);
  ASSERT_TRUE(parse_task_config(minimal(), c));
  EXPECT_DOUBLE_EQ(RobotTask(c).world_options(0).contact.grass_thickness_m, 0.005);
  // The thesis's world by name; a part named beside it overrides it.
  auto seed = minimal();
  seed["world"] = "seed";
  ASSERT_TRUE(parse_task_config(seed, c));
  EXPECT_EQ(RobotTask(c).world_options(0).servo.law, sim::ServoLaw::kSeed);
  EXPECT_TRUE(RobotTask(c).world_options(0).imu.chain.is_ideal());
  EXPECT_DOUBLE_EQ(RobotTask(c).world_options(0).contact.grass_thickness_m, 0.02);
  EXPECT_EQ(RobotTask(c).world_options(0).physics_step_ns, 2'000'000);  // the table's
  seed["imu"] = "cm730";
  ASSERT_TRUE(parse_task_config(seed, c));
  EXPECT_FALSE(RobotTask(c).world_options(0).imu.chain.is_ideal());
  EXPECT_EQ(RobotTask(c).world_options(0).servo.law, sim::ServoLaw::kSeed);
  seed["world"] = "gazebo";
  EXPECT_EQ(
      error_of(seed),
      "world: must be \"faithful\", \"seed\", a world file (.json), its object or an object of "
      "world options, got \"gazebo\"");
  test::TempDir tmp;
  std::filesystem::create_directories(tmp.path() / "robots");
  std::filesystem::copy_file(sim::RobotModel::igus_path(), tmp.path() / "robots" / "mine.urdf");
  auto d = minimal();
  d["urdf"] = "robots/mine.urdf";  // relative to the config file
  d["servo_law"] = "identified";
  d["imu"] = "cm730";
  d["physics_step_us"] = 500;
  d["contact"] = "turf";
  d["trials"] = 2;
  tmp.write("config.json", d.dump());
  ASSERT_TRUE(load_task_config(tmp.path() / "config.json", c));
  EXPECT_EQ(c.world.urdf, tmp.path() / "robots" / "mine.urdf");
  const RobotTask task(c);
  for (int k = 0; k < 2; ++k) {
    const sim::WorldOptions w = task.world_options(k);
    EXPECT_EQ(w.urdf, c.world.urdf);
    EXPECT_EQ(w.servo.law, sim::ServoLaw::kIdentified);
    EXPECT_FALSE(w.imu.chain.is_ideal());
    EXPECT_TRUE(w.imu.chain.noise);  // trials randomise with IMU noise on
    EXPECT_EQ(w.physics_step_ns, 500'000);
    EXPECT_DOUBLE_EQ(w.contact.grass_thickness_m, sim::ContactOptions::turf().grass_thickness_m);
    EXPECT_TRUE(w.contact.mujoco_solid_ground);
  }
  TaskConfig back;
  ASSERT_TRUE(parse_task_config(to_json(c), back));
  EXPECT_EQ(to_json(back), to_json(c));
  d = minimal();
  d["urdf"] = (tmp.path() / "none.urdf").string();
  EXPECT_EQ(error_of(d), "urdf: no such file '" + (tmp.path() / "none.urdf").string() + "'");
  d["urdf"] = tmp.write("broken.urdf", "<robot name='x'><link name='a'/>").string();
  EXPECT_EQ(error_of(d).rfind("urdf: ", 0), 0u) << error_of(d);
  d = minimal();
  d["servo_law"] = "gazebo";
  EXPECT_EQ(error_of(d), "servo_law: expected seed or identified, got 'gazebo'");
  d = minimal();
  d["imu"] = 3;
  EXPECT_EQ(error_of(d), "imu: expected ideal, cm730 or cm730-nimbro, got '3'");
  d = minimal();
  d["contact"] = "lawn";
  EXPECT_EQ(error_of(d), "contact: expected seed, turf, soft or hard, got 'lawn'");
  d = minimal();
  d["physics_step_us"] = 0;
  EXPECT_EQ(error_of(d), "physics_step_us: must be in 1..20000 us, got 0");
  // A step in range that does not divide the firmware's control period: the task's check,
  // against the period of the firmware it runs (stride optimise: exit 2 before any episode).
  d["physics_step_us"] = 3000;
  ASSERT_TRUE(parse_task_config(d, c));
  EXPECT_EQ(RobotTask(c).check().message(),
            "physics_step_us: 3000 us does not divide the firmware's control period of 10000 us");
  d["physics_step_us"] = 2500;
  ASSERT_TRUE(parse_task_config(d, c));
  EXPECT_TRUE(RobotTask(c).check());
}

// The world option table (issue 31 point 1): the `world` object takes its fields, the flat
// fields of before still load, and an unknown option is named with the known ones.
TEST(TaskConfig, AWorldObjectTakesTheTablesOptions) {
  auto d = minimal();
  d["world"] = {
      {"base", "seed"}, {"contact", "turf"}, {"physics_step_us", 1000}, {"engine", "mujoco"}};
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(d, c));
  const sim::WorldOptions w = RobotTask(c).world_options(0);
  EXPECT_EQ(w.servo.law, sim::ServoLaw::kSeed);  // the seed world's
  EXPECT_TRUE(w.imu.chain.is_ideal());           // the seed world's
  EXPECT_TRUE(w.contact.mujoco_solid_ground);    // turf overrides its grass
  EXPECT_EQ(w.physics_step_ns, 1'000'000);
  EXPECT_EQ(w.engine, sim::EngineKind::kMujoco);
  // The same world in the flat fields of before.
  auto flat = minimal();
  flat["world"] = "seed";
  flat["contact"] = "turf";
  flat["physics_step_us"] = 1000;
  flat["engine"] = "mujoco";
  TaskConfig f;
  ASSERT_TRUE(parse_task_config(flat, f));
  EXPECT_EQ(to_json(f), to_json(c));
  // Contact parameters, latency and pushes reach every trial world and survive run.json.
  d["world"] = {{"friction", 0.6}, {"latency_ticks", 2}, {"push", {"3,left,1.5", "5.5,30,2"}}};
  d["trials"] = 2;
  ASSERT_TRUE(parse_task_config(d, c));
  for (int k = 0; k < 2; ++k) {
    const sim::WorldOptions o = RobotTask(c).world_options(k);
    EXPECT_EQ(o.contact.friction, 0.6);
    EXPECT_EQ(o.robot.latency_ticks, 2);
    ASSERT_EQ(o.pushes.size(), 2u);
    EXPECT_EQ(o.pushes[0].time_s, 3.0);
    EXPECT_DOUBLE_EQ(o.pushes[0].direction_rad, std::numbers::pi / 2);
    EXPECT_DOUBLE_EQ(o.pushes[1].direction_rad, std::numbers::pi / 6);
    EXPECT_EQ(o.pushes[1].impulse_n_s, 2.0);
  }
  TaskConfig back;
  ASSERT_TRUE(parse_task_config(to_json(c), back));
  EXPECT_EQ(to_json(back), to_json(c));
  EXPECT_EQ(back.world.pushes[1].direction_rad, c.world.pushes[1].direction_rad);
  d.erase("trials");
  d["world"] = {{"gravity", 3.7}};
  EXPECT_EQ(error_of(d),
            "world.gravity: unknown world option (known: base, engine, physics_step_us, "
            "servo_law, imu, mag_disturbance, contact, friction, urdf, noise, seed, "
            "friction_range, mass_range, strength_range, latency_probability, contact_range, "
            "com_range, servo_friction_min, servo_friction_max, servo_torque_min, "
            "servo_torque_max, supply_min, supply_max, latency_ticks, push)");
  d["world"] = {{"friction", 9}};
  EXPECT_EQ(error_of(d), "world.friction: must be in 0.05..3, got 9");
  d["world"] = {{"push", {"3,up,1"}}};
  EXPECT_EQ(error_of(d),
            "world.push[0]: direction must be forward, backward, left, right or degrees, got "
            "'up' in '3,up,1' (expected T,DIR,IMPULSE, e.g. 5.2,forward,1.5)");
  // The trials own the seed, the noise and the randomisation ranges.
  d["world"] = {{"mass_range", 0.1}};
  EXPECT_EQ(error_of(d),
            "world.mass_range: set per trial by the task (trial_seed, randomisation), not in "
            "world");
  d.erase("world");
  d["randomisation"] = {{"mass_range", 1.5}};
  EXPECT_EQ(error_of(d), "randomisation.mass_range: must be in 0..0.99, got 1.5");
  d.erase("randomisation");
  d["world"] = {{"physics_step_us", 30000}};
  EXPECT_EQ(error_of(d), "world.physics_step_us: must be in 1..20000 us, got 30000");
  d["world"] = {{"engine", "mujoco"}};
  d["engine"] = "simbody";
  EXPECT_EQ(error_of(d), "world.engine: give the engine in world or at the top level, not both");
}

// Base parameters (issue 29 point 6): a file relative to the config or an object, stored by
// value in run.json; a bad one is named.
TEST(TaskConfig, BaseParametersFromAFileOrAnObject) {
  test::TempDir tmp;
  std::filesystem::create_directories(tmp.path() / "walk");
  tmp.write("walk/base.json",
            R"({"walk.compliance.gain": 0.0, "walk.balance.heading_gain": 0.25})");
  auto d = minimal();
  d["params"] = "base.json";
  tmp.write("walk/config.json", d.dump());
  TaskConfig c;
  ASSERT_TRUE(load_task_config(tmp.path() / "walk" / "config.json", c));
  ASSERT_EQ(c.base_params.size(), 2u);
  EXPECT_EQ(c.base_params[0].first, "walk.balance.heading_gain");  // sorted by name
  EXPECT_EQ(c.base_params[0].second, 0.25);
  EXPECT_EQ(to_json(c)["params"]["walk.compliance.gain"], 0.0);
  TaskConfig back;
  ASSERT_TRUE(parse_task_config(to_json(c), back));
  EXPECT_EQ(back.base_params, c.base_params);
  d["params"] = {{"walk.compliance.gain", "high"}};
  EXPECT_EQ(error_of(d), "params: walk.compliance.gain must be a number, got \"high\"");
  d["params"] = 3;
  EXPECT_EQ(error_of(d), "params: must be a parameter file's path or an object {name: number}");
  d["params"] = (tmp.path() / "none.json").string();
  EXPECT_EQ(error_of(d), "params: cannot open '" + (tmp.path() / "none.json").string() + "'");
}

// A world file (stride calibrate's output, sim_hal/world_file.hpp): a path relative to the
// config or the object itself; its base world sets the servo law, IMU and contact, its
// calibration reaches every trial world; run.json keeps it by value.
TEST(TaskConfig, AWorldFileReachesEveryTrialWorld) {
  test::TempDir tmp;
  std::filesystem::create_directories(tmp.path() / "walk");
  tmp.write("walk/robot.json", R"({"format": "stride-world", "base": "seed",
      "supply_voltage_v": 14.0, "robot": {"latency_ticks": 1, "trunk_mass_scale": 1.1}})");
  auto d = minimal();
  d["world"] = "robot.json";
  d["trials"] = 3;
  tmp.write("walk/config.json", d.dump());
  TaskConfig c;
  const Status s = load_task_config(tmp.path() / "walk" / "config.json", c);
  ASSERT_TRUE(s) << s.message();
  ASSERT_TRUE(c.world.file.has_value());
  EXPECT_EQ(c.world.base, sim::WorldPreset::kSeed);
  const RobotTask task(c);
  for (int w = 0; w < 3; ++w) {
    const sim::WorldOptions o = task.world_options(w);
    EXPECT_EQ(o.robot.latency_ticks, 1);
    EXPECT_EQ(o.robot.trunk_mass_scale, 1.1);
    EXPECT_EQ(o.battery_voltage_v, 14.0);
  }
  TaskConfig back;
  ASSERT_TRUE(parse_task_config(to_json(c), back));
  ASSERT_TRUE(back.world.file.has_value());
  EXPECT_EQ(sim::to_json(*back.world.file), sim::to_json(*c.world.file));
  d["world"] = {{"format", "stride-world"}, {"robot", {{"latency_ticks", 9}}}};
  EXPECT_EQ(error_of(d), "world: robot.latency_ticks: must be an integer in 0..3, got 9");
}

}  // namespace
}  // namespace stride::opt
