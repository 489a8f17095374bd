// Issue 30 point 4 in the simulator: the identification scripts (firmware/scripts/identify_*.json,
// IDENTIFICATION.md) play in the faithful world (identified MX servos, CM730 IMU, noise on)
// without a fall, and the trunk moves as intended, measured on the ground truth: the squats
// lower the trunk, the sway moves the centre of mass fore and aft, the weight shifts put the
// centre of mass over each foot in turn (and the load on it), the steps lift each foot.
// Figures are printed for the report.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "seeds.hpp"
#include "stride/sim_hal/script_episodes.hpp"

namespace stride::sim {
namespace {

// Seed 1 is the nominal robot. The scripts do not read the IMU, so its noise alone would give
// every seed the same motion: the seeds after it also randomise the robot as the kick test does
// (friction +-20 %, masses +-5 %, servo strength +-10 %, 5 % chance of a tick of latency).
// Each figure is judged as its median over seeds 1-5 (tests/README.md), and no fall as a count
// with one to spare.
WorldOptions faithful_world(std::uint64_t seed) {
  WorldOptions options;  // as `--servo-law identified --imu cm730 --noise on`
  options.seed = seed;
  if (seed > 1) {
    options.randomise.friction_range = 0.2;
    options.randomise.mass_range = 0.05;
    options.randomise.strength_range = 0.1;
    options.randomise.latency_probability = 0.05;
  }
  options.servo.law = ServoLaw::kIdentified;
  options.imu.set_noise(true);
  options.imu.chain = ImuChain{};
  options.imu.chain.noise = true;
  return options;
}

struct Sample {
  double t = 0.0;
  double torso_z = 0.0;
  double pitch = 0.0;       ///< trunk pitch, + forward [rad]
  double roll = 0.0;        ///< trunk roll, + to the right (left side up) [rad]
  Eigen::Vector3d com_rel;  ///< centre of mass minus the midpoint of the two feet (world)
  Eigen::Vector3d com, left_foot, right_foot;
  double left_fz = 0.0, right_fz = 0.0;
};

struct Trace {
  EpisodeResult result;
  std::vector<Sample> samples;
  double start_s = 1.0;  ///< when the script was requested
  /// Mean of `f` over [from, to).
  template <typename F>
  double mean(double from, double to, F f) const {
    double sum = 0.0;
    int n = 0;
    for (const Sample& s : samples) {
      if (s.t >= from && s.t < to) {
        sum += f(s);
        ++n;
      }
    }
    return n > 0 ? sum / n : std::nan("");
  }
  template <typename F>
  double max(F f) const {
    double m = -1e9;
    for (const Sample& s : samples) {
      if (s.t >= start_s) m = std::max(m, f(s));
    }
    return m;
  }
  template <typename F>
  double min(F f) const {
    return -max([&](const Sample& s) { return -f(s); });
  }
};

Trace play(const std::string& script, std::uint64_t seed, double script_s) {
  Trace trace;
  KickEpisodeOptions options;
  options.script = script;
  options.kick_at_s = trace.start_s;
  options.duration_s = trace.start_s + script_s + 2.0;
  options.ball_position = {1.5, 1.0, std::nan("")};  // out of the way
  options.episode.on_tick = [&](hal::Tick, const SimWorld& world, const hal::SensorFrame&) {
    const GroundTruth truth = world.ground_truth();
    Sample s;
    s.t = truth.time_s;
    s.torso_z = truth.torso.translation().z();
    const Eigen::Matrix3d r = truth.torso.linear();
    s.pitch = std::atan2(r(0, 2), r(2, 2));
    s.roll = std::atan2(-r(1, 2), r(2, 2));
    s.com = truth.center_of_mass;
    s.left_foot = truth.left_foot.translation();
    s.right_foot = truth.right_foot.translation();
    s.com_rel = s.com - 0.5 * (s.left_foot + s.right_foot);
    s.left_fz = truth.left_contact.force.z();
    s.right_fz = truth.right_contact.force.z();
    trace.samples.push_back(s);
  };
  const Status status = run_kick_episode(faithful_world(seed), options, trace.result);
  EXPECT_TRUE(status) << status.message();
  EXPECT_EQ(trace.result.status, WorldStatus::kRunning) << trace.result.failure_reason;
  if (trace.result.fell)
    std::printf("  %s seed %llu fell at %.2f s\n", script.c_str(),
                static_cast<unsigned long long>(seed), trace.result.fall_time_s);
  return trace;
}

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// The largest change of the trunk's pitch or roll from its stand attitude (the igus stand leans
// the trunk forward by about 11 deg) [deg].
double max_tilt_change_deg(const Trace& trace) {
  const double pitch0 = trace.mean(0.8, 1.0, [](const Sample& s) { return s.pitch; });
  const double roll0 = trace.mean(0.8, 1.0, [](const Sample& s) { return s.roll; });
  return trace.max([&](const Sample& s) {
    return std::max(std::abs(s.pitch - pitch0), std::abs(s.roll - roll0)) / kDegree;
  });
}

// Measured 2026-11-28, seeds 1-20: no fall in 20; squat drop 39.1 mm (IQR 0.03), CoM 27.4 mm
// forward and 31.1 mm back (IQR 0.2), tilt 4.52 deg (IQR 0.02), back to 0.02 mm of the stand
// height.
TEST(IdentifyScripts, StandSwayAndSquats) {
  int upright = 0;
  const std::vector<test::Figures> f = test::Seeds(5).run(
      {"squat drop [m]", "CoM forward [m]", "CoM back [m]", "max tilt [deg]", "end height [m]"},
      [&](std::uint64_t seed) {
        const Trace trace = play("identify_stand", seed, 33.2);
        upright += trace.result.fell ? 0 : 1;
        const double z0 = trace.mean(0.8, 1.0, [](const Sample& s) { return s.torso_z; });
        const double x0 = trace.mean(0.8, 1.0, [](const Sample& s) { return s.com_rel.x(); });
        return std::vector<double>{z0 - trace.min([](const Sample& s) { return s.torso_z; }),
                                   trace.max([](const Sample& s) { return s.com_rel.x(); }) - x0,
                                   x0 - trace.min([](const Sample& s) { return s.com_rel.x(); }),
                                   max_tilt_change_deg(trace),
                                   std::abs(trace.samples.back().torso_z - z0)};
      });
  EXPECT_GE(upright, static_cast<int>(f[0].size()) - 1);
  EXPECT_GE(f[0].median(), 0.030);  // 39.1 mm
  EXPECT_GE(f[1].median(), 0.020);  // 27.4 mm
  EXPECT_GE(f[2].median(), 0.020);  // 31.1 mm
  EXPECT_LT(f[3].median(), 10.0);   // 4.52 deg
  EXPECT_LT(f[4].median(), 0.01);   // back to the stand height: 0.02 mm
}

// The inner stud line of each foot: 0.0375 m inside the ankle (URDF collision spheres).
// Measured 2026-11-28, seeds 1-20: no fall in 20; CoM 11.5 and 11.3 mm inside the inner stud lines
// (IQR 0.5, 0.7), load 98.5 % and 98.7 % (IQR 0.3), tilt 2.49 deg (IQR 0.03).
TEST(IdentifyScripts, WeightShiftsPutTheCentreOfMassOverEachFoot) {
  int upright = 0;
  const std::vector<test::Figures> f = test::Seeds(5).run(
      {"inside left [m]", "inside right [m]", "left load", "right load", "max tilt [deg]"},
      [&](std::uint64_t seed) {
        const Trace trace = play("identify_shift", seed, 24.0);
        upright += trace.result.fell ? 0 : 1;
        const auto share = [](double mine, double other) {
          return mine / std::max(mine + other, 1e-6);
        };
        return std::vector<double>{
            trace.max([](const Sample& s) { return s.com.y() - (s.left_foot.y() - 0.0375); }),
            trace.max([](const Sample& s) { return (s.right_foot.y() + 0.0375) - s.com.y(); }),
            trace.max([&](const Sample& s) { return share(s.left_fz, s.right_fz); }),
            trace.max([&](const Sample& s) { return share(s.right_fz, s.left_fz); }),
            max_tilt_change_deg(trace)};
      });
  EXPECT_GE(upright, static_cast<int>(f[0].size()) - 1);
  EXPECT_GT(f[0].median(), 0.005);  // 11.5 mm
  EXPECT_GT(f[1].median(), 0.005);  // 11.3 mm
  EXPECT_GT(f[2].median(), 0.85);   // 98.5 %
  EXPECT_GT(f[3].median(), 0.85);   // 98.7 %
  EXPECT_LT(f[4].median(), 10.0);   // 2.49 deg
}

// In single support the stance hip roll (gain 40) gives way under the trunk. With the weight
// shifted 0.25 rad before the lift, the randomised robots (seeds 2 on) fell in this script in 9
// of 20 seeds (tilted about 60 deg towards the stance side, a foot 0.1 m up), and 16 of 160
// recordings of the calibration study's robots fell; at 0.22 rad (issue 56) none of either.
// Measured 2026-11-28, seeds 1-20: 20 of 20 stand, the left foot rises a median 11.5 mm (11.5-11.9),
// the right 12.5 mm (12.4-12.7), tilt 14.6 deg (14.5-14.7), the feet back within 0.1 mm.
TEST(IdentifyScripts, SlowStepsInPlaceLiftEachFoot) {
  std::vector<double> left, right, tilt, left_end, right_end;
  int upright = 0;
  const int n = test::seed_count(5);
  for (std::uint64_t seed = 1; seed <= static_cast<std::uint64_t>(n); ++seed) {
    const Trace trace = play("identify_steps", seed, 32.0);
    const double l0 = trace.mean(0.8, 1.0, [](const Sample& s) { return s.left_foot.z(); });
    const double r0 = trace.mean(0.8, 1.0, [](const Sample& s) { return s.right_foot.z(); });
    const double tilt_deg = max_tilt_change_deg(trace);
    std::printf("  seed %llu: fell %d, left lift %.1f mm, right %.1f mm, tilt %.1f deg\n",
                static_cast<unsigned long long>(seed), trace.result.fell ? 1 : 0,
                (trace.max([](const Sample& s) { return s.left_foot.z(); }) - l0) * 1e3,
                (trace.max([](const Sample& s) { return s.right_foot.z(); }) - r0) * 1e3, tilt_deg);
    if (trace.result.fell) continue;
    ++upright;
    left.push_back(trace.max([](const Sample& s) { return s.left_foot.z(); }) - l0);
    right.push_back(trace.max([](const Sample& s) { return s.right_foot.z(); }) - r0);
    tilt.push_back(tilt_deg);
    left_end.push_back(std::abs(trace.samples.back().left_foot.z() - l0));
    right_end.push_back(std::abs(trace.samples.back().right_foot.z() - r0));
  }
  EXPECT_GE(upright, test::count_limit(20.0 / 20.0, n));
  ASSERT_GT(upright, 0);
  EXPECT_GE(test::Figures("left lift [m]", {}, left).median(), 0.007);       // 11.5 mm
  EXPECT_GE(test::Figures("right lift [m]", {}, right).median(), 0.007);     // 12.5 mm
  EXPECT_LT(test::Figures("tilt [deg]", {}, tilt).median(), 23.0);           // 14.6 deg, IQR 0.1
  EXPECT_LT(test::Figures("left end [m]", {}, left_end).median(), 0.005);    // 0.1 mm
  EXPECT_LT(test::Figures("right end [m]", {}, right_end).median(), 0.005);  // 0.1 mm
}

}  // namespace
}  // namespace stride::sim
