// The omnidirectional walk task (issue 22): after start_s of walking in place, six segments
// forward, backward, sideways both ways and turning both ways, each a ramp, a hold where the
// speed is measured and a stop (walk_measures.hpp).
//   Obj1 = -(v_f + v_b + 2 v_side + 0.2 w_turn), Obj2 = max |a| [m/s^2];
//   c0 fell (-(1 + time lost / length)), c1 drift, c2 heading change, c3 translation while
//   turning (omni_constraints).
// Its own settings (walk_omni_settings.hpp): `omni` {start_s, ramp_s, hold_s, stop_s} and the
// straightness limits; its own figures: the directions' (direction_figures.hpp).
#include <algorithm>
#include <array>
#include <iterator>
#include <string>

#include "stride/firmware/motion_request.hpp"
#include "stride/optimiser/tasks/direction_figures.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/optimiser/tasks/walk_omni_settings.hpp"

namespace stride::opt {

namespace {

/// The config's `omni` object over `out`'s values; the error names the field.
Status parse_omni(const nlohmann::json& o, OmniTiming& out) {
  if (!o.is_object()) return Status::error("omni: must be an object");
  for (const auto& [key, value] : o.items())
    if (key != "start_s" && key != "ramp_s" && key != "hold_s" && key != "stop_s")
      return Status::error("omni." + key + ": unknown field");
  for (auto [name, target] : {std::pair{"start_s", &out.start_s},
                              {"ramp_s", &out.ramp_s},
                              {"hold_s", &out.hold_s},
                              {"stop_s", &out.stop_s}}) {
    if (Status s = read_config_number(o, name, *target); !s)
      return Status::error("omni." + s.message());
    if (!(*target >= 0.0 && *target <= 60.0))
      return Status::error(std::string("omni.") + name + ": must be in [0, 60]");
  }
  if (!(out.hold_s >= 1.0)) return Status::error("omni.hold_s: must be at least 1 s");
  return {};
}

class WalkOmniEpisode final : public TaskEpisode {
 public:
  WalkOmniEpisode(const TaskConfig& config, double period_s)
      : settings_(config.own_settings<OmniSettings>()), segments_(settings_.timing, period_s) {}
  sim::EpisodeOptions options() const override {
    sim::EpisodeOptions o;
    o.duration_s = segments_.duration_s();
    o.goal_distance_m = 1e9;
    o.stop_on_fall = true;
    return o;
  }
  void before_step(const hal::SensorFrame&, hal::Tick tick, const sim::SimWorld& world,
                   fw::Controller& controller) override {
    segments_.observe(tick, world);
    const auto c = segments_.command(tick);
    if (!requested_ || c != requested_command_) {
      controller.request(fw::MotionRequest::walk(c[0], c[1], c[2]));
      requested_command_ = c;
      requested_ = true;
    }
  }
  Status score(const sim::EpisodeResult& r, const sim::SimWorld&, const fw::Controller& controller,
               EpisodeScore& out) override {
    if (controller.motion().refused_requests() > 0) return Status::error("walk request refused");
    DirectionFigures& figures = out.figures.as<DirectionFigures>();
    figures.segments = segments_.segments();
    figures.distance_m = r.distance_m;
    out.objectives = {omni_speed_objective(figures.segments), r.max_accel};
    const double length = segments_.duration_s();
    const double lost = r.fell ? std::max(0.0, length - r.fall_time_s) : 0.0;
    const auto c = omni_constraints(figures.segments, settings_.straightness);
    out.constraints = {r.fell ? -(1.0 + lost / length) : 0.0, c[0], c[1], c[2]};
    return {};
  }

 private:
  const OmniSettings& settings_;
  OmniEpisode segments_;
  std::array<double, 3> requested_command_{0.0, 0.0, 0.0};
  bool requested_ = false;
};

/// `omni` and the straightness limits.
std::vector<std::string_view> omni_settings_fields() {
  std::vector<std::string_view> fields = {"omni"};
  fields.insert(fields.end(), std::begin(kStraightnessFields), std::end(kStraightnessFields));
  return fields;
}

class WalkOmniTask final : public TaskType {
 public:
  WalkOmniTask()
      : TaskType({.name = "walk-omni",
                  .constraint_count = 4,
                  .labels = {"-(v_f + v_b + 2 v_side + 0.2 w_turn) [m/s]", "max |a| [m/s^2]"},
                  .legend = "f1 -(v_f + v_b + 2 v_side + 0.2 w_turn), f2 max |a| [m/s^2]",
                  .best_f1_pick = "fastest",
                  .best_f2_pick = "most_stable",
                  .words = {"walk every segment", "walks every segment",
                            "does not walk every segment", "speed score", "walk",
                            "its median speed score is {} % worse than in the run"},
                  .measures_directions = true,
                  .settings_fields = omni_settings_fields()}) {}
  bool succeeded(const TaskConfig&, const EpisodeScore& score) const override {
    return every_direction_measured(score);
  }
  std::string outcome_note(const TaskConfig&, const EpisodeScore& s, double end_s) const override {
    return direction_outcome_note(s, end_s);
  }
  ValidationFigures validation_figures(
      const std::vector<const EpisodeScore*>& seeds) const override {
    return direction_validation_figures(seeds);
  }
  Status parse_settings(const nlohmann::json& doc, const TaskConfig&,
                        OwnSettings& out) const override {
    OmniSettings o;
    if (doc.contains("omni"))
      if (Status s = parse_omni(doc.at("omni"), o.timing); !s) return s;
    if (Status s = parse_straightness(doc, o.straightness); !s) return s;
    out.set(o);
    return {};
  }
  void write_settings(const TaskConfig& config, nlohmann::json& doc) const override {
    const OmniSettings& o = config.own_settings<OmniSettings>();
    const OmniTiming& t = o.timing;
    doc["omni"] = {
        {"start_s", t.start_s}, {"ramp_s", t.ramp_s}, {"hold_s", t.hold_s}, {"stop_s", t.stop_s}};
    write_straightness(o.straightness, doc);
  }
  std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int, double period_s,
                                             const sim::SimWorld&) const override {
    return std::make_unique<WalkOmniEpisode>(config, period_s);
  }
};

}  // namespace

const TaskType& walk_omni_task_type() {
  static const WalkOmniTask type;
  return type;
}

}  // namespace stride::opt
