// The get-up task (the seed's future work): the robot lies still on its front, then on its back
// (two episodes per world, sim::lying_reset_spec); the firmware's motion manager sees the fall,
// waits until the robot lies still (motion.fallen_still_time) and plays get_up_front or
// get_up_back (each a direct get-up, issue 43). The genes are those scripts' keyframes: targets
// and frame durations (script.get_up_*.frameK.*, make_configs.py).
//   Obj1 = time until standing [s], from lying still: when the last get-up handed over to stand
//          (sim::GetUpWatch); an episode that does not end standing counts duration_s + 10 s.
//   Obj2 = peak servo load [N m]: the largest |motor torque| of any servo over the episode's
//          physics steps (SimWorld::last_period_peaks, the torque the gear train carries).
//   c0   = -(episodes that do not end standing within duration_s) / episodes (g >= 0 feasible).
// Each value is the mean of the two episodes. An episode ends as soon as its outcome is decided
// (issue 42 point 4): once the robot has stood up by sim::StoodUpWatch's criterion (in Stand after
// a get-up, upright, held 1 s: the `stride sim getup` stood_up_s), and otherwise at duration_s.
// So Obj2 is the peak up to that moment, and a robot that stood up and fell again later would
// count as standing; standing still for 1 s after its get-up, none did in the runs.
// Why the motor torque (issue 43): pushing the body up a servo sits at its stall torque (MX-106
// about 8 N m), but where a limb takes the body's weight or an impact, the gear train is
// back-driven and carries two to three times that (18-26 N m across the first genomes of
// getup.json): that is the load that strips gears. The load register (the PWM duty) saturates at
// 100 % in every get-up and tells them apart poorly; the IMU's peak |a| (Obj2 before issue 43)
// stays in EpisodeScore::max_accel and the report.
// Its own figures (getup_figures.hpp): episodes stood, get-up attempts and the mean stand time,
// merged over the world's two episodes here.
#include <algorithm>
#include <cstdio>

#include "stride/optimiser/tasks/getup_figures.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/sim_hal/get_up_watch.hpp"

namespace stride::opt {

namespace {

/// Added to the time limit for an episode that does not end standing [s].
constexpr double kNotStandingPenaltyS = 10.0;

class GetUpEpisode final : public TaskEpisode {
 public:
  GetUpEpisode(const TaskConfig& config, double period_s) : config_(config), watch_(period_s) {}
  sim::EpisodeOptions options() const override {
    sim::EpisodeOptions o;
    o.duration_s = config_.duration_s;
    o.stop_on_fall = false;  // it starts lying
    o.stop_when = [this] { return watch_.stood_up_at_s().has_value(); };
    return o;
  }
  void before_step(const hal::SensorFrame&, hal::Tick, const sim::SimWorld&,
                   fw::Controller&) override {}
  void after_step(const fw::Controller& controller, const sim::SimWorld& world,
                  hal::Tick tick) override {
    watch_.after_step(controller, world, tick);
    peak_servo_torque_nm_ =
        std::max(peak_servo_torque_nm_, world.last_period_peaks().servo_torque_nm);
  }
  Status score(const sim::EpisodeResult& r, const sim::SimWorld& world,
               const fw::Controller& controller, EpisodeScore& out) override {
    const bool stood = sim::stands_at_end(world, r.status, controller);
    GetUpFigures& figures = out.figures.as<GetUpFigures>();
    figures.stood = stood ? 1 : 0;
    figures.get_up_attempts = watch_.get_up().attempts();
    figures.stand_time_s = stood ? std::max(0.0, watch_.get_up().stand_again_s()) : -1.0;
    out.fell = !stood;
    const double time = stood ? figures.stand_time_s : config_.duration_s + kNotStandingPenaltyS;
    out.objectives = {time, peak_servo_torque_nm_};
    out.constraints = {stood ? 0.0 : -1.0};
    return {};
  }

 private:
  const TaskConfig& config_;
  sim::StoodUpWatch watch_;
  double peak_servo_torque_nm_ = 0.0;  ///< Obj2, over the episode's physics steps [N m]
};

class GetUpTask final : public TaskType {
 public:
  GetUpTask()
      : TaskType({.name = "getup",
                  .constraint_count = 1,
                  .labels = {"time until standing [s]", "peak servo load [N m]"},
                  .legend = "f1 time until standing [s], f2 peak servo load [N m]",
                  .best_f1_pick = "quickest",
                  .best_f2_pick = "gentlest",
                  .words = {"stand up from the front and from the back",
                            "stands up from the front and from the back",
                            "does not stand up in time", "time until standing", "get-up",
                            "{} % slower than in the run", "stays down", " within the time limit"},
                  .episodes_per_world = 2,
                  // 2 ms: at 2.5 ms the front side stood up 3.5 % sooner on Simbody
                  // (tests/bench/RESULTS.md).
                  .trial_step_us_simbody = 2000,
                  .trial_step_us_mujoco = 2000,
                  .settings_fields = {}}) {}  // none of its own
  bool succeeded(const TaskConfig&, const EpisodeScore& score) const override {
    return score.figures.read<GetUpFigures>().stood == descriptor().episodes_per_world;
  }
  std::string outcome_note(const TaskConfig&, const EpisodeScore& s, double) const override {
    const GetUpFigures figures = s.figures.read<GetUpFigures>();
    char text[96];
    if (figures.stood == descriptor().episodes_per_world)
      std::snprintf(text, sizeof text, "stood up in %.2f s (mean of front and back)",
                    figures.stand_time_s);
    else
      std::snprintf(text, sizeof text, "stood up in %d of %d episodes", figures.stood,
                    descriptor().episodes_per_world);
    return text;
  }
  /// Over the world's episodes: the running mean of the stand time (-1 once one did not stand),
  /// the episodes stood and the attempts summed.
  void merge_figures(const TaskFigures& next_figures, int count,
                     TaskFigures& total_figures) const override {
    const GetUpFigures next = next_figures.read<GetUpFigures>();
    GetUpFigures& total = total_figures.as<GetUpFigures>();
    const double w = 1.0 / count;
    const bool all_stood = total.stand_time_s >= 0.0 && next.stand_time_s >= 0.0;
    total.stand_time_s =
        all_stood ? total.stand_time_s + (next.stand_time_s - total.stand_time_s) * w : -1.0;
    total.stood += next.stood;
    total.get_up_attempts += next.get_up_attempts;
  }
  sim::ResetSpec reset_spec(const TaskConfig&, int episode) const override {
    return sim::lying_reset_spec(episode == 0);
  }
  std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int, double period_s,
                                             const sim::SimWorld&) const override {
    return std::make_unique<GetUpEpisode>(config, period_s);
  }
};

}  // namespace

const TaskType& getup_task_type() {
  static const GetUpTask type;
  return type;
}

}  // namespace stride::opt
