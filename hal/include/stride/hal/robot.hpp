// Robot: the hardware abstraction the firmware is written against, one control cycle in size.
//
// A cycle is:   sleep_until(k) -> read(sensors) -> [controller step] -> write(commands)
// The HAL owns time: tick k happens at t_k = k * period_ns(). On the robot sleep_until waits on
// CLOCK_MONOTONIC; in simulation it advances the physics to t_k in the calling thread, so
// lockstep is structural and cannot deadlock.
//
// Real-time rules (hold for every implementation, stated again on each method):
//  - called from the control thread only; never concurrently;
//  - no heap allocation, no exceptions, no unbounded blocking after start();
//  - a failure is reported in the frames (health, error flags) and in diagnostics(), never
//    by throwing or stopping the loop.
#pragma once

#include "stride/hal/command_frame.hpp"
#include "stride/hal/diagnostics.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/hal/types.hpp"

namespace stride::hal {

class Robot {
 public:
  virtual ~Robot() = default;

  /// Length of one tick [ns]. Constant for the lifetime of the object.
  /// Real-time: yes (pure getter).
  virtual std::int64_t period_ns() const noexcept = 0;

  /// Blocks until tick `tick` has come and returns the tick it actually woke at (>= tick).
  /// A return value greater than `tick` means the caller overran: the loop counts the
  /// difference as missed ticks and goes on from the returned tick (never catches up).
  /// Real-time: blocks at most until t_tick (plus OS latency); no allocation.
  virtual Tick sleep_until(Tick tick) noexcept = 0;

  /// Fills `out` with the readings of the current cycle (values, error flags, health).
  /// Devices that did not answer keep their last values and are marked kTimeout.
  /// Real-time: bounded by the bus budget of one cycle; no allocation; never throws.
  virtual void read(SensorFrame& out) noexcept = 0;

  /// Sends the targets of this cycle. Out-of-range values are the caller's bug but are
  /// clamped to what the hardware accepts, never rejected.
  /// Real-time: bounded by the bus budget of one cycle; no allocation; never throws.
  virtual void write(const CommandFrame& commands) noexcept = 0;

  /// Enables or disables torque on every servo at once (emergency stop, start-up, shutdown).
  /// Per-servo torque follows CommandFrame::servos[i].torque_enable otherwise.
  /// Real-time: one bus transaction at most; no allocation.
  virtual void set_torque_enable(bool enabled) noexcept = 0;

  /// Cumulative health and timing counters. The reference stays valid for the object's life.
  /// Real-time: yes (returns a reference to preallocated storage).
  virtual const Diagnostics& diagnostics() const noexcept = 0;
};

}  // namespace stride::hal
