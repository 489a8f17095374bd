// MotionEngine: one source of joint targets (stand, walk, keyframe script) that the
// MotionManager switches between. Engines are pure: no I/O, no clock (time is the tick and the
// period given at construction), no heap allocation and no exceptions in start() or step().
#pragma once

#include <string_view>

#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/hal/types.hpp"

namespace stride::fw {

class MotionEngine {
 public:
  virtual ~MotionEngine() = default;

  /// Name for status output ("stand", "walk", "script").
  virtual std::string_view name() const noexcept = 0;

  /// Called when the manager switches to this engine at `tick`. `last_sent` holds the
  /// commands sent in the previous tick (the pose to start from), `sensors` the latest readings.
  virtual void start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
                     hal::Tick tick) noexcept = 0;

  /// Writes this tick's targets into `out`, which holds the previous tick's commands on entry
  /// (an engine may leave servos it does not drive untouched, e.g. the head).
  virtual void step(const hal::SensorFrame& sensors, hal::Tick tick,
                    hal::CommandFrame& out) noexcept = 0;

  /// True once the engine is at rest and the manager may switch away without a jump
  /// (stand settled, walk stopped with both feet down, script finished).
  virtual bool done() const noexcept = 0;
};

/// A walk engine as the MotionManager drives it (implemented in firmware/walk/).
class WalkControl : public MotionEngine {
 public:
  /// Normalised velocity command, each component in [-1, 1] (scaled by the walk's limits).
  virtual void set_velocity(double vx, double vy, double vtheta) noexcept = 0;
  /// Finish the current step, make the next one the last, and end with both feet down.
  virtual void request_stop() noexcept = 0;
};

/// A keyframe script player as the MotionManager drives it (implemented in firmware/script/).
class ScriptControl : public MotionEngine {
 public:
  /// Index of the loaded script called `name` ("kick_right", "get_up_front"), or -1.
  virtual int find(std::string_view name) const noexcept = 0;
  /// Selects the script to play from the next start(). Returns false for a bad index.
  virtual bool select(int script_index) noexcept = 0;
  /// Every frame duration of the next start() times `scale` (>= 1: slower; on top of the
  /// player's own modifier): the motion manager's slower get-up variant. 1 until changed.
  virtual void set_time_scale(double scale) noexcept = 0;
  /// True when the playing script ended early: a frame's wait timed out or its guard tripped
  /// (then done() is true too). False again at the next start().
  virtual bool aborted() const noexcept = 0;
};

}  // namespace stride::fw
