// MotionManager: decides which motion engine drives the servos, and switches between them
// without jumps.
//
// States and transitions:
//   kStand   -> kWalk     on a walk request once the stand pose is reached
//   kWalk    -> kStand    on a stand request: the walk finishes its step, stops, then stand
//   kWalk    -> kWalk     a walk request while the walk is stopping: once stopped it starts again
//   kStand   -> kScript   on a script request once the stand pose is reached; a script request
//                         while walking first stops the walk (kWalk -> kStand -> kScript)
//   kScript  -> kStand    when the script has finished, or at once on a stand request (the
//                         console's `stop`: the stand engine ramps from the pose reached)
//   kStand, kWalk, kScript -> kFalling  when the safety layer predicts a fall (FallPredictor)
//                         and fall.protect is on: FallProtection's pose, soft and torque-limited
//   kFalling -> kStand    when the prediction has cleared for fall.hold_time_s without a fall
//   any      -> kFallen   when the safety layer reports a fall (not during a get-up)
//   kFallen  -> kGetUp    once the robot lies still (every gyro axis below
//                         motion.fallen_still_rate for motion.fallen_still_time) or at the
//                         latest after motion.fallen_settle_time, with get_up_front (lying on
//                         the front: torso x axis down, accel x < 0) or get_up_back (accel x >
//                         0); lying on a side (|accel y| > |accel x|) and still rocking it waits
//                         up to twice the settle time, then plays the script of the side the
//                         torso leans to
//   kGetUp   -> kStand    when the get-up script has finished and the robot is upright,
//                         otherwise back to kFallen and try again; a get-up whose wait timed
//                         out or whose guard tripped (ScriptControl::aborted) goes to kFallen
//                         at once: the soft hold below, not the rest of the rise
// Each attempt differs from the failed one before it (issue 54): after a failed get_up_back the
// robot rolls onto its front (script roll_to_front, if loaded and motion.get_up_roll is on) and
// gets up from there; lying on the front after an odd number of failed attempts it plays
// get_up_front_retry (if loaded and motion.get_up_retry is on: a quicker push-up at a higher
// servo load), after an even number get_up_front again; from the
// motion.get_up_slow_after-th failed attempt on, the other get-ups play
// motion.get_up_slow_scale times slower (the waits of their frames hold as long as before).
// Without a walk or script engine the corresponding requests are refused (counted).
// While fallen the servos are held soft (motion.fallen_gain) at their measured positions; after
// a protected fall that went past fall.relax_tilt_rad they are first off (relaxed) for
// fall.relax_time_s, through the impact.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "stride/firmware/fall_protection.hpp"
#include "stride/firmware/motion_engine.hpp"
#include "stride/firmware/motion_request.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/stand_engine.hpp"

namespace stride::fw {

enum class MotionState : std::uint8_t { kStand, kWalk, kScript, kFallen, kGetUp, kFalling };

/// What the safety layer says about falls this tick.
struct FallSignal {
  bool fallen = false;   ///< the fall has happened (SafetyLayer::fallen)
  bool falling = false;  ///< a fall is predicted (SafetyLayer::falling)
  FallDirection direction = FallDirection::kNone;
  double tilt_rad = 0.0;  ///< the predictor's attitude (FallPredictor::tilt_rad)
};

std::string_view to_string(MotionState state);

class MotionManager {
 public:
  /// `walk` and `script` may be null (that motion is then unavailable). Engines must outlive
  /// the manager.
  MotionManager(ParameterStore& params, double period_s, WalkControl* walk, ScriptControl* script);

  /// Takes a request; it is acted on in the next step(). Real-time: yes.
  void request(const MotionRequest& request) noexcept;

  /// Runs the active engine for this tick, writing targets into `out` (which holds the
  /// previous tick's commands). `fallen` comes from the safety layer. Real-time: yes.
  void step(const hal::SensorFrame& sensors, hal::Tick tick, const FallSignal& fall,
            hal::CommandFrame& out) noexcept;
  /// The same without a fall prediction (`fallen` alone).
  void step(const hal::SensorFrame& sensors, hal::Tick tick, bool fallen,
            hal::CommandFrame& out) noexcept {
    step(sensors, tick, FallSignal{fallen, false, FallDirection::kNone}, out);
  }

  MotionState state() const noexcept { return state_; }
  /// Requests refused because the engine or script was not available.
  std::uint32_t refused_requests() const noexcept { return refused_; }
  /// Name of the script playing (kScript/kGetUp), or "".
  std::string_view active_script() const noexcept { return active_script_name_.data(); }
  StandEngine& stand() noexcept { return stand_; }

 private:
  void take_request() noexcept;
  void note_fall(const FallSignal& fall, hal::Tick tick) noexcept;
  void step_fallen(const hal::SensorFrame& sensors, hal::Tick tick, bool fallen,
                   const hal::CommandFrame& last, hal::CommandFrame& out) noexcept;
  void enter(MotionState state, MotionEngine& engine, const hal::SensorFrame& sensors,
             const hal::CommandFrame& last, hal::Tick tick) noexcept;
  bool start_script(int index, std::string_view name, const hal::SensorFrame& sensors,
                    const hal::CommandFrame& last, hal::Tick tick) noexcept;
  void hold_soft(const hal::SensorFrame& sensors, hal::CommandFrame& out) noexcept;

  ParameterStore& params_;
  double period_s_;
  StandEngine stand_;
  FallProtection protection_;
  WalkControl* walk_;
  ScriptControl* script_;
  ParamHandle fallen_settle_time_, fallen_still_time_, fallen_still_rate_, fallen_gain_,
      get_up_enabled_, get_up_roll_, get_up_retry_, get_up_slow_after_, get_up_slow_scale_;

  MotionState state_ = MotionState::kStand;
  bool started_ = false;
  bool have_request_ = false;
  MotionRequest pending_{};
  bool want_walk_ = false;
  double walk_vx_ = 0.0, walk_vy_ = 0.0, walk_vtheta_ = 0.0;
  int want_script_ = -1;  // script index to play once standing, -1 for none, -2 stop the script
  hal::Tick fallen_since_ = 0;
  hal::Tick moving_since_fall_ = 0;    // last tick a gyro axis was at or above fallen_still_rate
  hal::Tick falling_clear_since_ = 0;  // last tick the fall was still predicted (kFalling)
  FallDirection falling_direction_ = FallDirection::kNone;
  bool relaxed_ = false;  // torque off: past fall.relax_tilt_rad, until fall.relax_time_s lying
  std::uint32_t refused_ = 0;
  // Script names the manager itself plays; resolved once at construction.
  int get_up_front_ = -1;
  int get_up_back_ = -1;
  int roll_to_front_ = -1;
  int get_up_front_retry_ = -1;
  int playing_get_up_ = -1;           // the script of the kGetUp in progress
  int failed_get_ups_ = 0;            // failed get-up attempts since the robot fell
  bool back_attempt_failed_ = false;  // the last attempt was get_up_back and failed
  std::array<char, 32> want_script_name_{};
  std::array<char, 32> active_script_name_{};
};

}  // namespace stride::fw
