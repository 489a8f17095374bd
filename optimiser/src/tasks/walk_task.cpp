// The walk task (the seed's walk evaluator, igus.md 7.4): from standing, walk forward at the
// config's command until goal_distance_m is covered or duration_s is up.
//   Obj1 = time to cover goal_distance_m [s]; not reached: duration_s + 10 s/m * the distance
//          still missing (a penalty that still rewards progress).
//   Obj2 = max |a| of the IMU over the episode [m/s^2].
//   c0 = fell ? -(1 + time lost / duration) : 0  (g >= 0 is feasible).
//   Straightness at the goal (or the episode's end), from ground truth (walk_measures.hpp):
//   c1 = min(0, 1 - (|lateral drift| / max(forward, 0.25 m)) / max_drift_ratio),
//   c2 = min(0, 1 - |heading change| / max_heading_change_deg); a limit of null is off.
// Its own settings (walk_settings.hpp): goal_distance_m, walk_vx, the straightness limits; its
// own figures (walk_figures.hpp): distance, time to the goal, drift and heading change.
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <numbers>

#include "stride/firmware/motion_request.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/optimiser/tasks/walk_figures.hpp"
#include "stride/optimiser/tasks/walk_measures.hpp"
#include "stride/optimiser/tasks/walk_settings.hpp"

namespace stride::opt {

namespace {

class WalkEpisode final : public TaskEpisode {
 public:
  WalkEpisode(const TaskConfig& config, const sim::SimWorld& world)
      : config_(config), walk_(config.own_settings<WalkSettings>()), start_(world.ground_truth()) {
    yaw_.reset(torso_yaw(start_.torso));
  }
  sim::EpisodeOptions options() const override {
    sim::EpisodeOptions o;
    o.duration_s = config_.duration_s;
    o.goal_distance_m = walk_.goal_distance_m;
    o.stop_on_fall = true;
    o.stop_at_goal = true;
    return o;
  }
  void before_step(const hal::SensorFrame&, hal::Tick, const sim::SimWorld& world,
                   fw::Controller& controller) override {
    yaw_.update(torso_yaw(world.torso_pose()));
    if (!requested_) {
      controller.request(fw::MotionRequest::walk(walk_.walk_vx, 0.0, 0.0));
      requested_ = true;
    }
  }
  Status score(const sim::EpisodeResult& r, const sim::SimWorld& world,
               const fw::Controller& controller, EpisodeScore& out) override {
    if (controller.motion().refused_requests() > 0) return Status::error("walk request refused");
    // Straightness in the start's walking frame, at the goal or the episode's end.
    const PlanarPose a = walking_frame(start_, torso_yaw(start_.torso));
    const PlanarPose b = walking_frame(world.ground_truth(), yaw_.yaw());
    const Translation t = measure_translation(a, b, 1.0, 0.0);
    WalkFigures& figures = out.figures.as<WalkFigures>();
    figures.distance_m = r.distance_m;
    figures.time_to_goal_s = r.time_to_goal_s ? *r.time_to_goal_s : -1.0;
    figures.lateral_drift_m = t.off_axis_m;
    figures.heading_change_rad = t.heading_change_rad;
    const StraightnessLimits& limits = walk_.straightness;
    const double heading_limit = limits.max_heading_change_deg * std::numbers::pi / 180.0;
    const double missing = std::max(0.0, walk_.goal_distance_m - r.distance_m);
    const double time = r.time_to_goal_s ? *r.time_to_goal_s : config_.duration_s + 10.0 * missing;
    out.objectives = {time, r.max_accel};
    const double lost = r.fell ? std::max(0.0, config_.duration_s - r.fall_time_s) : 0.0;
    out.constraints = {
        r.fell ? -(1.0 + lost / config_.duration_s) : 0.0,
        limits.max_drift_ratio > 0.0
            ? limit_violation(t.drift_ratio() / limits.max_drift_ratio, 1.0)
            : limit_violation(t.drift_ratio(), limits.max_drift_ratio),
        heading_limit > 0.0 ? limit_violation(t.heading_change_rad / heading_limit, 1.0) : 0.0};
    return {};
  }

 private:
  const TaskConfig& config_;
  const WalkSettings& walk_;
  const sim::GroundTruth start_;
  YawTracker yaw_;
  bool requested_ = false;
};

/// The walk's settings fields: its own and the straightness limits.
std::vector<std::string_view> walk_settings_fields() {
  std::vector<std::string_view> fields = {"goal_distance_m", "walk_vx"};
  fields.insert(fields.end(), std::begin(kStraightnessFields), std::end(kStraightnessFields));
  return fields;
}

class WalkTask final : public TaskType {
 public:
  WalkTask()
      : TaskType({.name = "walk",
                  .constraint_count = 3,
                  .labels = {"time to 2.5 m [s]", "max |a| [m/s^2]"},
                  .legend = "f1 time to goal [s], f2 max |a| [m/s^2]",
                  .best_f1_pick = "fastest",
                  .best_f2_pick = "most_stable",
                  .words = {"reach the goal", "reaches the goal", "does not reach the goal in time",
                            "time to the goal", "walk", "{} % slower than in the run"},
                  .settings_fields = walk_settings_fields()}) {}
  /// The goal in the first label is the config's.
  ObjectiveLabels objective_labels(const nlohmann::json& task_doc) const override {
    double goal = 2.5;
    if (task_doc.is_object() && task_doc.contains("goal_distance_m") &&
        task_doc["goal_distance_m"].is_number())
      goal = task_doc["goal_distance_m"].get<double>();
    char f1[64];
    std::snprintf(f1, sizeof f1, "time to %.3g m [s]", goal);
    return {f1, descriptor().labels.f2};
  }
  bool succeeded(const TaskConfig&, const EpisodeScore& score) const override {
    return score.figures.read<WalkFigures>().time_to_goal_s >= 0.0;
  }
  std::optional<double> replay_goal_m(const TaskConfig& config) const override {
    return config.own_settings<WalkSettings>().goal_distance_m;
  }
  std::string outcome_note(const TaskConfig& config, const EpisodeScore& s,
                           double end_s) const override {
    const WalkFigures figures = s.figures.read<WalkFigures>();
    if (s.fell || figures.time_to_goal_s < 0) return travel_note(s.fell, figures.distance_m, end_s);
    char text[96];
    std::snprintf(text, sizeof text, "reached %.3g m at %.2f s",
                  config.own_settings<WalkSettings>().goal_distance_m, figures.time_to_goal_s);
    return text;
  }
  Status parse_settings(const nlohmann::json& doc, const TaskConfig&,
                        OwnSettings& out) const override {
    WalkSettings w;
    if (Status s = read_config_number(doc, "goal_distance_m", w.goal_distance_m); !s) return s;
    if (!(w.goal_distance_m > 0.0)) return Status::error("goal_distance_m: must be positive");
    if (Status s = read_config_number(doc, "walk_vx", w.walk_vx); !s) return s;
    if (!(w.walk_vx >= -1.0 && w.walk_vx <= 1.0))
      return Status::error("walk_vx: must be in [-1, 1]");
    if (Status s = parse_straightness(doc, w.straightness); !s) return s;
    out.set(w);
    return {};
  }
  void write_settings(const TaskConfig& config, nlohmann::json& doc) const override {
    const WalkSettings& w = config.own_settings<WalkSettings>();
    doc["goal_distance_m"] = w.goal_distance_m;
    doc["walk_vx"] = w.walk_vx;
    write_straightness(w.straightness, doc);
  }
  std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int, double,
                                             const sim::SimWorld& world) const override {
    return std::make_unique<WalkEpisode>(config, world);
  }
};

}  // namespace

const TaskType& walk_task_type() {
  static const WalkTask type;
  return type;
}

}  // namespace stride::opt
