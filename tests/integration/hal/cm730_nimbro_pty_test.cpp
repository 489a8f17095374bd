// The CM730 with NimbRo's firmware end to end on a pseudo-terminal: `stride vbus` serving the
// simulated robot with that table (--imu cm730-nimbro), the serial HAL (libserialport) reading
// its 16-bit IMU and magnetometer, the start-up model check against the other profile, and
// stride-fw's --cm730 option (one-line error on a bad value; a run on the NimbRo bus).
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "child_process.hpp"
#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/dynamixel_robot.hpp"
#include "temp_dir.hpp"

namespace {

namespace dxl = stride::hal::dxl;
const std::string kBin = STRIDE_BIN_DIR;
using stride::test::slurp;
using stride::test::spawn;
using stride::test::wait_exit;

class Vbus {
 public:
  Vbus(const stride::test::TempDir& dir, const std::vector<std::string>& extra)
      : link_(dir.path() / "bus"), err_(dir.path() / "vbus.err") {
    std::vector<std::string> argv{kBin + "/stride", "vbus", "--link", link_.string(), "--no-rt"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    pid_ = spawn(argv, dir.path() / "vbus.out", err_);
    for (int i = 0; i < 1000 && slurp(err_).find("serving on") == std::string::npos; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ~Vbus() {
    kill(pid_, SIGINT);
    wait_exit(pid_);
  }
  std::string link() const { return link_.string(); }
  std::string errors() const { return slurp(err_); }

 private:
  std::filesystem::path link_, err_;
  pid_t pid_ = -1;
};

dxl::DynamixelRobot::Options options(dxl::Cm730Profile profile) {
  auto o = stride::fw::dynamixel_options(stride::fw::ServoTable::defaults(), 10'000'000);
  o.cm730_profile = profile;
  o.margin_ns = 20'000'000;  // a pty on a shared machine, not a line
  return o;
}

TEST(Cm730NimbroPty, SerialHalReadsTheSimulatedNimbroImuAndMagnetometer) {
  stride::test::TempDir dir;
  Vbus vbus(dir, {"--sim", "--imu", "cm730-nimbro", "--seed", "4"});
  ASSERT_NE(vbus.errors().find("nimbro CM730"), std::string::npos) << vbus.errors();
  std::unique_ptr<dxl::DynamixelRobot> robot;
  const stride::Status s =
      dxl::open_dynamixel_robot(vbus.link(), 1'000'000, options(dxl::Cm730Profile::kNimbro), robot);
  ASSERT_TRUE(s.is_ok()) << s.message() << "\n" << vbus.errors();
  stride::hal::SensorFrame frame;
  robot->read(frame);
  // Hold the pose the simulation starts in (torque is off until written, and the robot would
  // fold).
  stride::hal::CommandFrame hold;
  for (std::size_t i = 0; i < stride::hal::kServoCount; ++i) {
    hold.servos[i].position_rad = frame.servos[i].position_rad;
    hold.servos[i].torque_enable = true;
    hold.servos[i].p_gain = 32;
  }
  robot->set_torque_enable(true);
  int good = 0;
  for (int tick = 1; tick <= 60; ++tick) {
    robot->write(hold);
    robot->sleep_until(tick);
    robot->read(frame);
    if (frame.cm730.health != stride::hal::DeviceHealth::kOk) continue;
    ++good;
    const auto& m = frame.cm730.mag_gauss;
    const auto& a = frame.cm730.accel_mps2;
    ASSERT_TRUE(frame.cm730.has_magnetometer);
    // Standing: the Earth's 0.49 gauss, 66 deg down, give or take the floor's 0.03 gauss and
    // the hard iron's 0.01 per axis.
    const double norm = std::hypot(m[0], m[1], m[2]);
    EXPECT_GT(norm, 0.42) << tick;
    EXPECT_LT(norm, 0.56) << tick;
    EXPECT_LT(m[2], -0.38) << tick;
    // Specific force 1 g once the robot has settled on the ground (about 0.15 s after the
    // reset; it stands leaning, so not all of it along z).
    if (tick > 20) {
      EXPECT_NEAR(std::hypot(a[0], a[1], a[2]), 9.81, 0.4) << tick;
      EXPECT_GT(a[2], 9.0) << tick;
    }
    // 1/820 gauss steps and NimbRo's gyro steps arrive intact over the wire.
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(m[k] * 820.0, std::round(m[k] * 820.0), 1e-6);
      const double g = frame.cm730.gyro_rad_s[k] / dxl::units::kNimbroGyroPerLsb;
      EXPECT_NEAR(g, std::round(g), 1e-6);
    }
  }
  EXPECT_GE(good, 50);
}

TEST(Cm730NimbroPty, StockHalOnTheNimbroBusIsAModelError) {
  stride::test::TempDir dir;
  Vbus vbus(dir, {"--cm730", "nimbro"});
  std::unique_ptr<dxl::DynamixelRobot> robot;
  const stride::Status s =
      dxl::open_dynamixel_robot(vbus.link(), 1'000'000, options(dxl::Cm730Profile::kStock), robot);
  ASSERT_FALSE(s.is_ok());
  EXPECT_NE(s.message().find("200 CM730 is CM730 (NimbRo firmware) (29441), --cm730 stock "
                             "expects CM730 (29440)"),
            std::string::npos)
      << s.message();
}

TEST(Cm730NimbroPty, StrideFwRunsOnTheNimbroBusAndRejectsABadProfile) {
  stride::test::TempDir dir;
  const auto out = dir.path() / "fw.out", err = dir.path() / "fw.err";
  pid_t pid = spawn({kBin + "/stride-fw", "--hal", "serial", "--port", "/dev/null", "--cm730",
                     "nimbro2", "--ticks", "1"},
                    out, err);
  EXPECT_NE(wait_exit(pid), 0);
  const std::string message = slurp(err);
  EXPECT_NE(message.find("option --cm730: expected stock or nimbro, got 'nimbro2'"),
            std::string::npos)
      << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;

  Vbus vbus(dir, {"--sim", "--imu", "cm730-nimbro"});
  pid = spawn({kBin + "/stride-fw", "--hal", "serial", "--port", vbus.link(), "--cm730", "nimbro",
               "--ticks", "200", "--bus-margin-us", "4000", "--json"},
              out, err);
  ASSERT_EQ(wait_exit(pid), 0) << slurp(err);
  const std::string report = slurp(out);
  EXPECT_NE(report.find("\"200 CM730\""), std::string::npos);
  EXPECT_NE(slurp(err).find("21 of 21 devices found"), std::string::npos) << slurp(err);
}

}  // namespace
