// Quintic: a fifth-order polynomial in time that starts and ends in given states (position,
// velocity, acceleration), the building block of the spline walk's foot and trunk trajectories
// (Bit-Bots' quintic walk and Rhoban's IKWalk build every trajectory this way,
// ../shared/research/spline-walk.md): a segment built from where a trajectory is now ends where
// the next step wants it, so position, velocity and acceleration stay continuous across every
// segment boundary, however early a step ends.
//
//   p(t) = c0 + c1 t + c2 t^2 + c3 t^3 + c4 t^4 + c5 t^5,  t in [0, T]
//   p(0) = p0, p'(0) = v0, p''(0) = a0,  p(T) = p1, p'(T) = v1, p''(T) = a1
//
// Before 0 and after T the segment holds its end states (position extrapolated at the end
// velocity would walk a foot through the floor). Units follow the caller (m or rad, s).
// Real-time: plain arithmetic, no allocation.
#pragma once

namespace stride::fw::walk {

/// Position, velocity and acceleration of one coordinate.
struct AxisState {
  double position = 0.0;
  double velocity = 0.0;
  double acceleration = 0.0;
};

class Quintic {
 public:
  Quintic() = default;
  /// A segment held at `p` (zero velocity and acceleration).
  static Quintic hold(double p) noexcept { return hold_state({p, 0.0, 0.0}); }
  /// The segment from `from` at t = 0 to `to` at t = duration [s]; a duration <= 0 jumps to `to`.
  static Quintic between(const AxisState& from, const AxisState& to, double duration) noexcept {
    if (!(duration > 0.0)) return hold_state(to);
    Quintic q;
    q.end_ = to;
    q.start_ = from;
    const double t = duration, t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
    const double p0 = from.position, v0 = from.velocity, a0 = from.acceleration;
    const double p1 = to.position, v1 = to.velocity, a1 = to.acceleration;
    q.duration_ = t;
    q.c_[0] = p0;
    q.c_[1] = v0;
    q.c_[2] = 0.5 * a0;
    q.c_[3] = (20.0 * (p1 - p0) - (8.0 * v1 + 12.0 * v0) * t - (3.0 * a0 - a1) * t2) / (2.0 * t3);
    q.c_[4] =
        (30.0 * (p0 - p1) + (14.0 * v1 + 16.0 * v0) * t + (3.0 * a0 - 2.0 * a1) * t2) / (2.0 * t4);
    q.c_[5] = (12.0 * (p1 - p0) - (6.0 * v1 + 6.0 * v0) * t - (a0 - a1) * t2) / (2.0 * t5);
    return q;
  }
  /// Rest to rest: from p0 to p1 with zero velocity and acceleration at both ends.
  static Quintic rest_to_rest(double p0, double p1, double duration) noexcept {
    return between({p0, 0.0, 0.0}, {p1, 0.0, 0.0}, duration);
  }

  double duration() const noexcept { return duration_; }
  const AxisState& end() const noexcept { return end_; }

  /// The state at time t [s] after the segment's start.
  AxisState at(double t) const noexcept {
    if (!(duration_ > 0.0) || t >= duration_) return end_;
    if (t <= 0.0) return start_;
    const auto& c = c_;
    const double p = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
    const double v = c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])));
    const double a = 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]));
    return {p, v, a};
  }
  double position(double t) const noexcept { return at(t).position; }

 private:
  static Quintic hold_state(const AxisState& s) noexcept {
    Quintic q;
    q.c_[0] = s.position;
    q.start_ = q.end_ = s;
    return q;
  }

  double c_[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double duration_ = 0.0;
  AxisState start_{}, end_{};
};

}  // namespace stride::fw::walk
