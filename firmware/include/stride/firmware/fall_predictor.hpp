// FallPredictor: sees a fall coming from the IMU, before the trunk hits the ground.
//
// Attitude: roll and pitch of the torso from the firmware's one attitude estimate
// (attitude_estimator.hpp): roll = atan2(u_y, u_z), pitch = atan2(-u_x, u_z) of its up
// direction u (pitch > 0 leaning forward, roll > 0 leaning right; upright and still both are
// 0; lying down they reach +-pi/2 and beyond).
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

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw {

enum class FallDirection : std::uint8_t { kNone, kForward, kBackward, kLeft, kRight };

const char* to_string(FallDirection direction);

class FallPredictor {
 public:
  /// Registers fall.tilt_rad, fall.rate_rad_s, fall.confirm_ticks and fall.upright_rad.
  explicit FallPredictor(ParameterStore& params);

  /// Updates the prediction from this tick's attitude estimate (already updated with this
  /// tick's IMU). Real-time: yes.
  void observe(const AttitudeEstimator& attitude) noexcept;

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
  ParamHandle tilt_, rate_, confirm_ticks_, upright_;
  double roll_ = 0.0, pitch_ = 0.0;
  bool falling_ = false;
  bool armed_ = false;  // upright since the last prediction
  FallDirection direction_ = FallDirection::kNone;
  std::uint32_t run_ = 0;
};

}  // namespace stride::fw
