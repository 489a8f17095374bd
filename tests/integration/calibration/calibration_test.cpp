// stride calibrate and world files (issue 30 point 3): a world file reads, writes and names a
// bad field; its calibration changes the simulated robot (trunk mass and centre of mass, bus
// latency); `stride calibrate` fits a perturbed robot from the identification routine's log,
// writes a world file that `stride sim` takes (task configs: task_config_test.cpp), prints a
// prediction check whose walk is stride sim's in each world, resumes a stopped run to the same
// result, and gives bad input one line, exit 2 and no output file.
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "expect_bad_input.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/firmware/robot_description.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "stride/sim_hal/world_file.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

const std::string kBin = STRIDE_BIN_DIR;

using CliRun = test::ChildRun;
using test::expect_bad_input;

CliRun stride(const test::TempDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), kBin + "/stride");
  return test::run_child(args, dir.path());
}

std::string parse_error(const nlohmann::json& doc) {
  WorldFile w;
  const Status s = parse_world_file(doc, w);
  return s ? "" : s.message();
}

TEST(WorldFile, ReadsWritesAndNamesTheBadField) {
  WorldFile w;
  w.base = WorldPreset::kSeed;
  w.supply_voltage_v = 14.0;
  w.robot.torque_scale_mx106 = 0.85;
  w.robot.latency_ticks = 2;
  w.robot.trunk_mass_scale = 1.1;
  w.robot.trunk_com_offset_m = {0.01, -0.002};
  w.gyro_bias_rad_s = {0.0, 0.01, 0.0};
  WorldFile back;
  ASSERT_TRUE(parse_world_file(to_json(w), back));
  EXPECT_EQ(to_json(back), to_json(w));
  EXPECT_EQ(back.base, WorldPreset::kSeed);
  EXPECT_EQ(back.robot.latency_ticks, 2);
  // Absent fields are nominal.
  ASSERT_TRUE(parse_world_file({{"format", "stride-world"}}, back));
  EXPECT_EQ(back.robot.torque_scale_mx64, 1.0);
  EXPECT_EQ(back.supply_voltage_v, 14.8);

  const nlohmann::json ok = {{"format", "stride-world"}};
  auto with = [&ok](const nlohmann::json& patch) {
    nlohmann::json d = ok;
    d.merge_patch(patch);
    return d;
  };
  EXPECT_EQ(parse_error({{"format", "stride-task"}}),
            "not a Stride world file (\"format\" is not \"stride-world\")");
  EXPECT_EQ(parse_error(with({{"robot", {{"latency_ticks", 4}}}})),
            "robot.latency_ticks: must be an integer in 0..3, got 4");
  EXPECT_EQ(parse_error(with({{"robot", {{"torque_scale", {{"MX-28", 1.0}}}}}})),
            "robot.torque_scale.MX-28: unknown field");
  EXPECT_EQ(parse_error(with({{"supply_voltage_v", 30}})),
            "supply_voltage_v: must be a number in [9, 18], got 30");
  EXPECT_EQ(parse_error(with({{"robot", {{"trunk_com_offset_m", {0.01}}}}})),
            "robot.trunk_com_offset_m: must be 2 numbers, each in [-0.1, 0.1], got [0.01]");
  EXPECT_EQ(parse_error(with({{"base", "moon"}})), "base: expected faithful or seed, got 'moon'");
  EXPECT_EQ(parse_error(with({{"gravity", 9.81}})), "gravity: unknown field");
}

TEST(WorldFile, TheCalibrationChangesTheSimulatedRobot) {
  WorldOptions nominal;
  nominal.ball.present = false;
  WorldOptions heavy = nominal;
  WorldFile file;
  file.robot.trunk_mass_scale = 1.1;
  file.robot.trunk_com_offset_m = {0.01, 0.0};
  file.apply_calibration(heavy);
  std::unique_ptr<SimWorld> a, b;
  ASSERT_TRUE(SimWorld::create(nominal, a));
  ASSERT_TRUE(SimWorld::create(heavy, b));
  const double trunk = 1.8051;  // kg, igus_op.urdf trunk_link
  EXPECT_NEAR(b->model().total_mass() - a->model().total_mass(), 0.1 * trunk, 1e-9);
  const double com_shift =
      b->ground_truth().center_of_mass.x() - a->ground_truth().center_of_mass.x();
  EXPECT_NEAR(com_shift, 0.01 * 1.1 * trunk / b->model().total_mass(), 0.001);

  // Latency: a step command to the head reaches the servo `latency_ticks` periods later.
  const auto first_move = [](int latency) {
    WorldOptions o;
    o.ball.present = false;
    o.robot.latency_ticks = latency;
    std::unique_ptr<SimWorld> w;
    EXPECT_TRUE(SimWorld::create(o, w));
    const std::size_t head_yaw = 18;
    const double start = w->servo_joint_angle(head_yaw);
    hal::ServoCommand c;
    c.position_rad = w->servo_state(head_yaw).goal_position_rad + 0.3;
    c.p_gain = 32;
    c.torque_enable = true;
    w->set_servo_command(head_yaw, c);
    for (int period = 1; period <= 10; ++period) {
      w->advance_period();
      if (std::abs(w->servo_joint_angle(head_yaw) - start) > 0.005) return period;
    }
    return -1;
  };
  const int immediate = first_move(0);
  ASSERT_GT(immediate, 0);
  EXPECT_EQ(first_move(1), immediate + 1);
  EXPECT_EQ(first_move(2), immediate + 2);
}

// A robot one tick of bus latency away from the model, recorded by the product: standing 2 s,
// walking in place 5 s, a stop, 5 s forward, a stop (noise off: the test is about the fit).
class Calibrate : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<test::TempDir>();
    perturbed_ = dir_->write("perturbed.json",
                             R"({"format": "stride-world", "robot": {"latency_ticks": 1}})");
    log_ = dir_->path() / "routine.flog";
    const CliRun run = stride(
        *dir_, {"identify", "--out", log_.string(), "--world", perturbed_.string(), "--noise",
                "off", "--parts", "stand,walk", "--stand-s", "2", "--walk-s", "5"});
    ASSERT_EQ(run.code, 0) << run.err;
  }
  static void TearDownTestSuite() { dir_.reset(); }
  static std::unique_ptr<test::TempDir> dir_;
  static std::filesystem::path perturbed_, log_;
};
std::unique_ptr<test::TempDir> Calibrate::dir_;
std::filesystem::path Calibrate::perturbed_, Calibrate::log_;

TEST_F(Calibrate, FitsTheBusLatencyAndWritesAWorldFileTheSimulatorTakes) {
  test::TempDir dir;
  const auto world = dir.path() / "calibrated.json";
  const CliRun run =
      stride(dir, {"calibrate", log_.string(), "--fit", "latency", "--out", world.string(),
                   "--subsets", "0", "--jobs", "2", "--window", "4"});
  ASSERT_EQ(run.code, 0) << run.err;
  WorldFile fitted;
  ASSERT_TRUE(load_world_file(world, fitted));
  EXPECT_EQ(fitted.robot.latency_ticks, 1);
  // The latency is identified: no warning (issue 45 point 2: warned values are named).
  EXPECT_EQ(run.err.find("warning"), std::string::npos) << run.err;
  EXPECT_TRUE(fitted.calibration["warnings"].empty());
  // Measured: J 867 at the nominal robot, 601 calibrated.
  EXPECT_LT(fitted.calibration["objective"].get<double>(),
            0.8 * fitted.calibration["objective_start"].get<double>());
  EXPECT_FALSE(std::filesystem::exists(world.string() + ".progress.jsonl"));
  // stride sim takes it, and says what it changes.
  const CliRun sim = stride(dir, {"sim", "stand", "--world", world.string(), "--duration", "1"});
  EXPECT_EQ(sim.code, 0) << sim.err;
  // Task configs take it too: TaskConfig.AWorldFileReachesEveryTrialWorld.

  // The prediction check (calibration_check.hpp): its walk is stride sim's, in each world.
  const auto row = [&run](const std::string& figure) {
    const auto at = run.out.find("  " + figure);
    EXPECT_NE(at, std::string::npos) << figure << " missing from:\n" << run.out;
    return at == std::string::npos ? std::string()
                                   : run.out.substr(at, run.out.find('\n', at) - at);
  };
  const auto walk_time = [&dir](const std::string& w) {
    const CliRun walk =
        stride(dir, {"sim", "walk", "--vx", "1", "--duration", "30", "--world", w, "--json"});
    EXPECT_EQ(walk.code, 0) << walk.err;
    char text[32];
    std::snprintf(text, sizeof text, "%.2f",
                  nlohmann::json::parse(walk.out)["time_to_goal_s"].get<double>());
    return std::string(text);
  };
  const std::string times = row("time to walk 2.5 m [s]");
  EXPECT_NE(times.find(" " + walk_time("faithful") + " "), std::string::npos) << times;
  EXPECT_EQ(times.substr(times.size() - walk_time(world.string()).size()),
            walk_time(world.string()))
      << times;
  // The logs' own peak |a| is a number, and the forward walk goes forward in both worlds.
  EXPECT_NE(row("peak |a| in the logs' replay [m/s^2]").find('.'), std::string::npos);
  double nominal_speed = 0.0, calibrated_speed = 0.0;
  ASSERT_EQ(std::sscanf(row("speed forward [m/s]").c_str(), " speed forward [m/s] %lf %lf",
                        &nominal_speed, &calibrated_speed),
            2);
  EXPECT_GT(nominal_speed, 0.1);
  EXPECT_GT(calibrated_speed, 0.1);
}

TEST_F(Calibrate, AStoppedRunResumesToTheSameWorldFile) {
  const std::vector<std::string> fit = {
      "--fit", "trunk_mass,torque_mx106", "--max-evals", "12", "--subsets", "2", "--window", "4"};
  test::TempDir whole_dir;
  const auto whole = whole_dir.path() / "whole.json";
  std::vector<std::string> args = {"calibrate", log_.string(), "--out", whole.string()};
  args.insert(args.end(), fit.begin(), fit.end());
  ASSERT_EQ(stride(whole_dir, args).code, 0);

  // The same run stopped with Ctrl-C once it has stored a few evaluations, then resumed.
  test::TempDir dir;
  const auto out = dir.path() / "resumed.json";
  const auto progress = dir.path() / "resumed.json.progress.jsonl";
  args = {kBin + "/stride", "calibrate", log_.string(), "--out", out.string()};
  args.insert(args.end(), fit.begin(), fit.end());
  const pid_t pid = test::spawn(args, dir.path() / "out", dir.path() / "err");
  const auto lines = [&progress] {
    const std::string text = test::slurp(progress);
    return std::count(text.begin(), text.end(), '\n');
  };
  for (int i = 0; i < 600 && lines() < 4; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GE(lines(), 4) << "no progress";
  ::kill(pid, SIGINT);
  EXPECT_EQ(test::wait_exit(pid), 1);
  const std::string err = test::slurp(dir.path() / "err");
  EXPECT_NE(err.find("interrupted"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // Without --resume the progress file is not overwritten.
  args.erase(args.begin());
  expect_bad_input(stride(dir, args), "--resume");
  args.push_back("--resume");
  const CliRun resumed = stride(dir, args);
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(test::slurp(out), test::slurp(whole));
  EXPECT_FALSE(std::filesystem::exists(progress));
}

TEST_F(Calibrate, BadInputIsOneLineExitTwoAndNoOutputFile) {
  test::TempDir dir;
  const auto out = dir.path() / "w.json";
  const std::string log = log_.string();
  const std::string bytes = test::slurp(log_);
  const auto cut = dir.write("cut.flog", bytes.substr(0, bytes.size() / 2 + 7));
  expect_bad_input(
      stride(dir, {"calibrate", cut.string(), "--fit", "latency", "--out", out.string()}),
      "truncated");
  const auto foreign = dir.write("notes.flog", "not a log\n");
  expect_bad_input(
      stride(dir, {"calibrate", foreign.string(), "--fit", "latency", "--out", out.string()}),
      "not a Stride flight log");
  const std::string description = test::slurp(fw::RobotDescription::default_path());
  const auto other = dir.write("robot_description.json", description + " ");
  expect_bad_input(stride(dir, {"calibrate", log, "--fit", "latency", "--out", out.string(),
                                "--robot-description", other.string()}),
                   "robot description");
  expect_bad_input(
      stride(dir, {"calibrate", log, "--fit", "latency,wheel_radius", "--out", out.string()}),
      "--fit: cannot fit 'wheel_radius'");
  expect_bad_input(
      stride(dir, {"calibrate", log, "--fit", "latency", "--out", out.string(), "--window", "60"}),
      "--window");
  expect_bad_input(stride(dir, {"calibrate", log, "--fit", "latency"}), "--out");
  expect_bad_input(stride(dir, {"calibrate", log, "--fit", "latency", "--out", out.string(),
                                "--subsets", "3", "--window", "15"}),
                   "--subsets: 3 subsets need at least 3 windows");
  expect_bad_input(stride(dir, {"calibrate", log, "--fit", "trunk_mass", "--out", out.string(),
                                "--robot-mass", "6.6", "--subsets", "0"}),
                   "--robot-mass: sets the trunk mass");
  expect_bad_input(stride(dir, {"calibrate", log, "--fit", "latency", "--out", out.string(),
                                "--robot-mass", "20", "--subsets", "0"}),
                   "--robot-mass: 20 kg is too far from the model's 6.460 kg");
  const auto broken = dir.write("broken.json", R"({"format": "stride-world", "robot": 3})");
  expect_bad_input(stride(dir, {"calibrate", log, "--fit", "latency", "--out", out.string(),
                                "--world", broken.string()}),
                   "robot: must be an object");
  expect_bad_input(stride(dir, {"sim", "stand", "--world", broken.string()}),
                   "robot: must be an object");
  EXPECT_FALSE(std::filesystem::exists(out));
}

/// The mean accelerometer reading over ticks [from, to) of a flight log [m/s^2].
Eigen::Vector3d mean_accel(const std::filesystem::path& log_path, std::size_t from,
                           std::size_t to) {
  fw::FlightLog log;
  EXPECT_TRUE(fw::read_flight_log(log_path, log));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  if (log.ticks.size() < to) {
    ADD_FAILURE() << log_path << ": " << log.ticks.size() << " ticks";
    return sum;
  }
  for (std::size_t i = from; i < to; ++i) {
    const auto& a = log.ticks[i].sensors.cm730.accel_mps2;
    sum += Eigen::Vector3d(a[0], a[1], a[2]);
  }
  return sum / static_cast<double>(to - from);
}

// Issue 30 point 5: the routine (standing 20 s, sway and squats, weight shifts) recorded by the
// product with noise on, on a robot whose trunk is 10 % heavier with its centre of mass 1 cm
// forward, whose MX-106 servos give 0.85 of their torque, with one tick of bus latency and a
// 14.0 V supply; its accelerometer carries the bias the world draws per episode (0.1 m/s^2 per
// axis). Calibrated from the nominal world with two measured inputs (calibration.hpp says why
// they are not fitted): the supply as the log reads it and the trunk mass from the robot
// weighed (--robot-mass: the perturbed model's total mass). Fitted: each value within 20 % of
// its perturbation, or within the stated tolerance where it is 0; the accelerometer biases
// within 20 % of the drawn bias (x) or 0.02 m/s^2 (y, where the draw is small), the drawn bias
// measured as the noisy log's standing readings less those of the same robot standing without
// noise. Then the replay objective is at most a third of the nominal world's, and the forward
// walk's time to 2.5 m within 5 % of the perturbed robot's. Two values these parts do not tell
// (measured), so the test does not claim them: the MX-64 torque scale (arms and head; the arms
// hang still: J equal within 0.01 at x1.02 and x1.09), left out of the fit, and the trunk's
// centre of mass, fitted (left out, the MX-106 scale takes its place: 0.809) but not asserted:
// with the trunk heavier and the MX-106 weaker, J is 14.17 at a true 15 mm and 14.15 at 7.9 mm.
// calibrate_urdf_robot_test.cpp asserts the centre of mass where the routine tells it.
TEST(CalibratePerturbedRobot, ServoLatencyAndBiasLandWithinTwentyPercentAndTheWalkIsPredicted) {
  test::TempDir dir;
  const auto perturbed = dir.write("perturbed.json", R"({"format": "stride-world",
      "supply_voltage_v": 14.0, "robot": {"torque_scale": {"MX-106": 0.85}, "latency_ticks": 1,
      "trunk_mass_scale": 1.1, "trunk_com_offset_m": [0.01, 0.0]}})");
  const auto log = dir.path() / "routine.flog";
  CliRun run = stride(dir, {"identify", "--out", log.string(), "--world", perturbed.string(),
                            "--parts", "stand,identify_stand,identify_shift"});
  ASSERT_EQ(run.code, 0) << run.err;
  const auto quiet = dir.path() / "quiet.flog";
  run = stride(dir, {"identify", "--out", quiet.string(), "--world", perturbed.string(), "--parts",
                     "stand", "--stand-s", "5", "--noise", "off"});
  ASSERT_EQ(run.code, 0) << run.err;
  const Eigen::Vector3d drawn_bias = mean_accel(log, 100, 500) - mean_accel(quiet, 100, 500);
  // The robot weighed: the perturbed model's total mass.
  WorldFile perturbation;
  ASSERT_TRUE(load_world_file(perturbed, perturbation));
  WorldOptions weighed_world;
  weighed_world.ball.present = false;
  perturbation.apply_calibration(weighed_world);
  std::unique_ptr<SimWorld> weighed;
  ASSERT_TRUE(SimWorld::create(weighed_world, weighed));
  const double weighed_kg = weighed->model().total_mass();

  const auto world = dir.path() / "calibrated.json";
  run = stride(dir, {"calibrate", log.string(), "--robot-mass", std::to_string(weighed_kg), "--fit",
                     "torque_mx106,latency,trunk_com_x,trunk_com_y,accel_bias_x,"
                     "accel_bias_y",
                     "--out", world.string(), "--subsets", "0", "--jobs", "2"});
  ASSERT_EQ(run.code, 0) << run.err;
  std::printf("%s", run.out.c_str());
  std::printf("weighed %.4f kg; drawn accelerometer bias %.4f %.4f m/s^2\n", weighed_kg,
              drawn_bias.x(), drawn_bias.y());
  WorldFile fit;
  ASSERT_TRUE(load_world_file(world, fit));
  // The values the routine does not identify on drawn robots are fitted with a warning each.
  for (const char* warned : {"torque_mx106", "trunk_com_x", "trunk_com_y"})
    EXPECT_NE(run.err.find(std::string("warning: --fit ") + warned + ": not identified"),
              std::string::npos)
        << warned << " in:\n"
        << run.err;
  // The lateral accelerometer bias, with the lateral centre of mass fitted too.
  EXPECT_NE(run.err.find("warning: --fit accel_bias_y: not identified by the routine with "
                         "trunk_com_y also fitted"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(fit.calibration["warnings"].size(), 4u);
  EXPECT_EQ(run.err.find("--fit latency"), std::string::npos);
  // Fitted.
  EXPECT_NEAR(fit.robot.torque_scale_mx106, 0.85, 0.2 * 0.15);
  EXPECT_EQ(fit.robot.latency_ticks, 1);
  ASSERT_GT(std::abs(drawn_bias.x()), 0.1);  // measured -0.254: a fit that ignored it fails
  EXPECT_NEAR(fit.accel_bias_mps2.x(), drawn_bias.x(), 0.2 * std::abs(drawn_bias.x()));
  EXPECT_NEAR(fit.accel_bias_mps2.y(), drawn_bias.y(), 0.02);  // stated tolerance
  EXPECT_LE(fit.calibration["objective"].get<double>(),
            fit.calibration["objective_nominal"].get<double>() / 3.0);

  const auto time_to_goal = [&dir](const std::string& w) {
    const CliRun sim =
        stride(dir, {"sim", "walk", "--vx", "1", "--duration", "40", "--world", w, "--json"});
    EXPECT_EQ(sim.code, 0) << sim.err;
    const nlohmann::json j = nlohmann::json::parse(sim.out);
    return j["time_to_goal_s"].is_number() ? j["time_to_goal_s"].get<double>() : 1e9;
  };
  const double truth = time_to_goal(perturbed.string());
  const double calibrated = time_to_goal(world.string());
  const double nominal = time_to_goal("faithful");
  std::printf("time to 2.5 m: perturbed %.2f s, calibrated %.2f s, nominal %.2f s\n", truth,
              calibrated, nominal);
  EXPECT_NEAR(calibrated / truth, 1.0, 0.05);
  EXPECT_GT(std::abs(nominal / truth - 1.0), 0.05);  // the calibration is what closes the gap
}

}  // namespace
}  // namespace stride::sim
