// ScriptEngine: plays keyframe scripts the way the igus robot's Dynamixel servos did.
//
// Timing. start(tick t0) fixes every frame's deadline in ticks:
//   D_i = t0 + round(m * (d_1 + ... + d_i) [ms] / period),  strictly increasing (>= 1 tick each),
// where m is the duration modifier (parameter script.duration_modifier). Each servo has a
// queue of its targets in frame order; its *front* target is the first whose deadline has not
// passed (D_i > tick). There is no software interpolation:
//  - when a target becomes a servo's front target (at t0, or at the tick its predecessor's
//    deadline passes), its moving speed is fixed once, as the MX hardware did on receiving a
//    ServoTarget:  v = |theta_target - theta_present| / ((D_i - tick) * period)  [rad/s],
//    floored at kMinMovingSpeed (one MX speed unit, since 0 would mean "full speed");
//  - every tick sends the front target: goal = theta_target, moving speed v,
//    P = round(2.54 g) (capped at 254), I = D = 0, torque_limit = torque / 100,
//    torque_enable = torque > 0; the servo's own speed limit makes the move end at D_i;
//  - once a servo's last deadline has passed it holds its last target with moving speed 0
//    (full speed, Dynamixel semantics).
// The present position comes from the sensor frame (the last commanded goal if the servo did
// not answer). Servos the script never lists are left untouched (e.g. the head).
//
// Parameters. For every loaded script, every target position is a parameter
//   script.<name>.frame<k>.<servo>.position   (k = 1..N in file order; rad; default = the file's
// value; bounds = the servo table limits), so a genome can address frames 2..N-1 as the seed's
// kick genome does (see script_genome.hpp). Positions are read from the store at start(), so a
// playing script never changes half-way.
//
// Closing the loop (issue 54). A frame may carry a wait and a guard (script.hpp ScriptWait,
// ScriptGuard), read from the trunk's pitch and pitch rate of the firmware's attitude estimate
// (attitude_estimator.hpp):
//  - wait: when the frame's deadline D_i arrives and the pitch is outside [pitch_min,
//    pitch_max] or |gyro y| > rate_max, the frame is held (its servos keep their targets) and
//    D_i, D_i+1, ... move back one tick per tick held; once the condition holds the next frame
//    starts. Held timeout_ms without it: the script aborts.
//  - guard: while the frame plays (from the previous deadline to its own, a wait included) the
//    pitch outside [pitch_min, pitch_max] aborts the script.
// An aborted script is done() and aborted(); its servos keep the last commands until the
// motion manager takes over (a get-up: the soft hold of kFallen). Their values are parameters
// too, script.<name>.frame<k>.wait.{pitch_min, pitch_max, rate_max, timeout_ms} and
// .guard.{pitch_min, pitch_max} [rad, rad/s, ms], read at start(). Without an attitude
// estimate (a player made without one, as some tests are) waits and guards are not evaluated:
// the script plays as timed.
//
// Real-time: start(), step(), done(), find(), select() do not allocate, throw, read a clock or
// do I/O. Loading (add_script, load_folder) allocates and must happen before the loop runs.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <string_view>
#include <vector>

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/motion_engine.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/script/script.hpp"
#include "stride/firmware/servo_table.hpp"

namespace stride::fw {

class ScriptEngine final : public ScriptControl {
 public:
  /// Smallest non-zero moving speed sent [rad/s]: one MX speed register unit (igus.md 6.4).
  static constexpr double kMinMovingSpeed = 117.07 * 2.0 * std::numbers::pi / (1023.0 * 60.0);

  /// Registers script.duration_modifier in `params` (which must outlive the engine).
  /// `period_ns` is the loop period. Throws std::invalid_argument if period_ns <= 0 or the
  /// parameter already exists.
  ScriptEngine(std::int64_t period_ns, ParameterStore& params,
               const ServoTable& servos = ServoTable::defaults(),
               const AttitudeEstimator* attitude = nullptr);

  /// Adds a validated script and registers its position parameters. Fails (changing nothing)
  /// on a duplicate script name or a parameter name already in the store.
  Status add_script(Script script);
  /// load_script_folder + add_script for each script; all or nothing.
  Status load_folder(const std::filesystem::path& folder);

  std::size_t script_count() const noexcept { return scripts_.size(); }
  const Script& script(std::size_t index) const { return scripts_.at(index).script; }
  /// Parameter handle of the position of `target` in `frame` (0-based) of script `index`.
  ParamHandle position_handle(std::size_t index, std::size_t frame, std::size_t target) const;

  // --- ScriptControl ----------------------------------------------------------------------
  std::string_view name() const noexcept override { return "script"; }
  int find(std::string_view script_name) const noexcept override;
  bool select(int script_index) noexcept override;
  /// Starts the selected script at `tick` (does nothing and stays done() if none is selected).
  void start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
             hal::Tick tick) noexcept override;
  void step(const hal::SensorFrame& sensors, hal::Tick tick,
            hal::CommandFrame& out) noexcept override;
  /// True when no script is playing, the last step() was at or after the final deadline, or
  /// the script aborted.
  bool done() const noexcept override;
  void set_time_scale(double scale) noexcept override { time_scale_ = scale; }
  bool aborted() const noexcept override { return aborted_; }

  // --- inspection (tests, status output) ----------------------------------------------------
  int selected() const noexcept { return selected_; }
  int playing() const noexcept { return playing_; }
  /// Deadline tick of frame `frame` (0-based) of the playing script.
  hal::Tick deadline(std::size_t frame) const noexcept { return deadlines_[frame]; }
  /// The tick at which the playing script ends (its last deadline).
  hal::Tick end_tick() const noexcept;

 private:
  struct LoadedScript {
    Script script;
    std::vector<std::vector<ParamHandle>> handles;  ///< [frame][target]
    std::vector<ParamHandle> durations;             ///< [frame], in ms
    /// [frame]: wait pitch_min, pitch_max, rate_max, timeout_ms; guard pitch_min, pitch_max
    /// (handles of the frames that have them).
    std::vector<std::array<ParamHandle, 6>> checks;
    /// For each servo: (frame, target) indices of its targets in frame order.
    std::array<std::vector<std::pair<std::uint16_t, std::uint16_t>>, hal::kServoCount> queues;
  };

  struct ServoPlayback {
    std::size_t cursor = 0;            ///< index into the servo's queue of the front target
    std::size_t activated = SIZE_MAX;  ///< queue index whose speed has been fixed
    double speed_rad_s = 0.0;          ///< moving speed of the front target
  };

  /// A frame's wait and guard as read at start().
  struct FrameCheck {
    bool wait = false, guard = false;
    double wait_min = 0.0, wait_max = 0.0, rate_max = 0.0;
    hal::Tick timeout_ticks = 0;
    double guard_min = 0.0, guard_max = 0.0;
  };
  /// Moves frame_ past the deadlines reached at `tick`, holding a frame whose wait is not met
  /// and aborting on a timed-out wait or a tripped guard.
  void advance_frames(hal::Tick tick) noexcept;

  std::int64_t period_ns_;
  ParameterStore& params_;
  const ServoTable& servos_;
  const AttitudeEstimator* attitude_;
  ParamHandle duration_modifier_;
  std::vector<LoadedScript> scripts_;
  int selected_ = -1;
  int playing_ = -1;
  hal::Tick last_step_tick_ = 0;
  bool stepped_ = false;
  // Playback buffers (fixed size: scripts have at most kMaxScriptFrames frames).
  std::array<hal::Tick, kMaxScriptFrames> deadlines_{};
  /// Target positions [frame][servo] of the playing script, read from the store at start().
  std::array<std::array<double, hal::kServoCount>, kMaxScriptFrames> positions_{};
  std::array<ServoPlayback, hal::kServoCount> playback_{};
  std::array<FrameCheck, kMaxScriptFrames> checks_{};
  std::size_t frame_ = 0;     ///< the frame playing (or held by its wait)
  bool waiting_ = false;      ///< frame_'s deadline passed, its wait not yet met
  hal::Tick wait_start_ = 0;  ///< the tick frame_'s wait began
  bool aborted_ = false;
  double time_scale_ = 1.0;
};

}  // namespace stride::fw
