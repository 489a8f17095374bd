// TrajectoryRecorder: a simulated episode as JSON lines, one object per control tick.
//
// Format (one line per recorded tick; all SI units, world frame x forward, y left, z up):
//   {"tick":12,"t":0.12,
//    "torso":{"p":[x,y,z],"q":[w,x,y,z],"v":[vx,vy,vz],"w":[wx,wy,wz]},
//    "com":[x,y,z],
//    "joints":[20 present angles, servo order (Dynamixel ID 1..20), URDF angles, rad],
//    "goals":[20 goal angles, rad],
//    "imu":{"acc":[ax,ay,az],"gyro":[gx,gy,gz]} (+ "mag":[mx,my,mz] [gauss] with a magnetometer),
//    "contacts":{"left":{"points":n,"force":[fx,fy,fz]},"right":{...},"other":n},
//    "ball":{"p":[x,y,z],"v":[vx,vy,vz]}}
// The first line is a header: {"format":"stride-trajectory","version":1,"joints":[names],
// "period_s":0.01}. The file is written atomically by save().
#pragma once

#include <filesystem>
#include <string>

#include "stride/core/status.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

class TrajectoryRecorder {
 public:
  explicit TrajectoryRecorder(int every_n_ticks = 1)
      : every_(every_n_ticks < 1 ? 1 : every_n_ticks) {}
  /// Appends tick `tick` (skipped unless tick % every_n_ticks == 0).
  void record(hal::Tick tick, const SimWorld& world, const hal::SensorFrame& sensors,
              const hal::CommandFrame& commands);
  std::size_t lines() const { return lines_; }
  const std::string& text() const { return text_; }
  Status save(const std::filesystem::path& path) const;

 private:
  int every_;
  std::size_t lines_ = 0;
  std::string text_;
};

}  // namespace stride::sim
