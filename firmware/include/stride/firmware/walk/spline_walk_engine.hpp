// SplineWalkEngine: a phase-based omnidirectional walk in the lineage of Rhoban's IKWalk and
// Bit-Bots' quintic walk (../shared/research/spline-walk.md), beside the seed's ZMP walk and
// chosen by walk.engine (walk_selector.hpp). Parameters walk.spline.* (spline_walk_parameters.hpp);
// the equations, the tuning advice and the measured figures are in
// firmware/src/walk/SPLINE_WALK.md.
//
// Open-loop core. A walk is a sequence of steps of T = 1/(2 f) seconds; each starts with both
// feet down for double_support_ratio T, then the swing foot travels. At each step's start the
// engine plans the swing foot's landing pose (spline_footsteps.hpp) and builds quintic
// segments (quintic.hpp) from the states the trajectories have now:
//   - swing foot x, y, yaw: rest to rest over the swing (optionally past the target by
//     foot_overshoot and back); z: up to foot_rise at foot_apex_phase, down to -foot_put_down;
//   - hips (the midpoint of the hip roll/pitch crossings) x, y, yaw, pitch: from their present
//     position, velocity and acceleration to the end state of the nominal periodic motion, the
//     feet's midpoint plus trunk_x_offset, a lateral sway A sin(2 pi (phi - trunk_sway_phase))
//     towards the support foot (phi the cycle's phase, 0 when the left foot takes the weight),
//     moving at the walking velocity. So every trajectory is continuous in position, velocity
//     and acceleration, whenever a step ends.
// Each tick samples the segments, puts both ankles into the trunk frame (hips at trunk_height,
// pitched by trunk_pitch) and solves the exact leg IK.
//
// Closed loop (each part has its parameters under walk.spline.*; gains 0 switch it off):
//   - step end at touchdown (capture.touchdown_*): late in a step, a swing knee that carries
//     load ends the step now, and the next one starts from the measured moment;
//   - capture-point foot placement (capture.step_gain_x/y): the landing pose moves with the
//     capture point's deviation, within the collision rule;
//   - step timing (capture.timing_gain from the roll, timing_gain_pitch from the pitch): the
//     phase runs faster when the capture point leaves towards the swing side or along x;
//   - heading hold (balance.heading_*, the magnetometer where the CM730 has one): adds its
//     correction to each step's turn while no turn is commanded;
//   - gyro and tilt feedback on the support leg (balance.*) and the compliance feed-forward
//     (compliance.*), with the hips' planned acceleration folded into gravity.
//
// Start: blends from the last commands to the walk's stance on the feet where they stand over
// kStartBlendTime, then steps in place for start_steps steps while the sway and the foot rise
// ramp in. Stop: the speed ramps down at the acceleration limits, then one closing step puts
// the feet side by side; done() is then true. Parameters are latched at each step's start.
// Real-time: start() and step() do no I/O, read no clock, allocate nothing, throw nothing.
#pragma once

#include <array>
#include <cstdint>

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/motion_engine.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/robot_description.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/firmware/walk/balance_feedback.hpp"
#include "stride/firmware/walk/capture_step.hpp"
#include "stride/firmware/walk/compliance_compensation.hpp"
#include "stride/firmware/walk/heading_hold.hpp"
#include "stride/firmware/walk/leg_kinematics.hpp"
#include "stride/firmware/walk/spline_footsteps.hpp"
#include "stride/firmware/walk/spline_trajectories.hpp"
#include "stride/firmware/walk/walk_servos.hpp"

namespace stride::fw {

class SplineWalkEngine final : public WalkControl {
 public:
  enum class State : std::uint8_t { kStopped, kStarting, kWalking, kStopping, kLastStep };

  /// What the engine planned in the latest step() (tests, logs, the console).
  struct Snapshot {
    State state = State::kStopped;
    double phase = 0.0;  ///< phase within the current step [0, 1]
    int step_count = 0;  ///< steps begun since start()
    walk::Foot swing = walk::Foot::kRight;
    walk::Pose2 hips;  ///< hips' ground projection and yaw in the walk plane
    walk::Pose2 left_foot, right_foot;
    double left_lift = 0.0, right_lift = 0.0;  ///< ankle height above its standing height [m]
    walk::WalkVelocity velocity;               ///< the walk's velocity [m/s, rad/s]
    double phase_rate = 1.0;                   ///< the timing feedback's phase rate
    bool ik_clamped = false;                   ///< a leg target was out of reach this tick
  };

  /// Blend from the previous pose into the walk's stance at start() [s].
  static constexpr double kStartBlendTime = 1.0;

  /// Registers walk.spline.* in `store` (throws std::invalid_argument on a name clash,
  /// std::runtime_error if a servo is missing from `servos`). `robot` must outlive the engine;
  /// `attitude` (kept by reference) is the firmware's attitude estimate, which the controller
  /// updates with each tick's IMU before the engine steps.
  SplineWalkEngine(ParameterStore& store, const ServoTable& servos, std::int64_t period_ns,
                   const AttitudeEstimator& attitude,
                   const RobotDescription& robot = RobotDescription::defaults());

  std::string_view name() const noexcept override { return "walk"; }
  void start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
             hal::Tick tick) noexcept override;
  void step(const hal::SensorFrame& sensors, hal::Tick tick,
            hal::CommandFrame& out) noexcept override;
  bool done() const noexcept override { return state_ == State::kStopped; }
  void set_velocity(double vx, double vy, double vtheta) noexcept override;
  void request_stop() noexcept override;

  State state() const noexcept { return state_; }
  const Snapshot& snapshot() const noexcept { return snapshot_; }
  const walk::SplineWalkParameters& parameters() const noexcept { return params_; }
  /// Steps ended by a detected touchdown since construction.
  std::uint64_t touchdown_steps() const noexcept { return touchdown_steps_; }
  /// Ticks since construction in which a leg target had to be clamped.
  std::uint64_t ik_clamped_ticks() const noexcept { return ik_clamped_ticks_; }

 private:
  static constexpr std::size_t kDriven = walk::WalkServos::kDriven;

  void adopt_feet(const std::array<double, hal::kServoCount>& pose) noexcept;
  void begin_step() noexcept;
  void walk_tick(const hal::SensorFrame& sensors) noexcept;
  void compute_targets(const walk::StepSample& sample) noexcept;
  void solve_leg(const walk::LegKinematics& leg, const walk::FootSample& foot,
                 const walk::HipsSample& hips, double feedback,
                 const std::array<std::size_t, 6>& servo_index) noexcept;

  walk::SplineWalkParameterSet parameter_set_;
  walk::WalkServos servos_;
  walk::SplineWalkParameters params_;
  double period_s_;
  const AttitudeEstimator& attitude_;  // the firmware's, updated by the controller each tick
  walk::BalanceFeedback balance_;
  walk::BalanceShift balance_shift_;
  walk::HeadingHold heading_;
  walk::ComplianceCompensation compliance_;
  walk::CaptureStep capture_;
  walk::LegKinematics left_leg_{walk::LegSide::kLeft};
  walk::LegKinematics right_leg_{walk::LegSide::kRight};

  State state_ = State::kStopped;
  hal::Tick start_tick_ = 0;
  walk::PlanarVector command_;  // normalised
  walk::WalkVelocity velocity_;
  int step_count_ = 0;
  double time_in_step_ = 0.0;     // [s], advanced at the phase rate
  double landed_feedback_ = 1.0;  // the support leg's balance-feedback share when it landed
  walk::StepPlan plan_;           // this step's segments
  walk::StepSample sample_;       // this tick's sample of them
  walk::FootContact contact_;
  Eigen::Vector3d field_{0.0, 0.0, -9.81};  // g - planned hip acceleration, trunk frame

  std::array<double, hal::kServoCount> targets_{};
  std::array<double, kDriven> blend_from_{};
  bool tick_clamped_ = false;
  std::uint64_t ik_clamped_ticks_ = 0;
  std::uint64_t touchdown_steps_ = 0;
  Snapshot snapshot_;
};

}  // namespace stride::fw
