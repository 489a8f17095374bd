// Getting up in simulation: the lying start, the get-up watch and the standing criterion.
#include "stride/sim_hal/get_up_watch.hpp"

#include <cmath>
#include <numbers>

namespace stride::sim {

ResetSpec lying_reset_spec(bool on_front) {
  ResetSpec spec = ResetSpec::standing();
  spec.level_feet = false;
  // Face down: the torso's x axis (forward) points down, its z axis forward; face up the reverse.
  const double pitch = on_front ? std::numbers::pi / 2.0 : -std::numbers::pi / 2.0;
  spec.torso_orientation = Eigen::Quaterniond(Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()));
  spec.ball_position = {5.0, 5.0, std::nan("")};  // out of the way
  return spec;
}

void GetUpWatch::after_step(const fw::Controller& controller, hal::Tick tick) {
  const fw::MotionState state = controller.motion().state();
  if (state == fw::MotionState::kGetUp && previous_ != fw::MotionState::kGetUp) {
    ++attempts_;
    if (first_script_.empty()) first_script_ = std::string(controller.motion().active_script());
  }
  if (state == fw::MotionState::kStand && previous_ == fw::MotionState::kGetUp) {
    stand_again_s_ = static_cast<double>(tick) * period_s_;
    stood_after_get_up_ = true;
  }
  if (state == fw::MotionState::kFallen || state == fw::MotionState::kGetUp)
    stood_after_get_up_ = false;
  previous_ = state;
}

namespace {

bool upright(const Eigen::Isometry3d& torso, const StandingCriterion& criterion) {
  return torso.linear()(2, 2) > std::cos(criterion.max_tilt_deg * std::numbers::pi / 180.0) &&
         torso.translation().z() > criterion.min_torso_height_m;
}

}  // namespace

bool trunk_upright(const SimWorld& world, const StandingCriterion& criterion) {
  return upright(world.torso_pose(), criterion);
}

bool stands_at_end(const SimWorld& world, WorldStatus status, const fw::Controller& controller) {
  return status == WorldStatus::kRunning && upright(world.ground_truth().torso, {}) &&
         controller.motion().state() == fw::MotionState::kStand;
}

StoodUpWatch::StoodUpWatch(double period_s, StandingCriterion criterion)
    : period_s_(period_s), criterion_(criterion), get_up_(period_s) {}

void StoodUpWatch::after_step(const fw::Controller& controller, const SimWorld& world,
                              hal::Tick tick) {
  get_up_.after_step(controller, tick);
  if (stood_up_at_s_) return;
  const bool standing = get_up_.stood_after_get_up() && world.status() == WorldStatus::kRunning &&
                        trunk_upright(world, criterion_);
  if (!standing) {
    standing_since_.reset();
    return;
  }
  if (!standing_since_) standing_since_ = tick;
  const double held_s = static_cast<double>(tick - *standing_since_) * period_s_;
  if (held_s >= criterion_.hold_s - 1e-9)
    stood_up_at_s_ = static_cast<double>(*standing_since_) * period_s_;
}

}  // namespace stride::sim
