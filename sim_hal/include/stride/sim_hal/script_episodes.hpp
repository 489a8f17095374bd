// Script episodes: the firmware (Controller with the script engine) playing a kick, or getting
// up after a scripted push, against the simulated robot. Used by `stride sim kick`, the
// integration tests and the optimiser's kick task.
//
// Kick (the seed's evaluator, igus.md 4.4 and 7.3): the robot starts standing with the ball in
// front of the kicking foot; at kick_at_s the kick script is requested (the motion manager
// starts it once the stand pose is reached); the episode ends at duration_s, or at a fall
// (EpisodeResult::fell: torso tilted more than 60 deg or its origin below 0.25 m).
// ball_distance_m is how far the ball moved in the field plane, max_fps the seed's "maximum
// field-plane sway" sqrt(ax^2 + ay^2) over the IMU samples.
//
// Push and get up: the robot starts standing and a ball thrown at its chest (0.26 kg at
// push_speed m/s, the scripted impulse) knocks it over, from behind (it falls on its front) or
// from the front (on its back). The motion manager detects the fall, plays get_up_front or
// get_up_back and returns to stand. got_up: the robot ends upright (torso z axis within
// 25 deg of vertical, torso origin above 0.45 m) in MotionState kStand (stands_at_end,
// get_up_watch.hpp, which also holds the lying start and the get-up watch).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <string>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/get_up_watch.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

/// The kick episode's start: standing in the Stand pose, the ball at `ball_position` (NaN z:
/// resting on the grass).
ResetSpec kick_reset_spec(const Eigen::Vector3d& ball_position);

/// Where a kick episode places the ball for `script`: before the right foot (0.25, -0.06, NaN
/// z: resting on the grass), mirrored before the left foot for kick_left. `stride sim kick` and
/// the optimiser's kick task both place it here.
Eigen::Vector3d kick_ball_position(const std::string& script);

/// Whether the firmware has a kick script of that name (the error names it).
Status check_kick_script(const fw::Firmware& firmware, const std::string& script);

/// The kick episode's requests, shared by run_kick_episode and the optimiser's kick task: the
/// script is requested once, at the first tick at or after kick_at_s (the motion manager starts
/// it once the stand pose is reached). Real-time: no allocation in before_step.
class KickRequest {
 public:
  KickRequest(std::string script, double kick_at_s, double period_s);
  void before_step(hal::Tick tick, fw::Controller& controller);
  const std::string& script() const { return script_; }

 private:
  std::string script_;
  hal::Tick kick_tick_ = 0;
  bool requested_ = false;
};

struct KickEpisodeOptions {
  std::string script = "kick_right";
  double kick_at_s = 1.0;   ///< when the kick is requested
  double duration_s = 8.0;  ///< episode length (the ball has stopped rolling by then)
  /// Ball centre; NaN z: resting on the grass. Default: in front of the right foot.
  Eigen::Vector3d ball_position{0.25, -0.06, std::nan("")};
  fw::FirmwareOptions firmware;  ///< scripts, parameter file (a genome)
  EpisodeOptions episode;        ///< recorder, snapshots (duration is set from duration_s)
};

/// Runs one kick. Fails (Status) only on a broken firmware configuration or world set-up, or
/// a kick script the firmware does not have. `robot_out`, if given, receives the simulated
/// robot after the episode (for pictures of its model).
Status run_kick_episode(const WorldOptions& world_options, const KickEpisodeOptions& options,
                        EpisodeResult& out, std::unique_ptr<SimRobot>* robot_out = nullptr);

struct PushEpisodeOptions {
  bool from_behind = true;   ///< true: falls on its front; false: on its back
  double push_speed = 12.0;  ///< ball speed at the chest [m/s]
  double duration_s = 15.0;  ///< time allowed to fall, lie still, get up and stand
  fw::FirmwareOptions firmware;
  EpisodeOptions episode;
};

struct PushEpisodeResult {
  EpisodeResult episode;  ///< fell = it was knocked over
  bool got_up = false;
  std::string get_up_script;    ///< the get-up script the motion manager chose first ("" if none)
  double final_upright = 0.0;   ///< world z of the torso z axis at the end (1 = upright)
  int get_up_attempts = 0;      ///< get-up scripts started
  double stand_again_s = -1.0;  ///< when a get-up last handed over to stand (-1: never)
};

Status run_push_episode(const WorldOptions& world_options, const PushEpisodeOptions& options,
                        PushEpisodeResult& out);

}  // namespace stride::sim
