// VirtualBusPhysics: how the emulated servos and the CM730's IMU of the virtual bus move.
//
// The virtual bus turns register writes into per-servo commands (URDF joint angles, SI units)
// and reads back the state to fill the present-value registers. FirstOrderPhysics is a simple
// kinematic model (below); the Simbody world of sim_hal implements the same interface so that
// the unmodified firmware can drive the simulated robot over a pseudo-terminal.
#pragma once

#include <array>
#include <cstddef>

#include "stride/hal/dynamixel/units.hpp"
#include "stride/hal/types.hpp"

namespace stride::hal::dxl {

/// What one servo has been told (converted from its registers).
struct PhysicsServoCommand {
  double goal_rad = 0.0;           ///< goal position, URDF joint angle [rad]
  double speed_limit_rad_s = 0.0;  ///< moving speed [rad/s]; 0 = the servo's full speed
  double p_gain = 32.0;            ///< P gain register (1.0 units, Kp = P/8)
  double torque_limit = 1.0;       ///< fraction of max torque [0, 1]
  bool torque_enabled = false;
};

struct PhysicsServoState {
  double position_rad = 0.0;
  double speed_rad_s = 0.0;
  double load = 0.0;  ///< signed fraction of max torque in the joint's sense
  double temperature_c = 35.0;
  double voltage_v = 15.0;
};

struct PhysicsImu {
  std::array<double, 3> accel_mps2{0.0, 0.0, units::kStandardGravity};  ///< torso frame
  std::array<double, 3> gyro_rad_s{0.0, 0.0, 0.0};
  std::array<double, 3> mag_gauss{0.0, 0.0, 0.0};  ///< served by a CM730 with a magnetometer
};

class VirtualBusPhysics {
 public:
  virtual ~VirtualBusPhysics() = default;
  /// Sets servo `index`'s command (index = Dynamixel ID - 1).
  virtual void set_command(std::size_t index, const PhysicsServoCommand& command) = 0;
  /// Advances the world by `dt_s` seconds.
  virtual void advance(double dt_s) = 0;
  virtual PhysicsServoState servo_state(std::size_t index) const = 0;
  virtual PhysicsImu imu() const = 0;
};

/// First-order servo model: with torque on, each joint approaches its goal as
///   dq/dt = clamp((goal - q) / tau, -v_max, v_max),   tau = tau_32 * 32 / P,
/// v_max = the moving speed, or the model's no-load speed (MX-64 78 rpm, MX-106 55 rpm at
/// 14.8 V) when the moving speed is 0. P = 0 or torque off: the joint stays where it is (no
/// gravity). Load is a quasi-static proxy (P/32) * (goal - q) / 0.5 rad, clamped to the torque
/// limit. Temperature rises with load^2 (1 K/s at full load) and relaxes to ambient with a
/// 300 s time constant. The IMU reads an upright, still torso: accel (0, 0, g), gyro 0.
class FirstOrderPhysics final : public VirtualBusPhysics {
 public:
  struct Options {
    std::array<ServoModelId, kServoCount> models{};
    std::array<double, kServoCount> initial_rad{};
    double tau_at_p32_s = 0.02;
    double ambient_c = 35.0;
    double supply_v = 15.0;
  };
  explicit FirstOrderPhysics(const Options& options);

  void set_command(std::size_t index, const PhysicsServoCommand& command) override;
  void advance(double dt_s) override;
  PhysicsServoState servo_state(std::size_t index) const override;
  PhysicsImu imu() const override { return {}; }

 private:
  Options options_;
  std::array<PhysicsServoCommand, kServoCount> commands_{};
  std::array<PhysicsServoState, kServoCount> states_{};
};

}  // namespace stride::hal::dxl
