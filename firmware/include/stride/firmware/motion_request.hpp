// MotionRequest: what the outside world (console, optimiser task, behaviour) asks the motion
// manager to do. Fixed-size plain data so it crosses threads without allocation.
#pragma once

#include <array>
#include <cstddef>
#include <cstring>
#include <string_view>

namespace stride::fw {

struct MotionRequest {
  enum class Kind : unsigned char {
    kStand,   ///< stop whatever runs (walk stops at the end of its step) and stand
    kWalk,    ///< walk with the normalised velocity (vx, vy, vtheta), each in [-1, 1]
    kScript,  ///< play the named script from stand (a walk stops first)
  };
  Kind kind = Kind::kStand;
  double vx = 0.0;
  double vy = 0.0;
  double vtheta = 0.0;
  std::array<char, 32> script{};  ///< NUL-terminated script name for kScript

  static MotionRequest stand() { return {}; }
  static MotionRequest walk(double vx, double vy, double vtheta) {
    MotionRequest r;
    r.kind = Kind::kWalk;
    r.vx = vx;
    r.vy = vy;
    r.vtheta = vtheta;
    return r;
  }
  /// Names longer than 31 characters are truncated (and then not found).
  static MotionRequest play(std::string_view name) {
    MotionRequest r;
    r.kind = Kind::kScript;
    const std::size_t n = name.size() < r.script.size() - 1 ? name.size() : r.script.size() - 1;
    std::memcpy(r.script.data(), name.data(), n);
    return r;
  }
  std::string_view script_name() const { return std::string_view(script.data()); }
};

}  // namespace stride::fw
