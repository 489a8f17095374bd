// FallPredictor: sees a fall coming from the IMU, before the trunk hits the ground.
//
// Attitude: roll and pitch of the torso from a complementary filter, the gyro integrated each
// tick and pulled towards the accelerometer's gravity direction by fall.accel_weight
// (pitch > 0 leaning forward, roll > 0 leaning right; upright and still both are 0).
// Rule, per axis (the form of Bit-Bots' bitbots_hcm "Falling" decision, thresholds ours):
// the torso is falling when it rotates away from upright and
//   |angle| / fall.tilt_rad + |rate| / fall.rate_rad_s >= 1,
// so a fast rotation near upright or a slow one far from it both count; beyond fall.tilt_rad
// any rotation away from upright does. The prediction must hold for fall.confirm_ticks ticks.
// It is a fall forward/backward when the pitch term is the larger, else to a side.
// A prediction needs the torso to have been upright (|roll| and |pitch| below fall.upright_rad)
// since the last one: a robot lying on the ground, or getting up, is not about to fall.
// Thresholds: firmware/src/FALLING.md (measured: what the stand and the walk recover from,
// pushed with `stride sim stand|walk --push`, and 20 s of walking in each direction).
// Real-time: observe() does no I/O, reads no clock and allocates nothing.
#pragma once

#include <cstdint>

#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw {

enum class FallDirection : std::uint8_t { kNone, kForward, kBackward, kLeft, kRight };

const char* to_string(FallDirection direction);

class FallPredictor {
 public:
  /// Registers fall.tilt_rad, fall.rate_rad_s, fall.confirm_ticks, fall.accel_weight and
  /// fall.upright_rad.
  FallPredictor(ParameterStore& params, double period_s);

  /// Updates the attitude and the prediction from this tick's IMU. Real-time: yes.
  void observe(const hal::Cm730State& imu) noexcept;

  /// True while a fall is predicted (confirmed).
  bool falling() const noexcept { return falling_; }
  /// Direction of the predicted fall (kNone while not falling).
  FallDirection direction() const noexcept { return falling_ ? direction_ : FallDirection::kNone; }
  double roll_rad() const noexcept { return roll_; }
  double pitch_rad() const noexcept { return pitch_; }
  /// The larger of |roll| and |pitch| [rad].
  double tilt_rad() const noexcept;

 private:
  ParameterStore& params_;
  double period_s_;
  ParamHandle tilt_, rate_, confirm_ticks_, accel_weight_, upright_;
  double roll_ = 0.0, pitch_ = 0.0;
  bool initialised_ = false;
  bool falling_ = false;
  bool armed_ = false;  // upright since the last prediction
  FallDirection direction_ = FallDirection::kNone;
  std::uint32_t run_ = 0;
};

}  // namespace stride::fw
