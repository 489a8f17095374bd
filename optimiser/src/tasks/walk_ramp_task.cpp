// The speed-ramp walk task (issue 32 point 1; its own settings in speed_ramp.hpp, config `ramp`;
// the ramp of one direction in ramp_direction.hpp): the top speed of each direction, as the
// Bit-Bots search for it, one episode per direction.
//   Obj1 = -(v_f + v_b + 2 v_side + 0.2 w_turn) [m/s], each v the direction's best speed held,
//          v_side and w_turn the means of both sides (the Bit-Bots' score): each episode scores
//          -6 w_d v_d (w = 1, 1, 1, 1, 0.1, 0.1), so that the world's mean is the sum.
//   Obj2 = max |a| of the IMU [m/s^2], the mean over the six episodes of each one's peak.
//   c0   = -(directions with no level held before a fall) / 6.
//   c1   = -(directions whose first level was already beyond the straightness limits) / 6.
// A direction's best speed is its segment in the task's figures (direction_figures.hpp; measured:
// a level counted), each episode filling its own, so that the run's report and stride validate
// show the per-direction top speeds beside the reference figures.
// A level is a speed (speed_ramp.hpp); the episode commands it with the walk's parameters as the
// genome set them, read once at the first tick (parameters_applied).
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "stride/firmware/motion_request.hpp"
#include "stride/optimiser/tasks/direction_figures.hpp"
#include "stride/optimiser/tasks/ramp_command.hpp"
#include "stride/optimiser/tasks/ramp_direction.hpp"
#include "stride/optimiser/tasks/speed_ramp.hpp"
#include "stride/optimiser/tasks/task_type.hpp"

namespace stride::opt {

namespace {

constexpr std::array<double, kOmniSegments> kWeights = {1.0, 1.0, 1.0, 1.0, 0.1, 0.1};

class RampEpisode final : public TaskEpisode {
 public:
  RampEpisode(const TaskConfig& config, int direction, double period_s)
      : direction_(direction),
        period_s_(period_s),
        settings_(config.own_settings<RampSettings>()),
        axis_(omni_command(static_cast<OmniDirection>(direction))),
        ramp_(settings_, axis_) {}
  sim::EpisodeOptions options() const override {
    sim::EpisodeOptions o;
    o.duration_s = settings_.timing.episode_s();
    o.goal_distance_m = 1e9;
    o.stop_on_fall = true;
    o.stop_when = [this] { return ramp_.ended(); };
    return o;
  }
  void parameters_applied(const fw::ParameterStore& params) override {
    walk_read_ = read_walk_parameters(params, walk_);
  }
  void before_step(const hal::SensorFrame&, hal::Tick tick, const sim::SimWorld& world,
                   fw::Controller& controller) override {
    const double t = static_cast<double>(tick) * period_s_;
    yaw_ = tick == 0 ? (yaws_.reset(torso_yaw(world.torso_pose())), yaws_.yaw())
                     : yaws_.update(torso_yaw(world.torso_pose()));
    const int level = ramp_.level_at(t);
    if (level != level_) {  // a level ends (or the first starts)
      if (level_ >= 1) end_level(world);
      if (level_ == 0) direction_start_ = walking_frame(world.ground_truth(), yaw_);
      level_ = level;
      const double c = ramp_.begin_level(level_, walk_);
      if (ramp_.ended()) return;
      controller.request(fw::MotionRequest::walk(c * axis_[0], c * axis_[1], c * axis_[2]));
    }
    // The measurement window: the level's last measure_s.
    if (level_ >= 1 && !window_open_ && ramp_.window_begun(level_, t)) {
      window_start_ = walking_frame(world.ground_truth(), yaw_);
      window_open_ = true;
    }
  }
  Status score(const sim::EpisodeResult& r, const sim::SimWorld&, const fw::Controller& controller,
               EpisodeScore& out) override {
    if (controller.motion().refused_requests() > 0) return Status::error("walk request refused");
    if (!walk_read_) return Status::error("walk parameters: " + walk_read_.message());
    DirectionFigures& figures = out.figures.as<DirectionFigures>();
    figures.distance_m = r.distance_m;
    OmniSegment& s = figures.segments[static_cast<std::size_t>(direction_)];
    const RampLevel& best = ramp_.best();
    s.measured = ramp_.counted();
    s.speed = ramp_.counted() ? best.speed : 0.0;
    s.drift_ratio = best.drift_ratio;
    s.heading_change_rad = best.heading_change_rad;
    s.translation_m = best.translation_m;
    out.objectives = {-static_cast<double>(kOmniSegments) *
                          kWeights[static_cast<std::size_t>(direction_)] * s.speed,
                      r.max_accel};
    out.constraints = {r.fell && !ramp_.counted() ? -1.0 : 0.0, ramp_.crooked_first() ? -1.0 : 0.0};
    return {};
  }

 private:
  /// The level just completed: its figures over the window decide whether the direction goes on.
  void end_level(const sim::SimWorld& world) {
    if (!window_open_) return;
    window_open_ = false;
    const PlanarPose end = walking_frame(world.ground_truth(), yaw_);
    ramp_.end_level(level_,
                    measure_ramp_level(direction_start_, window_start_, end, axis_, settings_));
  }

  int direction_;
  double period_s_;
  const RampSettings& settings_;
  std::array<double, 3> axis_;
  RampDirection ramp_;
  fw::walk::WalkParameters walk_;  ///< as the genome set them (parameters_applied)
  Status walk_read_ = Status::error("never read");
  YawTracker yaws_;
  double yaw_ = 0.0;
  int level_ = 0;
  bool window_open_ = false;
  PlanarPose window_start_, direction_start_;
};

/// `ramp` and the straightness limits.
std::vector<std::string_view> ramp_settings_fields() {
  std::vector<std::string_view> fields = {"ramp"};
  fields.insert(fields.end(), std::begin(kStraightnessFields), std::end(kStraightnessFields));
  return fields;
}

class WalkRampTask final : public TaskType {
 public:
  WalkRampTask()
      : TaskType(
            {.name = "walk-ramp",
             .constraint_count = 2,
             .labels = {"-(v_f + v_b + 2 v_side + 0.2 w_turn), top speeds [m/s]",
                        "max |a| [m/s^2]"},
             .legend =
                 "f1 -(v_f + v_b + 2 v_side + 0.2 w_turn) of the top speeds, f2 max |a| [m/s^2]",
             .best_f1_pick = "fastest",
             .best_f2_pick = "most_stable",
             .words = {"hold a speed in every direction", "holds a speed in every direction",
                       "does not hold a speed in every direction", "speed score", "walk",
                       "its median speed score is {} % worse than in the run"},
             .measures_directions = true,
             .episodes_per_world = kOmniSegments,
             .settings_fields = ramp_settings_fields()}) {}
  bool succeeded(const TaskConfig&, const EpisodeScore& score) const override {
    return every_direction_measured(score);
  }
  std::string outcome_note(const TaskConfig&, const EpisodeScore& s, double end_s) const override {
    return direction_outcome_note(s, end_s);
  }
  void merge_figures(const TaskFigures& next, int, TaskFigures& total) const override {
    merge_direction_figures(next, total);
  }
  ValidationFigures validation_figures(
      const std::vector<const EpisodeScore*>& seeds) const override {
    return direction_validation_figures(seeds);
  }
  Status parse_settings(const nlohmann::json& doc, const TaskConfig&,
                        OwnSettings& out) const override {
    RampSettings r;
    if (doc.contains("ramp"))
      if (Status s = parse_ramp(doc.at("ramp"), r.timing); !s) return s;
    if (Status s = parse_straightness(doc, r.straightness); !s) return s;
    out.set(r);
    return {};
  }
  void write_settings(const TaskConfig& config, nlohmann::json& doc) const override {
    const RampSettings& r = config.own_settings<RampSettings>();
    doc["ramp"] = to_json(r.timing);
    write_straightness(r.straightness, doc);
  }
  std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int episode, double period_s,
                                             const sim::SimWorld&) const override {
    return std::make_unique<RampEpisode>(config, episode, period_s);
  }
};

}  // namespace

const TaskType& walk_ramp_task_type() {
  static const WalkRampTask type;
  return type;
}

Status parse_ramp(const nlohmann::json& doc, RampTiming& out) {
  if (!doc.is_object()) return Status::error("ramp: must be an object");
  RampTiming r = out;
  for (const auto& [key, value] : doc.items()) {
    double* target = key == "start_s"           ? &r.start_s
                     : key == "increment_mps"   ? &r.increment_mps
                     : key == "increment_radps" ? &r.increment_radps
                     : key == "increment"       ? &r.increment
                     : key == "hold_s"          ? &r.hold_s
                     : key == "measure_s"       ? &r.measure_s
                                                : nullptr;
    if (key == "max_levels" || key == "patience") {
      if (!value.is_number_integer() || value.get<int>() < 1 || value.get<int>() > 100)
        return Status::error("ramp." + key + ": must be an integer in 1..100, got " + value.dump());
      (key == "patience" ? r.patience : r.max_levels) = value.get<int>();
      continue;
    }
    if (target == nullptr)
      return Status::error("ramp." + key +
                           ": unknown field (known: start_s, increment_mps, increment_radps, "
                           "increment, hold_s, measure_s, max_levels, patience)");
    if (!value.is_number() || !std::isfinite(value.get<double>()))
      return Status::error("ramp." + key + ": must be a number, got " + value.dump());
    *target = value.get<double>();
  }
  if (!(r.start_s >= 0.0 && r.start_s <= 60.0))
    return Status::error("ramp.start_s: must be in [0, 60] s");
  if (!(r.increment_mps > 0.0 && r.increment_mps <= 1.0))
    return Status::error("ramp.increment_mps: must be in (0, 1] m/s");
  if (!(r.increment_radps > 0.0 && r.increment_radps <= 5.0))
    return Status::error("ramp.increment_radps: must be in (0, 5] rad/s");
  if (!(r.increment >= 0.0 && r.increment <= 1.0))
    return Status::error(
        "ramp.increment: must be in [0, 1] (normalised command per level; 0: levels of "
        "increment_mps and increment_radps)");
  if (!(r.hold_s >= 1.0 && r.hold_s <= 60.0))
    return Status::error("ramp.hold_s: must be in [1, 60] s");
  if (!(r.measure_s > 0.0 && r.measure_s <= r.hold_s))
    return Status::error("ramp.measure_s: must be in (0, hold_s]");
  out = r;
  return {};
}

nlohmann::json to_json(const RampTiming& r) {
  return {{"start_s", r.start_s},
          {"increment_mps", r.increment_mps},
          {"increment_radps", r.increment_radps},
          {"increment", r.increment},
          {"hold_s", r.hold_s},
          {"measure_s", r.measure_s},
          {"max_levels", r.max_levels},
          {"patience", r.patience}};
}

}  // namespace stride::opt
