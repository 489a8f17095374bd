// The two physics engines side by side: real-time factor of MuJoCo against Simbody on the same
// URDF and the same motions (standing, stepping in place open loop, the firmware walking
// forward with Ind_O), measured in alternation in one run: each round steps a Simbody world
// and then a MuJoCo world through the same number of control periods, and the ratio of their
// times is taken per round, so that the host's drift cancels. Reported: per motion, the
// median and quartiles of rtf(mujoco) / rtf(simbody), and each engine's median rtf.
// Run: build/release/bench/bench_sim_hal_engines [rounds, default 15]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace {

using stride::sim::EngineKind;
namespace fw = stride::fw;
namespace hal = stride::hal;
namespace sim = stride::sim;
using Clock = std::chrono::steady_clock;

/// One engine running one motion: a robot and, for the walk, the firmware driving it.
class Runner {
 public:
  Runner(EngineKind engine, const std::string& motion) : motion_(motion) {
    if (!fw::Firmware::create({}, firmware_)) std::abort();
    sim::WorldOptions options;
    options.engine = engine;
    options.control_period_ns = firmware_->period_ns();
    std::unique_ptr<sim::SimWorld> world;
    if (const stride::Status s = sim::SimWorld::create(options, world); !s) {
      std::fprintf(stderr, "%s: %s\n", sim::to_string(engine), s.message().c_str());
      std::exit(2);
    }
    robot_ = std::make_unique<sim::SimRobot>(std::move(world));
    if (motion_ == "walk") firmware_->controller().request(fw::MotionRequest::walk(1.0, 0, 0));
  }

  /// Advances `periods` control periods; false once the robot fell or the world failed.
  bool run(int periods) {
    for (int k = 0; k < periods; ++k) {
      hal::CommandFrame commands;
      if (motion_ == "walk") {
        hal::SensorFrame sensors;
        robot_->read(sensors);
        commands = firmware_->controller().step(sensors, tick_);
      } else {
        commands = pose_commands(tick_ * 0.01);
      }
      robot_->write(commands);
      robot_->sleep_until(++tick_);
    }
    const sim::SimWorld& w = robot_->world();
    return w.status() == sim::WorldStatus::kRunning && w.torso_pose().linear()(2, 2) > 0.5;
  }

 private:
  /// Standing: the Stand pose. Stepping: the hips roll the torso over one foot while the
  /// other leg lifts, 1.2 s per left+right step (as bench_sim_hal_rtf's stepping).
  hal::CommandFrame pose_commands(double t) const {
    std::array<double, hal::kServoCount> pose = sim::igus_stand_pose();
    if (motion_ == "stepping") {
      const double s = std::sin(2 * M_PI * std::fmod(t, 1.2) / 1.2);
      const double lift_r = std::max(0.0, s * s * s) * 0.25,
                   lift_l = std::max(0.0, -s * s * s) * 0.25;
      for (std::size_t i : {8U, 9U}) pose[i] += -0.09 * s;
      for (std::size_t i : {16U, 17U}) pose[i] -= -0.09 * s;
      pose[10] -= lift_r;
      pose[12] += 2 * lift_r;
      pose[14] -= lift_r;
      pose[11] -= lift_l;
      pose[13] += 2 * lift_l;
      pose[15] -= lift_l;
    }
    hal::CommandFrame frame;
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      frame.servos[i].position_rad = pose[i];
      frame.servos[i].p_gain = 76;
      frame.servos[i].torque_enable = true;
    }
    return frame;
  }

  std::string motion_;
  std::unique_ptr<fw::Firmware> firmware_;
  std::unique_ptr<sim::SimRobot> robot_;
  hal::Tick tick_ = 0;
};

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(3, std::atoi(argv[1])) : 15;
  constexpr int kPeriods = 100;  // 1 s simulated per engine and round
  std::printf("%-9s %6s %9s %9s %9s %12s %12s  %s\n", "motion", "rounds", "ratio_q1", "ratio_med",
              "ratio_q3", "rtf_simbody", "rtf_mujoco", "(ratio = rtf mujoco / simbody)");
  for (const std::string motion : {"stand", "stepping", "walk"}) {
    // Fresh runners whenever either falls, so that both always simulate the same motion.
    std::unique_ptr<Runner> simbody, mujoco;
    std::vector<double> ratios, rtf_s, rtf_m;
    for (int r = 0; r < rounds; ++r) {
      if (!simbody) simbody = std::make_unique<Runner>(EngineKind::kSimbody, motion);
      if (!mujoco) mujoco = std::make_unique<Runner>(EngineKind::kMujoco, motion);
      const auto t0 = Clock::now();
      const bool s_ok = simbody->run(kPeriods);
      const auto t1 = Clock::now();
      const bool m_ok = mujoco->run(kPeriods);
      const auto t2 = Clock::now();
      const double sim_s = kPeriods * 0.01;
      rtf_s.push_back(sim_s / seconds(t0, t1));
      rtf_m.push_back(sim_s / seconds(t1, t2));
      ratios.push_back(seconds(t0, t1) / seconds(t1, t2));
      if (!s_ok) simbody.reset();
      if (!m_ok) mujoco.reset();
    }
    std::printf("%-9s %6d %9.2f %9.2f %9.2f %12.1f %12.1f\n", motion.c_str(), rounds,
                quantile(ratios, 0.25), quantile(ratios, 0.5), quantile(ratios, 0.75),
                quantile(rtf_s, 0.5), quantile(rtf_m, 0.5));
  }
  return 0;
}
