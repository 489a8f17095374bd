// The CM730 with NimbRo's firmware (igus.md 6.5): its register scales and signs, its control
// table, and the serial HAL decoding it from the in-process virtual bus serving that table,
// with the start-up model check telling it from the stock board.
#include <gtest/gtest.h>

#include <cmath>

#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/dynamixel_robot.hpp"
#include "stride/hal/dynamixel/units.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "stride/hal/dynamixel/virtual_bus_stream.hpp"

namespace stride::hal::dxl {
namespace {

using namespace units;

TEST(Cm730NimbroUnits, ScalesAreNimbrosAndSigned) {
  // One LSB: (pi/180) 500/65536 rad/s, 8 * 9.81 / 65536 m/s^2, 1/820 gauss.
  EXPECT_NEAR(nimbro_gyro_from_raw(1), 1.3315805e-4, 1e-10);
  EXPECT_NEAR(nimbro_gyro_from_raw(0xFFFF), -1.3315805e-4, 1e-10);  // two's complement
  EXPECT_NEAR(nimbro_gyro_from_raw(0x8000), -250.0 * kPi / 180.0, 1e-9);
  EXPECT_NEAR(nimbro_accel_from_raw(8192), 9.81, 1e-12);
  EXPECT_NEAR(nimbro_accel_from_raw(static_cast<std::uint16_t>(-8192)), -9.81, 1e-12);
  EXPECT_NEAR(nimbro_mag_from_raw(820), 1.0, 1e-12);
  EXPECT_NEAR(nimbro_mag_from_raw(static_cast<std::uint16_t>(-369)), -0.45, 1e-12);
  EXPECT_EQ(nimbro_mag_to_raw(-0.45), static_cast<std::uint16_t>(-369));
  EXPECT_EQ(nimbro_gyro_to_raw(1e9), 0x7FFF);  // clamped, not wrapped
  EXPECT_EQ(nimbro_gyro_to_raw(-1e9), 0x8000);
  EXPECT_EQ(nimbro_accel_to_raw(std::nan("")), 0);
  // A bias of a tenth of the stock register's step is 46 NimbRo steps.
  EXPECT_EQ(static_cast<std::int16_t>(nimbro_gyro_to_raw(0.1 * kGyroPerLsb)), 46);
  for (const double w : {-3.0, -0.01234, 0.0, 0.5, 4.2})
    EXPECT_NEAR(nimbro_gyro_from_raw(nimbro_gyro_to_raw(w)), w, 0.5 * kNimbroGyroPerLsb);
}

TEST(Cm730NimbroTable, AddressesModelAndProfiles) {
  const ControlTable& t = cm730_nimbro_table();
  EXPECT_EQ(t.model_number, 0x7301);
  EXPECT_EQ(t.find("gyro_x")->address, 32);
  EXPECT_EQ(t.find("acc_z")->address, 42);
  EXPECT_EQ(t.find("mag_x")->address, 44);
  EXPECT_EQ(t.find("mag_z")->address, 48);
  EXPECT_EQ(t.find("battery_voltage")->address, 31);
  EXPECT_EQ(t.covering(49)->name, "mag_z");
  EXPECT_EQ(table_for_model(0x7301, Protocol::kV1), &t);
  EXPECT_EQ(&cm730_table(Cm730Profile::kStock), &cm730_table());
  EXPECT_EQ(&cm730_table(Cm730Profile::kNimbro), &t);
  Cm730Profile p = Cm730Profile::kStock;
  EXPECT_TRUE(parse_cm730_profile("nimbro", p));
  EXPECT_EQ(p, Cm730Profile::kNimbro);
  EXPECT_FALSE(parse_cm730_profile("NimbRo", p));
  EXPECT_EQ(p, Cm730Profile::kNimbro);  // unchanged on a bad name
  EXPECT_STREQ(to_string(Cm730Profile::kStock), "stock");
}

/// A still robot whose IMU reads given values (first-order servos).
class FixedImuPhysics final : public VirtualBusPhysics {
 public:
  FixedImuPhysics(const FirstOrderPhysics::Options& servos, const PhysicsImu& imu)
      : servos_(servos), imu_(imu) {}
  void set_command(std::size_t i, const PhysicsServoCommand& c) override {
    servos_.set_command(i, c);
  }
  void advance(double dt_s) override { servos_.advance(dt_s); }
  PhysicsServoState servo_state(std::size_t i) const override { return servos_.servo_state(i); }
  PhysicsImu imu() const override { return imu_; }

 private:
  FirstOrderPhysics servos_;
  PhysicsImu imu_;
};

struct Rig {
  Rig(Cm730Profile bus_profile, Cm730Profile robot_profile, const PhysicsImu& imu) {
    const auto& table = fw::ServoTable::defaults();
    VirtualBus::Options bus_options;
    bus_options.calibration = fw::servo_calibrations(table);
    bus_options.lockstep = true;
    bus_options.cm730_profile = bus_profile;
    FirstOrderPhysics::Options physics;
    for (std::size_t i = 0; i < kServoCount; ++i)
      physics.models[i] = bus_options.calibration[i].model;
    bus =
        std::make_unique<VirtualBus>(bus_options, std::make_unique<FixedImuPhysics>(physics, imu));
    DynamixelRobot::Options options = fw::dynamixel_options(table, 10'000'000);
    options.cm730_profile = robot_profile;
    status =
        DynamixelRobot::create(std::make_unique<VirtualBusStream>(*bus, 1'000'000), options, robot);
  }
  std::unique_ptr<VirtualBus> bus;
  std::unique_ptr<DynamixelRobot> robot;
  Status status;
};

PhysicsImu tilted_imu() {
  PhysicsImu imu;
  imu.accel_mps2 = {-1.234, 0.567, 9.7};
  imu.gyro_rad_s = {0.0123, -0.0047, 0.00321};  // all below one stock step (0.061 rad/s)
  imu.mag_gauss = {0.19, -0.071, -0.447};
  return imu;
}

TEST(Cm730NimbroBus, SerialHalDecodesTheNimbroTable) {
  const PhysicsImu imu = tilted_imu();
  Rig rig(Cm730Profile::kNimbro, Cm730Profile::kNimbro, imu);
  ASSERT_TRUE(rig.status.is_ok()) << rig.status.message();
  // The bus holds NimbRo's registers: signed 16-bit at 32.. (not the stock 10-bit at 38..).
  const auto reg = [&](std::uint8_t a) {
    return static_cast<std::int16_t>(rig.bus->peek(kCm730Id, a) |
                                     (rig.bus->peek(kCm730Id, a + 1) << 8));
  };
  SensorFrame frame;
  rig.robot->sleep_until(1);
  rig.robot->read(frame);
  EXPECT_EQ(reg(cm730_nimbro::kMagZ), -367);  // -0.447 gauss * 820
  EXPECT_EQ(reg(cm730_nimbro::kGyroX), std::lround(0.0123 / kNimbroGyroPerLsb));
  EXPECT_EQ(frame.cm730.health, DeviceHealth::kOk);
  ASSERT_TRUE(frame.cm730.has_magnetometer);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(frame.cm730.gyro_rad_s[k], imu.gyro_rad_s[k], 0.5 * kNimbroGyroPerLsb) << k;
    EXPECT_NEAR(frame.cm730.accel_mps2[k], imu.accel_mps2[k], 0.5 * kNimbroAccelPerLsb) << k;
    EXPECT_NEAR(frame.cm730.mag_gauss[k], imu.mag_gauss[k], 0.5 * kNimbroMagPerLsb) << k;
  }
  EXPECT_NEAR(frame.cm730.voltage_v, 15.0, 1e-9);
}

TEST(Cm730NimbroBus, StockProfileReadsTenBitStepsAndNoMagnetometer) {
  const PhysicsImu imu = tilted_imu();
  Rig rig(Cm730Profile::kStock, Cm730Profile::kStock, imu);
  ASSERT_TRUE(rig.status.is_ok()) << rig.status.message();
  SensorFrame frame;
  rig.robot->sleep_until(1);
  rig.robot->read(frame);
  EXPECT_FALSE(frame.cm730.has_magnetometer);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(frame.cm730.gyro_rad_s[k], 0.0) << k;
  EXPECT_NEAR(frame.cm730.accel_mps2[0], imu.accel_mps2[0], 0.5 * kAccelPerLsb);
}

TEST(Cm730NimbroBus, ProfileMismatchIsAStartUpErrorNamingBoth) {
  Rig stock_board(Cm730Profile::kStock, Cm730Profile::kNimbro, tilted_imu());
  ASSERT_FALSE(stock_board.status.is_ok());
  EXPECT_NE(stock_board.status.message().find("200 CM730 is CM730 (29440), --cm730 nimbro "
                                              "expects CM730 (NimbRo firmware) (29441)"),
            std::string::npos)
      << stock_board.status.message();
  Rig nimbro_board(Cm730Profile::kNimbro, Cm730Profile::kStock, tilted_imu());
  ASSERT_FALSE(nimbro_board.status.is_ok());
  EXPECT_NE(nimbro_board.status.message().find("--cm730 stock expects CM730 (29440)"),
            std::string::npos)
      << nimbro_board.status.message();
}

}  // namespace
}  // namespace stride::hal::dxl
