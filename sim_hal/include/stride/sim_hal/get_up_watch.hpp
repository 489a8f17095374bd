// Getting up in simulation, shared by `stride sim getup` / `--after-fall getup`, the push
// episode (script_episodes.hpp) and the optimiser's get-up task: where a get-up starts (lying
// still on the front or the back), how the firmware's motion manager goes through it, and when
// the robot counts as standing again.
//
// Standing (StandingCriterion, the same figures as stands_at_end): the motion manager is in
// Stand after a get-up script handed over to it, the trunk's z axis is within 25 deg of
// vertical and the torso origin is above 0.45 m (standing it is at about 0.58 m), all held
// for 1 s. The time of standing is the start of the first such second.
#pragma once

#include <optional>
#include <string>

#include "stride/firmware/controller.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

/// Lying still on the grass on the front (face down) or on the back, the joints in the Stand
/// pose: where a get-up starts. The motion manager sees the fall, waits until the robot lies
/// still (motion.fallen_still_time; at most motion.fallen_settle_time) and plays get_up_front
/// or get_up_back.
ResetSpec lying_reset_spec(bool on_front);

/// Follows the motion manager through a get-up (run_push_episode, `stride sim getup` and the
/// optimiser's getup task): call after every Controller::step.
class GetUpWatch {
 public:
  explicit GetUpWatch(double period_s) : period_s_(period_s) {}
  void after_step(const fw::Controller& controller, hal::Tick tick);
  int attempts() const { return attempts_; }
  /// The get-up script the motion manager chose first ("" if none).
  const std::string& first_script() const { return first_script_; }
  /// When a get-up last handed over to stand [s] (-1: never).
  double stand_again_s() const { return stand_again_s_; }
  /// Whether a get-up has handed over to stand since the last fall (false while fallen or
  /// getting up, and before any get-up).
  bool stood_after_get_up() const { return stood_after_get_up_; }

 private:
  double period_s_;
  fw::MotionState previous_ = fw::MotionState::kStand;
  int attempts_ = 0;
  std::string first_script_;
  double stand_again_s_ = -1.0;
  bool stood_after_get_up_ = false;
};

/// What counts as standing after a get-up (see the header comment).
struct StandingCriterion {
  double max_tilt_deg = 25.0;        ///< trunk z axis from vertical
  double min_torso_height_m = 0.45;  ///< torso origin above the solid ground
  double hold_s = 1.0;               ///< held this long, without a break
};

/// The trunk is upright by `criterion`: z axis within max_tilt_deg of vertical, origin above
/// min_torso_height_m.
bool trunk_upright(const SimWorld& world, const StandingCriterion& criterion = {});

/// The robot stands at the end: the trunk upright (StandingCriterion's defaults), the world
/// still running and the motion manager in kStand.
bool stands_at_end(const SimWorld& world, WorldStatus status, const fw::Controller& controller);

/// When the robot stood up after a fall: follows the motion manager (GetUpWatch) and the trunk
/// every tick, and keeps the start of the first interval of criterion.hold_s in which the robot
/// was standing. Call after every Controller::step with the world the sensors came from.
class StoodUpWatch {
 public:
  explicit StoodUpWatch(double period_s, StandingCriterion criterion = {});
  void after_step(const fw::Controller& controller, const SimWorld& world, hal::Tick tick);
  const GetUpWatch& get_up() const { return get_up_; }
  /// Episode time at which the robot was first standing, held for hold_s [s]; empty if not
  /// (yet).
  std::optional<double> stood_up_at_s() const { return stood_up_at_s_; }

 private:
  double period_s_;
  StandingCriterion criterion_;
  GetUpWatch get_up_;
  std::optional<hal::Tick> standing_since_;
  std::optional<double> stood_up_at_s_;
};

}  // namespace stride::sim
