// WalkEngine: the seed's ZMP walk (NUbots OldWalkEngine, a port of the UPenn 2013 DARwIn walk;
// igus.md 2) driving the igus legs through exact leg IK, closed by the balance feedback below
// (on by default; with its gains at 0 it is the seed's open-loop walk). firmware/src/walk/README.md
// has the equations, parameter names and the departures from NUbots.
//
// Per tick: phase phi = (t - t_step_begin)/T; at phi >= 1 a new step is planned (velocity
// update, swing-leg swap, footstep, torso destination, LIPM coefficients). The torso follows
// the closed-form LIPM per axis, the swing foot the skewed cosine profile; feet and torso are
// turned into trunk-frame foot targets and solved with LegKinematics; arms swing between their
// start and end poses. Outputs are URDF joint angles for the 18 arm and leg servos, P gains
// round(2.54 g), moving speed 0 (full speed), torque limit 1; the head is left untouched.
//
// Frames: the walk plane holds 2-D poses of the ankles (projected to the ground) and of the
// torso reference point, a point fixed in the trunk 0.18 m above the hip roll/pitch axes
// (NUbots' chest-to-origin 0.135 + hip offset 0.045), at height walk.stance.body_height and
// pitched by walk.stance.body_tilt. The ankles sit 0.0565 m above the ground (tips of the studs).
//
// Start: the feet stay where the last commands put them (forward kinematics); start() blends
// from the last commands to the walk's standing pose on those feet over 1 s, then
// walks; the first two steps have zero velocity and no lift. request_stop() makes the next
// step the last (the swing foot lands beside the support foot); then the engine stands still
// (phase 0.5, both feet down) and done() is true. Parameters are latched at each step start.
// Gyro feedback (walk.balance.*, not in the genome; gains 0 = open loop) shifts the support leg's
// ankle and hip joints (balance_feedback.hpp); the heading hold (walk.balance.heading_*,
// heading_hold.hpp) adds the integrated gyro yaw, fed back, to each step's turn while no turn is
// commanded. Pure: no I/O, no clock, no allocation and no
// exceptions in start()/step().
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
#include "stride/firmware/walk/footstep_planner.hpp"
#include "stride/firmware/walk/heading_hold.hpp"
#include "stride/firmware/walk/leg_kinematics.hpp"
#include "stride/firmware/walk/lipm_trajectory.hpp"
#include "stride/firmware/walk/pose2.hpp"
#include "stride/firmware/walk/walk_parameters.hpp"
#include "stride/firmware/walk/walk_servos.hpp"

namespace stride::fw {

class WalkEngine final : public WalkControl {
 public:
  enum class State : std::uint8_t { kStopped, kStarting, kWalking, kStopRequest, kLastStep };

  /// What the engine planned in the latest step() (for tests, logging and the console).
  struct Snapshot {
    State state = State::kStopped;
    double phase = 0.5;  ///< step phase phi in [0, 1)
    int step_count = 0;  ///< steps planned since start()
    walk::Foot swing = walk::Foot::kRight;
    walk::Pose2 torso;  ///< torso reference point in the walk plane
    walk::Pose2 left_foot, right_foot;
    double left_lift = 0.0, right_lift = 0.0;  ///< ankle lift above its stance height [m]
    walk::Pose2 support_point;                 ///< ZMP target of the single-support phase
    walk::PlanarVector velocity;               ///< current velocity [m/step, rad/step]
    double heading_correction = 0.0;  ///< turn the heading hold added to this step [rad/step]
    double heading_error = 0.0;       ///< the heading hold's integrated yaw error [rad]
    double capture_x = 0.0, capture_y = 0.0;  ///< capture-point deviation, torso frame [m]
    double phase_rate = 1.0;                  ///< phase rate of the step timing feedback
    bool ik_clamped = false;                  ///< a leg target was out of reach this tick
  };

  /// Blend time from the previous pose into the walk's stance at start() [s].
  static constexpr double kStartBlendTime = 1.0;
  /// Height of the torso reference point above the hip roll/pitch crossing [m].
  static constexpr double kTorsoAboveHip = 0.18;
  /// Steps after start with zero velocity and no lift.
  static constexpr int kStepsWithoutLift = 2;

  /// Registers the walk.* parameters in `store` (throws std::invalid_argument on a name
  /// clash, std::runtime_error if a servo name is missing from `servos`). `robot` (kept by
  /// reference: it must outlive the engine) is the rigid-body model of the compliance
  /// compensation; `attitude` (kept by reference) the firmware's attitude estimate, which the
  /// controller updates with each tick's IMU before the engine steps.
  WalkEngine(ParameterStore& store, const ServoTable& servos, std::int64_t period_ns,
             const AttitudeEstimator& attitude,
             const RobotDescription& robot = RobotDescription::defaults());

  std::string_view name() const noexcept override { return "walk"; }
  void start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
             hal::Tick tick) noexcept override;
  void step(const hal::SensorFrame& sensors, hal::Tick tick,
            hal::CommandFrame& out) noexcept override;
  bool done() const noexcept override;
  void set_velocity(double vx, double vy, double vtheta) noexcept override;
  void request_stop() noexcept override;

  State state() const noexcept { return state_; }
  const Snapshot& snapshot() const noexcept { return snapshot_; }
  /// Ticks since construction in which a leg target had to be clamped.
  std::uint64_t ik_clamped_ticks() const noexcept { return ik_clamped_ticks_; }
  /// Steps since construction that ended at a detected touchdown (walk.capture.touchdown_load).
  std::uint64_t touchdown_steps() const noexcept { return touchdown_steps_; }
  /// The parameters latched for the current step.
  const walk::WalkParameters& parameters() const noexcept { return params_; }
  /// The capture-step feedback (its latest capture-point deviation).
  const walk::CaptureStep& capture() const noexcept { return capture_; }
  /// The compliance compensation (its last torques and offsets).
  const walk::ComplianceCompensation& compliance() const noexcept { return compliance_; }

 private:
  static constexpr std::size_t kDriven = walk::WalkServos::kDriven;

  void reset_stance() noexcept;
  void adopt_stance(const std::array<double, hal::kServoCount>& pose) noexcept;
  void begin_step() noexcept;
  void compute_targets(double time_in_step, bool standing) noexcept;
  void solve_leg(const walk::LegKinematics& leg, const walk::Pose2& foot, double lift,
                 const walk::Pose2& torso, double hip_roll_offset, double feedback,
                 const std::array<std::size_t, 6>& servo_index) noexcept;
  void write_arms(double phase, const walk::Pose2& torso, const walk::Pose2& left_foot,
                  const walk::Pose2& right_foot) noexcept;

  walk::WalkParameterSet parameter_set_;
  walk::WalkServos servos_;
  walk::WalkParameters params_;
  double period_s_;
  const AttitudeEstimator& attitude_;  // the firmware's, updated by the controller each tick
  walk::BalanceFeedback balance_;
  walk::BalanceShift balance_shift_;
  walk::HeadingHold heading_;
  walk::ComplianceCompensation compliance_;
  walk::CaptureStep capture_;
  walk::FootContact contact_;               // feet planned on the ground this tick
  Eigen::Vector3d field_{0.0, 0.0, -9.81};  // g - planned trunk acceleration, trunk frame
  double heading_correction_ = 0.0;         // added to the current step's turn [rad/step]
  walk::LegKinematics left_leg_{walk::LegSide::kLeft};
  walk::LegKinematics right_leg_{walk::LegSide::kRight};

  State state_ = State::kStopped;
  bool stop_requested_ = false;
  hal::Tick start_tick_ = 0;
  double step_begin_s_ = 0.0;  // walking time at which the current step began
  int step_count_ = 0;
  walk::Foot swing_ = walk::Foot::kRight;
  walk::Pose2 left_source_, left_destination_, right_source_, right_destination_;
  walk::Pose2 torso_source_, torso_destination_, support_;
  walk::LipmAxis lipm_x_, lipm_y_;
  walk::PlanarVector command_;   // normalised
  walk::PlanarVector velocity_;  // m/step, rad/step

  std::array<double, hal::kServoCount> targets_{};  // this tick's joint targets
  std::array<double, kDriven> blend_from_{};
  bool tick_clamped_ = false;
  std::uint64_t ik_clamped_ticks_ = 0;
  std::uint64_t touchdown_steps_ = 0;
  Snapshot snapshot_;
};

}  // namespace stride::fw
