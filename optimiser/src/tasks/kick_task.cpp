// The kick task (the seed's kick evaluator, igus.md 4.4 and 7.3): the script episode of
// `stride sim kick` (sim::KickRequest: standing, the ball before the kicking foot, the right or
// for kick_left the left, sim::kick_ball_position; the script requested at kick_at_s), scored as
// the seed does:
//   Obj1 = max field-plane sway sqrt(ax^2 + ay^2) [m/s^2] (1000 if fell),
//   Obj2 = 1 / ball distance, distance clamped to [0.001, 10] m (1000 if fell).
//   c0 = fell ? -10 : 0; c1 = -(|integral of gyro z| - limit) when over the limit.
// Its own settings (kick_settings.hpp): script, kick_at_s, yaw_drift_limit_rad; its own figures
// (kick_figures.hpp): the ball distance and the sway.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "stride/optimiser/tasks/kick_figures.hpp"
#include "stride/optimiser/tasks/kick_settings.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/sim_hal/script_episodes.hpp"

namespace stride::opt {

namespace {

constexpr double kFallPenalty = 1000.0;
/// The episode's goal distance (EpisodeResult::time_to_goal_s only; the kick has no goal): the
/// walk's default, which the kick's episodes have always had.
constexpr double kKickGoalDistanceM = 2.5;
/// A validation kick succeeds when the ball moves at least this far [m].
constexpr double kKickSuccessDistanceM = 0.5;

class KickEpisode final : public TaskEpisode {
 public:
  KickEpisode(const TaskConfig& config, double period_s)
      : config_(config),
        kick_settings_(config.own_settings<KickSettings>()),
        period_s_(period_s),
        kick_(kick_settings_.script, kick_settings_.kick_at_s, period_s) {}
  sim::EpisodeOptions options() const override {
    sim::EpisodeOptions o;
    o.duration_s = config_.duration_s;
    o.goal_distance_m = kKickGoalDistanceM;
    o.stop_on_fall = true;
    return o;
  }
  void before_step(const hal::SensorFrame& sensors, hal::Tick tick, const sim::SimWorld&,
                   fw::Controller& controller) override {
    kick_.before_step(tick, controller);
    if (static_cast<double>(tick) * period_s_ > 0.25)
      yaw_integral_ += sensors.cm730.gyro_rad_s[2] * period_s_;
  }
  Status score(const sim::EpisodeResult& r, const sim::SimWorld&, const fw::Controller& controller,
               EpisodeScore& out) override {
    if (controller.motion().refused_requests() > 0)
      return Status::error("kick script '" + kick_settings_.script + "' refused");
    KickFigures& figures = out.figures.as<KickFigures>();
    figures.ball_distance_m = r.ball_distance_m;
    figures.max_fps = r.max_fps;
    const double d = std::clamp(r.ball_distance_m, 0.001, 10.0);
    double sway = r.max_fps;
    if (r.fell || sway <= 0.0 || sway > kFallPenalty) sway = kFallPenalty;
    out.objectives = {sway, r.fell ? kFallPenalty : 1.0 / d};
    const double yaw = std::abs(yaw_integral_);
    const double limit = kick_settings_.yaw_drift_limit_rad;
    out.constraints = {r.fell ? -10.0 : 0.0, yaw > limit ? -(yaw - limit) : 0.0};
    return {};
  }

 private:
  const TaskConfig& config_;
  const KickSettings& kick_settings_;
  double period_s_;
  sim::KickRequest kick_;
  double yaw_integral_ = 0.0;
};

class KickTask final : public TaskType {
 public:
  KickTask()
      : TaskType({.name = "kick",
                  .constraint_count = 2,
                  .labels = {"max field-plane sway [m/s^2]", "1 / ball distance [1/m]"},
                  .legend = "f1 max sway [m/s^2], f2 1/ball distance [1/m]",
                  .best_f1_pick = "least_sway",
                  .best_f2_pick = "longest_kick",
                  .words = {"kick the ball at least 0.5 m", "kicks the ball at least 0.5 m",
                            "kicks the ball less than 0.5 m", "1 / ball distance", "kick",
                            "its median 1 / ball distance is {} % worse than in the run"},
                  .gate_objective = 1,
                  .uses_ball = true,
                  .settings_fields = {"script", "kick_at_s", "yaw_drift_limit_rad"}}) {}
  bool succeeded(const TaskConfig&, const EpisodeScore& score) const override {
    return score.figures.read<KickFigures>().ball_distance_m >= kKickSuccessDistanceM;
  }
  std::string outcome_note(const TaskConfig& config, const EpisodeScore& s,
                           double end_s) const override {
    if (s.fell) return TaskType::outcome_note(config, s, end_s);
    char text[64];
    std::snprintf(text, sizeof text, "ball kicked %.2f m",
                  s.figures.read<KickFigures>().ball_distance_m);
    return text;
  }
  /// The first episode's ball distance, the largest sway (one episode per world as it is).
  void merge_figures(const TaskFigures& next, int, TaskFigures& total) const override {
    if (const KickFigures* n = next.find<KickFigures>())
      total.as<KickFigures>().max_fps = std::max(total.as<KickFigures>().max_fps, n->max_fps);
  }
  sim::ResetSpec reset_spec(const TaskConfig& config, int) const override {
    // Before the kicking foot: the right, or the left for kick_left (as `stride sim kick`).
    return sim::kick_reset_spec(
        sim::kick_ball_position(config.own_settings<KickSettings>().script));
  }
  Status parse_settings(const nlohmann::json& doc, const TaskConfig& config,
                        OwnSettings& out) const override {
    KickSettings k;
    if (doc.contains("script")) {
      if (!doc.at("script").is_string()) return Status::error("script: must be a string");
      k.script = doc.at("script").get<std::string>();
    }
    if (Status s = read_config_number(doc, "kick_at_s", k.kick_at_s); !s) return s;
    if (!(k.kick_at_s >= 0.0 && k.kick_at_s < config.duration_s))
      return Status::error("kick_at_s: must be in [0, duration_s)");
    if (Status s = read_config_number(doc, "yaw_drift_limit_rad", k.yaw_drift_limit_rad); !s)
      return s;
    out.set(k);
    return {};
  }
  void write_settings(const TaskConfig& config, nlohmann::json& doc) const override {
    const KickSettings& k = config.own_settings<KickSettings>();
    doc["script"] = k.script;
    doc["kick_at_s"] = k.kick_at_s;
    doc["yaw_drift_limit_rad"] = k.yaw_drift_limit_rad;
  }
  double action_at_s(const TaskConfig& config) const override {
    return config.own_settings<KickSettings>().kick_at_s;
  }
  std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int, double period_s,
                                             const sim::SimWorld&) const override {
    return std::make_unique<KickEpisode>(config, period_s);
  }
};

}  // namespace

const TaskType& kick_task_type() {
  static const KickTask type;
  return type;
}

}  // namespace stride::opt
