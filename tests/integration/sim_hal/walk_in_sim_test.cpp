// The walk engine in the Simbody simulation (issue 5 point 6): the firmware (Controller,
// motion manager, walk engine, safety layer) drives the simulated igus robot with the default
// (Ind_O) parameters and sensor noise on.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "seeds.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride {
namespace {

struct WalkCommand {
  double vx = 0.0, vy = 0.0, vtheta = 0.0;
};

/// Where a walk ended, free of the step's sway: the torso yaw averaged over the last 2 s (two
/// and a bit steps; the torso yaws +-4 deg once per step pair) and the feet's midpoint.
struct WalkEnd {
  double mean_yaw = 0.0;              ///< [rad]
  double feet_x = 0.0, feet_y = 0.0;  ///< [m]
};

sim::EpisodeResult walk_in_sim(std::uint64_t seed, WalkCommand command, double duration_s,
                               const std::vector<fw::ParamWrite>& overrides = {},
                               double* yaw_out = nullptr, double* y_out = nullptr,
                               double left_hip_yaw_offset = 0.0, WalkEnd* end = nullptr,
                               bool seed_world = false, bool stop_at_goal = false) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  // seed_world: the thesis's world and the firmware's walk defaults of then.
  if (seed_world) {
    EXPECT_TRUE(
        firmware->params().load_file_now(STRIDE_SOURCE_DIR "/firmware/config/seed-walk.json"));
  }
  if (!overrides.empty()) {
    EXPECT_TRUE(firmware->params().set_now(overrides));
  }
  sim::WorldOptions options;
  if (seed_world) options.apply(sim::WorldPreset::kSeed);
  options.seed = seed;
  options.imu.set_noise(true);
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  const Status created = sim::SimWorld::create(options, world);
  EXPECT_TRUE(created) << created.message();
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(command.vx, command.vy, command.vtheta));
  const std::size_t hip_yaw = *firmware->servos().index_of("l_hip_yaw");
  const auto last_ticks = static_cast<hal::Tick>(std::llround((duration_s - 2.0) / 0.01));
  double yaw_sum = 0.0;
  int yaw_samples = 0;
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    if (end != nullptr && tick > last_ticks) {
      const Eigen::Isometry3d torso = robot.world().torso_pose();
      yaw_sum += std::atan2(torso.linear()(1, 0), torso.linear()(0, 0));
      ++yaw_samples;
    }
    hal::CommandFrame commands = controller.step(sensors, tick);
    // A disturbance the walk does not know of: the left hip yaw servo off by a fixed angle
    // (a miscalibrated zero), which turns every left step.
    commands.servos[hip_yaw].position_rad += left_hip_yaw_offset;
    return commands;
  };
  sim::EpisodeOptions episode;
  episode.duration_s = duration_s;
  episode.stop_at_goal = stop_at_goal;
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  const Eigen::Isometry3d torso = robot.world().ground_truth().torso;
  if (yaw_out != nullptr) {
    *yaw_out = std::atan2(torso.linear()(1, 0), torso.linear()(0, 0));
  }
  if (y_out != nullptr) *y_out = torso.translation().y();
  if (end != nullptr) {
    const sim::GroundTruth truth = robot.world().ground_truth();
    end->mean_yaw = yaw_samples > 0 ? yaw_sum / yaw_samples : 0.0;
    end->feet_x = 0.5 * (truth.left_foot.translation().x() + truth.right_foot.translation().x());
    end->feet_y = 0.5 * (truth.left_foot.translation().y() + truth.right_foot.translation().y());
  }
  return result;
}

// Issue 5 asks for 10 of 10 seeds forward and 20 s backward, sideways and turning without a
// fall. With the balance defaults of firmware/src/walk/README.md (gyro rate and torso tilt
// feedback) the simulated robot reaches 2.5 m (the episode ends there) and beats the seed's
// Ind_O (32.5 s, peak |a| 70.75 m/s^2). The walk is still sensitive to small changes (the
// parameters were found by a search), so the seeds are counted with one to spare
// (tests/README.md). Measured 2026-11-28, seeds 1-20: 20 of 20 reach 2.5 m, median 19.24 s (IQR
// 0.22), peak |a| median 21.8 m/s^2 (IQR 1.15).
TEST(WalkInSim, ForwardTwoAndAHalfMetresOnTenSeedsAndFasterThanTheSeed) {
  int reached = 0;
  const std::vector<test::Figures> f =
      test::Seeds(10).run({"time to 2.5 m [s]", "peak |a| [m/s^2]"}, [&](std::uint64_t seed) {
        const sim::EpisodeResult r = walk_in_sim(seed, {1.0, 0.0, 0.0}, 60.0, {}, nullptr, nullptr,
                                                 0.0, nullptr, false, true);
        EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
        const bool goal = !r.fell && r.time_to_goal_s.has_value();
        reached += goal ? 1 : 0;
        return std::vector<double>{goal ? *r.time_to_goal_s : 1e9, r.max_accel};
      });
  const int n = static_cast<int>(f[0].size());
  EXPECT_GE(reached, n - 1);
  EXPECT_LT(f[0].median(), 32.5);   // 19.24 s, IQR 0.22 (seeds 1-20)
  EXPECT_LT(f[1].median(), 70.75);  // 21.8 m/s^2, IQR 1.15 (seeds 1-20)
}

// Sideways both ways, backward and turning on the spot (both ways): 12 s without a fall, the
// world healthy, on seeds 1-5; sideways moves the commanded way (the torso rocks about +-0.12 m
// laterally, see firmware/src/walk/README.md, so the figure is the torso's end y). Seed 1 over
// 20 s measured 0.136 m left and -0.080 m right. Measured 2026-11-28, seeds 1-20 (12 s): no fall in
// 100 walks; torso y left median 0.047 m (IQR 0.024, 0.018-0.075), right -0.052 m (IQR 0.010,
// -0.076 to -0.033): each of the 20 seeds the commanded way, which a count judges (the left median
// is 2 IQR from 0).
TEST(WalkInSim, SidewaysBackwardAndTurningWithoutFalling) {
  struct Direction {
    const char* name;
    WalkCommand command;
  };
  for (const Direction d :
       {Direction{"left", {0.0, 1.0, 0.0}}, Direction{"right", {0.0, -1.0, 0.0}},
        Direction{"backward", {-1.0, 0.0, 0.0}}, Direction{"turn left", {0.0, 0.0, 1.0}},
        Direction{"turn right", {0.0, 0.0, -1.0}}}) {
    SCOPED_TRACE(d.name);
    int upright = 0;
    const test::Figures y =
        test::Seeds(5).run(std::string(d.name) + ": torso y [m]", [&](std::uint64_t seed) {
          double end_y = 0.0;
          const sim::EpisodeResult r = walk_in_sim(seed, d.command, 12.0, {}, nullptr, &end_y);
          EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
          upright += r.fell ? 0 : 1;
          return end_y;
        });
    EXPECT_GE(upright, static_cast<int>(y.size()) - 1) << "12 s without a fall";
    if (d.command.vy != 0.0) {
      const int commanded_way = d.command.vy > 0 ? y.count_above(0.0) : y.count_at_most(0.0);
      EXPECT_GE(commanded_way, static_cast<int>(y.size()) - 1) << "sideways the commanded way";
    }
  }
}

}  // namespace
}  // namespace stride

namespace stride {
namespace {

// Heading hold (walk.balance.heading_*, gain 0.5 by default since issue 29; these tests set it
// on or off themselves; firmware/src/walk/README.md has the measurements behind the settings
// used here).
const std::vector<fw::ParamWrite> kHoldOn{{"walk.balance.heading_gain", 0.5},
                                          {"walk.balance.heading_max_correction", 0.3}};
constexpr double kDeg = 180.0 / 3.141592653589793;

// The stock forward walk, 20 s, seeds 1..10: with the hold on the median seed ends within a few
// degrees of its start heading (mean over the last 2 s) and its feet near the start line.
// Measured 2026-11-28, seeds 1-20: median |yaw| 1.42 deg (IQR 1.42, up to 4.06), median |feet y|
// 0.008 m (IQR 0.024, up to 0.073); no fall in seeds 1-20 (the worst of seeds 1-10, which the test
// asserted before: 4.4 deg or 3.46 deg, 0.035 or 0.073 m; the hold off 7.7 deg, 0.118 m). Pins the
// seed's world and walk (issue 22's measurement). In the faithful default world the closed-loop
// walk with the same hold ends up to 17.8 deg off and its feet up to 0.50 m to the side (seeds
// 1-10): the straightness of issue 29 point 5, not met there.
TEST(WalkHeadingHold, StockForwardWalkStaysOnItsHeading) {
  int walked = 0;
  const std::vector<test::Figures> f =
      test::Seeds(10).run({"|mean yaw| [deg]", "|feet y| [m]"}, [&](std::uint64_t seed) {
        WalkEnd e;
        const sim::EpisodeResult r =
            walk_in_sim(seed, {1.0, 0.0, 0.0}, 20.0, kHoldOn, nullptr, nullptr, 0.0, &e, true);
        walked += !r.fell && r.distance_m > 1.5 ? 1 : 0;
        return std::vector<double>{std::abs(e.mean_yaw) * kDeg, std::abs(e.feet_y)};
      });
  // Walked 1.5 m without a fall: 91 of seeds 1-100 (2026-11-28, this test's episode on main at
  // 43103d6; seeds 25, 38, 43, 55, 59, 70, 73, 82 and 85 fell or fell short), though seeds 1-20
  // happened to hold all 20. So the count is 91 % of N with one to spare, not N - 1.
  EXPECT_GE(walked, test::count_limit(91.0 / 100.0, static_cast<int>(f[0].size())))
      << "1.5 m without a fall";
  EXPECT_LT(f[0].median(), 6.0);   // 1.42 deg, IQR 1.42 (seeds 1-20)
  EXPECT_LT(f[1].median(), 0.08);  // 0.008 m, IQR 0.024 (seeds 1-20)
}

// A disturbance the walk does not model: the left hip yaw servo 0.1 rad off its zero. Without
// the hold the robot turns; the hold keeps it nearer its heading. 12 s walks on seeds 1-5. Measured
// 2026-11-28, seeds 1-20: hold on median 3.18 deg (IQR 6.6), off 22.96 deg (IQR 11.9); the hold
// ended nearer its heading on 19 of 20 seeds (not seed 14, whose open walk happened to end 0.5 deg
// off): a count, as the medians' spreads are wide.
TEST(WalkHeadingHold, CorrectsAHipYawDisturbanceTheOpenWalkTurnsWith) {
  int upright = 0;
  const std::vector<test::Figures> f =
      test::Seeds(5).run({"hold on |yaw| [deg]", "hold off |yaw| [deg]"}, [&](std::uint64_t seed) {
        WalkEnd on, off;
        const sim::EpisodeResult r_on =
            walk_in_sim(seed, {1.0, 0.0, 0.0}, 12.0, kHoldOn, nullptr, nullptr, 0.1, &on);
        const sim::EpisodeResult r_off =
            walk_in_sim(seed, {1.0, 0.0, 0.0}, 12.0, {{"walk.balance.heading_gain", 0.0}}, nullptr,
                        nullptr, 0.1, &off);
        upright += !r_on.fell && !r_off.fell ? 1 : 0;
        return std::vector<double>{std::abs(on.mean_yaw) * kDeg, std::abs(off.mean_yaw) * kDeg};
      });
  const int n = static_cast<int>(f[0].size());
  EXPECT_GE(upright, n - 1);
  int nearer = 0;
  for (int i = 0; i < n; ++i) nearer += f[0].values()[i] < f[1].values()[i] ? 1 : 0;
  EXPECT_GE(nearer, test::count_limit(19.0 / 20.0, n)) << "the hold ends nearer its heading";
  // The open walk turns: beyond 6 deg on 19 of 20 seeds (all but seed 14).
  EXPECT_GE(f[1].count_above(6.0), test::count_limit(19.0 / 20.0, n));
}

}  // namespace
}  // namespace stride
