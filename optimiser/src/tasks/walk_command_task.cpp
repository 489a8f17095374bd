// The commanded-walk task (issue 53 point 2; its settings and schedule in
// walk_command_settings.hpp, config `command`; its figures in walk_command_figures.hpp): what a
// team commands, in one episode per world from standing. After start_s stepping in place, a
// fixed schedule of segments, each a normalised walk command held for hold_s (its realised speed
// measured over the last measure_s from ground truth, in the heading frame at the measurement's
// start, walk_measures.hpp, along the direction the walk plans for the command: the command's
// axis, or for a diagonal where the genome's limits send it, ramp_command.hpp) or a stand
// request held for stop_s.
//   Obj1 = -(1/6) sum over the six directions of min(1.5, speed / reference speed)
//          (kReferenceSpeeds: NUgus's 0.38, 0.42, 0.26, 0.26 m/s and 1.97, 1.97 rad/s)
//   Obj2 = max |a| of the IMU over the episode [m/s^2]
//   c0 fell anywhere: -(1 + time lost / episode length)
//   c1 drift, c2 heading change: sums over the pure translations (segments that do not turn),
//      c3 translation: over the pure turns, each term max(-1, min(0, 1 - figure / limit))
//      (walk_measures.hpp), the straightness limits being the constraints' limits: they are
//      figures, and never end a segment early
//   c4 stand: -(stand segments that did not end standing)
// A segment not reached before a fall scores speed 0 and adds -1 to each constraint it has, so
// that falling earlier never lowers the violation. The episode ends at a fall.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <set>
#include <string>

#include "stride/firmware/motion_manager.hpp"
#include "stride/firmware/motion_request.hpp"
#include "stride/optimiser/tasks/ramp_command.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/optimiser/tasks/walk_command_figures.hpp"
#include "stride/optimiser/tasks/walk_command_settings.hpp"

namespace stride::opt {

namespace {

bool translates(const CommandSegmentSpec& s) {
  return !s.stand && (s.command[0] != 0.0 || s.command[1] != 0.0);
}
bool turns(const CommandSegmentSpec& s) {
  return !s.stand && s.command[2] != 0.0;
}

/// The segment of each of the six directions (the schedule was checked to have each once).
std::array<std::size_t, kOmniSegments> direction_indices(const CommandSchedule& schedule) {
  std::array<std::size_t, kOmniSegments> out{};
  for (int d = 0; d < kOmniSegments; ++d)
    for (std::size_t k = 0; k < schedule.segments.size(); ++k)
      if (schedule.segments[k].name == to_string(static_cast<OmniDirection>(d))) out[d] = k;
  return out;
}

hal::Tick to_tick(double t_s, double period_s) {
  return static_cast<hal::Tick>(std::llround(t_s / period_s));
}

class CommandEpisode final : public TaskEpisode {
 public:
  CommandEpisode(const TaskConfig& config, double period_s)
      : settings_(config.own_settings<CommandSettings>()), period_s_(period_s) {
    const CommandSchedule& c = settings_.schedule;
    const std::size_t n = c.segments.size();
    begin_.resize(n);
    end_.resize(n);
    window_.resize(n);
    window_start_.resize(n);
    figures_.resize(n);
    axes_.assign(n, {1.0, 0.0});
    for (std::size_t k = 0; k < n; ++k) {
      begin_[k] = to_tick(c.begin_s(k), period_s);
      end_[k] = to_tick(c.begin_s(k + 1), period_s);
      window_[k] =
          c.segments[k].stand ? begin_[k] : to_tick(c.begin_s(k + 1) - c.measure_s, period_s);
      figures_[k].name = c.segments[k].name;
      figures_[k].stand = c.segments[k].stand;
    }
  }
  sim::EpisodeOptions options() const override {
    sim::EpisodeOptions o;
    o.duration_s = settings_.schedule.total_s();
    o.goal_distance_m = 1e9;
    o.stop_on_fall = true;
    return o;
  }
  /// The direction each translating segment is judged along: where the walk plans it (a
  /// diagonal command goes where the genome's own limits send it, ramp_command.hpp).
  void parameters_applied(const fw::ParameterStore& params) override {
    for (std::size_t k = 0; k < axes_.size(); ++k)
      if (translates(settings_.schedule.segments[k]))
        if (Status s = planned_direction(params, settings_.schedule.segments[k].command, axes_[k]);
            !s && planned_) {
          planned_ = Status::error("the walk's planned direction: " + s.message());
        }
  }
  void before_step(const hal::SensorFrame&, hal::Tick tick, const sim::SimWorld& world,
                   fw::Controller& controller) override {
    const double yaw = tick == 0 ? (yaws_.reset(torso_yaw(world.torso_pose())), yaws_.yaw())
                                 : yaws_.update(torso_yaw(world.torso_pose()));
    if (tick == 0) controller.request(fw::MotionRequest::walk(0.0, 0.0, 0.0));
    const std::size_t n = figures_.size();
    if (active_ < n && tick == end_[active_]) end_segment(world, controller, yaw);
    if (next_ < n && tick == begin_[next_]) {
      active_ = next_++;
      const CommandSegmentSpec& s = settings_.schedule.segments[active_];
      controller.request(s.stand
                             ? fw::MotionRequest::stand()
                             : fw::MotionRequest::walk(s.command[0], s.command[1], s.command[2]));
    }
    if (active_ < n && tick == window_[active_])
      window_start_[active_] = walking_frame(world.ground_truth(), yaw);
  }
  Status score(const sim::EpisodeResult& r, const sim::SimWorld&, const fw::Controller& controller,
               EpisodeScore& out) override {
    if (controller.motion().refused_requests() > 0) return Status::error("walk request refused");
    if (!planned_) return planned_;
    const CommandSchedule& c = settings_.schedule;
    const StraightnessLimits& limits = settings_.straightness;
    CommandFigures& figures = out.figures.as<CommandFigures>();
    figures.segments = figures_;
    figures.distance_m = r.distance_m;
    const auto directions = direction_indices(c);
    double ratio_sum = 0.0;
    for (int d = 0; d < kOmniSegments; ++d) {
      const CommandSegmentFigures& f = figures_[directions[d]];
      figures.directions[d] = {f.measured, f.speed, f.drift_ratio, f.heading_change_rad,
                               f.translation_m};
      ratio_sum += std::min(1.5, f.speed / kReferenceSpeeds[d]);
    }
    out.objectives = {-ratio_sum / kOmniSegments, r.max_accel};
    std::array<double, 4> g{0.0, 0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < c.segments.size(); ++k) {
      const CommandSegmentSpec& s = c.segments[k];
      const CommandSegmentFigures& f = figures_[k];
      if (s.stand) {
        g[3] -= f.measured && f.stood ? 0.0 : 1.0;
      } else if (!turns(s)) {
        if (limits.max_drift_ratio >= 0.0) g[0] += drift_term(f.measured, f.drift_ratio, limits);
        if (limits.max_heading_change_deg > 0.0)
          g[1] += heading_term(f.measured, f.heading_change_rad, limits);
      } else if (!translates(s) && limits.max_turn_translation_m > 0.0) {
        g[2] += turn_translation_term(f.measured, f.translation_m, limits);
      }
    }
    const double length = c.total_s();
    const double lost = r.fell ? std::max(0.0, length - r.fall_time_s) : 0.0;
    out.constraints = {r.fell ? -(1.0 + lost / length) : 0.0, g[0], g[1], g[2], g[3]};
    return {};
  }

 private:
  /// The active segment ends: its figures over its window, or whether it stands.
  void end_segment(const sim::SimWorld& world, const fw::Controller& controller, double yaw) {
    const CommandSegmentSpec& s = settings_.schedule.segments[active_];
    CommandSegmentFigures& f = figures_[active_];
    const PlanarPose a = window_start_[active_];
    const PlanarPose b = walking_frame(world.ground_truth(), yaw);
    f.measured = true;
    f.translation_m = std::hypot(b.x - a.x, b.y - a.y);
    f.heading_change_rad = std::abs(b.yaw - a.yaw);
    if (s.stand) {
      f.stood = controller.motion().state() == fw::MotionState::kStand;
      return;
    }
    const double window_s = static_cast<double>(end_[active_] - window_[active_]) * period_s_;
    if (translates(s)) {
      const Translation t = measure_translation(a, b, axes_[active_][0], axes_[active_][1]);
      f.speed = t.along_m / window_s;
      f.drift_ratio = t.drift_ratio();
    }
    if (turns(s)) {
      f.turn_rate_radps = std::copysign(1.0, s.command[2]) * (b.yaw - a.yaw) / window_s;
      if (!translates(s)) f.speed = f.turn_rate_radps;
    }
  }

  const CommandSettings& settings_;
  double period_s_;
  // Per segment (sized once, before the episode; before_step only writes into them).
  std::vector<hal::Tick> begin_, end_, window_;
  std::vector<PlanarPose> window_start_;
  std::vector<CommandSegmentFigures> figures_;
  std::vector<std::array<double, 2>> axes_;  ///< translating segments' planned directions
  Status planned_;
  std::size_t next_ = 0;                               ///< the next segment to begin
  std::size_t active_ = static_cast<std::size_t>(-1);  ///< the segment running (none yet)
  YawTracker yaws_;
};

/// The figures' mean over a world's seeds.
ValidationFigures command_validation_figures(const std::vector<const EpisodeScore*>& seeds) {
  ValidationFigures out;
  if (seeds.empty()) return out;
  const double n = static_cast<double>(seeds.size());
  std::array<double, kOmniSegments> speeds{};
  std::vector<CommandSegmentFigures> mean;
  std::vector<double> measured, stood;
  for (const EpisodeScore* score : seeds) {
    const CommandFigures f = score->figures.read<CommandFigures>();
    for (int d = 0; d < kOmniSegments; ++d) speeds[d] += f.directions[d].speed / n;
    if (mean.empty()) {
      mean.resize(f.segments.size());
      measured.assign(f.segments.size(), 0.0);
      stood.assign(f.segments.size(), 0.0);
    }
    for (std::size_t k = 0; k < std::min(mean.size(), f.segments.size()); ++k) {
      const CommandSegmentFigures& s = f.segments[k];
      mean[k].name = s.name;
      mean[k].stand = s.stand;
      mean[k].speed += s.speed / n;
      mean[k].turn_rate_radps += s.turn_rate_radps / n;
      mean[k].drift_ratio += s.drift_ratio / n;
      mean[k].heading_change_rad += s.heading_change_rad / n;
      mean[k].translation_m += s.translation_m / n;
      measured[k] += s.measured ? 1.0 / n : 0.0;
      stood[k] += s.stood ? 1.0 / n : 0.0;
    }
  }
  nlohmann::json by_name = nlohmann::json::object();
  for (int d = 0; d < kOmniSegments; ++d) {
    const char* name = to_string(static_cast<OmniDirection>(d));
    by_name[name] = speeds[d];
    out.table_row[name] = speeds[d];
  }
  out.cell["speeds"] = by_name;
  nlohmann::json segments = nlohmann::json::array();
  for (std::size_t k = 0; k < mean.size(); ++k) {
    const CommandSegmentFigures& s = mean[k];
    nlohmann::json row = {{"name", s.name}, {"measured", measured[k]}};
    if (s.stand) {
      row["stood"] = stood[k];
      row["translation_m"] = s.translation_m;
    } else {
      row["speed"] = s.speed;
      row["turn_rate_radps"] = s.turn_rate_radps;
      row["drift_ratio"] = s.drift_ratio;
      row["heading_change_deg"] = s.heading_change_rad * 180.0 / std::numbers::pi;
      row["translation_m"] = s.translation_m;
      if (!out.table_row.contains(s.name)) out.table_row[s.name] = s.speed;
    }
    segments.push_back(row);
  }
  out.cell["segments"] = segments;
  return out;
}

/// `command` and the straightness limits.
std::vector<std::string_view> command_settings_fields() {
  std::vector<std::string_view> fields = {"command"};
  fields.insert(fields.end(), std::begin(kStraightnessFields), std::end(kStraightnessFields));
  return fields;
}

class WalkCommandTask final : public TaskType {
 public:
  WalkCommandTask()
      : TaskType({.name = "walk-command",
                  .constraint_count = 5,
                  .labels = {"-mean speed / reference over 6 directions [1]", "max |a| [m/s^2]"},
                  .legend = "f1 -mean over the six directions of speed / NUgus's (each at most "
                            "1.5), f2 max |a| [m/s^2]",
                  .best_f1_pick = "fastest",
                  .best_f2_pick = "most_stable",
                  .words = {"walk every commanded segment", "walks every commanded segment",
                            "does not walk every commanded segment", "speed score", "walk",
                            "its median speed score is {} % worse than in the run"},
                  .measures_directions = true,
                  .settings_fields = command_settings_fields()}) {}
  bool succeeded(const TaskConfig&, const EpisodeScore& score) const override {
    for (const CommandSegmentFigures& s : score.figures.read<CommandFigures>().segments)
      if (!s.measured || (s.stand && !s.stood)) return false;
    return !score.figures.read<CommandFigures>().segments.empty();
  }
  std::string outcome_note(const TaskConfig&, const EpisodeScore& s, double end_s) const override {
    const CommandFigures f = s.figures.read<CommandFigures>();
    std::size_t done = 0;
    while (done < f.segments.size() && f.segments[done].measured) ++done;
    char text[200];
    if (s.fell && done < f.segments.size())
      std::snprintf(text, sizeof text, "fell at %.2f s in '%s' (segment %zu of %zu)", end_s,
                    f.segments[done].name.c_str(), done + 1, f.segments.size());
    else if (s.fell)
      std::snprintf(text, sizeof text, "fell at %.2f s", end_s);
    else
      std::snprintf(text, sizeof text, "%zu of %zu segments in %.3g s, %.2f m along x", done,
                    f.segments.size(), end_s, f.distance_m);
    return text;
  }
  ValidationFigures validation_figures(
      const std::vector<const EpisodeScore*>& seeds) const override {
    return command_validation_figures(seeds);
  }
  OmniSegments direction_segments(const EpisodeScore& score) const override {
    return score.figures.read<CommandFigures>().directions;
  }
  Status parse_settings(const nlohmann::json& doc, const TaskConfig&,
                        OwnSettings& out) const override {
    CommandSettings c;
    if (doc.contains("command"))
      if (Status s = parse_command_schedule(doc.at("command"), c.schedule); !s) return s;
    if (Status s = parse_straightness(doc, c.straightness); !s) return s;
    out.set(c);
    return {};
  }
  void write_settings(const TaskConfig& config, nlohmann::json& doc) const override {
    const CommandSettings& c = config.own_settings<CommandSettings>();
    doc["command"] = to_json(c.schedule);
    write_straightness(c.straightness, doc);
  }
  std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int, double period_s,
                                             const sim::SimWorld&) const override {
    return std::make_unique<CommandEpisode>(config, period_s);
  }
};

/// A segment of the config's `command.segments`; the error names the field.
Status parse_segment(const nlohmann::json& doc, const std::string& field, CommandSegmentSpec& out) {
  if (!doc.is_object()) return Status::error(field + ": must be an object");
  for (const auto& [key, value] : doc.items())
    if (key != "name" && key != "command" && key != "stand")
      return Status::error(field + "." + key + ": unknown field (known: name, command, stand)");
  if (!doc.contains("name") || !doc["name"].is_string() || doc["name"].get<std::string>().empty())
    return Status::error(field + ".name: must be a non-empty string");
  out.name = doc["name"].get<std::string>();
  out.stand = false;
  if (doc.contains("stand")) {
    if (!doc["stand"].is_boolean()) return Status::error(field + ".stand: must be true or false");
    out.stand = doc["stand"].get<bool>();
  }
  if (out.stand) {
    if (doc.contains("command"))
      return Status::error(field + ".command: a stand segment has no command");
    out.command = {0.0, 0.0, 0.0};
    return {};
  }
  const nlohmann::json* c = doc.contains("command") ? &doc["command"] : nullptr;
  if (c == nullptr || !c->is_array() || c->size() != 3)
    return Status::error(field + ".command: must be [vx, vy, vtheta], each in [-1, 1]");
  for (std::size_t i = 0; i < 3; ++i) {
    const nlohmann::json& v = (*c)[i];
    if (!v.is_number() || !(std::abs(v.get<double>()) <= 1.0))
      return Status::error(field + ".command: must be [vx, vy, vtheta], each in [-1, 1], got " +
                           c->dump());
    out.command[i] = v.get<double>();
  }
  if (out.command == std::array<double, 3>{0.0, 0.0, 0.0})
    return Status::error(field + ".command: must not be zero (a stop is {\"stand\": true})");
  return {};
}

}  // namespace

const TaskType& walk_command_task_type() {
  static const WalkCommandTask type;
  return type;
}

std::vector<CommandSegmentSpec> default_command_segments() {
  return {{"forward", {1.0, 0.0, 0.0}},
          {"backward", {-1.0, 0.0, 0.0}},
          {"left", {0.0, 1.0, 0.0}},
          {"right", {0.0, -1.0, 0.0}},
          {"turn_left", {0.0, 0.0, 1.0}},
          {"turn_right", {0.0, 0.0, -1.0}},
          {"curve", {1.0, 0.0, 0.5}},
          {"diagonal", {0.7, 0.7, 0.0}},
          {"stop", {}, true},
          {"restart", {1.0, 0.0, 0.0}},
          {"reverse", {-1.0, 0.0, 0.0}}};
}

double CommandSchedule::begin_s(std::size_t k) const {
  double t = start_s;
  for (std::size_t i = 0; i < k && i < segments.size(); ++i)
    t += segments[i].stand ? stop_s : hold_s;
  return t;
}

double CommandSchedule::total_s() const {
  return begin_s(segments.size());
}

Status parse_command_schedule(const nlohmann::json& doc, CommandSchedule& out) {
  if (!doc.is_object()) return Status::error("command: must be an object");
  CommandSchedule c = out;
  for (const auto& [key, value] : doc.items()) {
    double* target = key == "start_s"     ? &c.start_s
                     : key == "hold_s"    ? &c.hold_s
                     : key == "measure_s" ? &c.measure_s
                     : key == "stop_s"    ? &c.stop_s
                                          : nullptr;
    if (key == "segments") {
      if (!value.is_array() || value.empty() || value.size() > 64)
        return Status::error("command.segments: must be a list of 1..64 segments");
      c.segments.assign(value.size(), {});
      std::set<std::string> names;
      for (std::size_t k = 0; k < value.size(); ++k) {
        const std::string field = "command.segments[" + std::to_string(k) + "]";
        if (Status s = parse_segment(value[k], field, c.segments[k]); !s) return s;
        if (!names.insert(c.segments[k].name).second)
          return Status::error(field + ".name: '" + c.segments[k].name + "' appears twice");
      }
      continue;
    }
    if (target == nullptr)
      return Status::error("command." + key +
                           ": unknown field (known: start_s, hold_s, measure_s, stop_s, "
                           "segments)");
    if (!value.is_number() || !std::isfinite(value.get<double>()))
      return Status::error("command." + key + ": must be a number, got " + value.dump());
    *target = value.get<double>();
  }
  if (!(c.start_s >= 0.0 && c.start_s <= 60.0))
    return Status::error("command.start_s: must be in [0, 60] s");
  if (!(c.hold_s >= 1.0 && c.hold_s <= 60.0))
    return Status::error("command.hold_s: must be in [1, 60] s");
  if (!(c.measure_s > 0.0 && c.measure_s <= c.hold_s))
    return Status::error("command.measure_s: must be in (0, hold_s]");
  if (!(c.stop_s >= 0.5 && c.stop_s <= 60.0))
    return Status::error("command.stop_s: must be in [0.5, 60] s");
  // The six directions the speed objective scores: each once, commanding its direction.
  for (int d = 0; d < kOmniSegments; ++d) {
    const auto direction = static_cast<OmniDirection>(d);
    const std::string name = to_string(direction);
    const auto it = std::find_if(c.segments.begin(), c.segments.end(),
                                 [&](const CommandSegmentSpec& s) { return s.name == name; });
    if (it == c.segments.end())
      return Status::error("command.segments: needs a segment named '" + name +
                           "' (the speed objective scores forward, backward, left, right, "
                           "turn_left and turn_right)");
    const auto axis = omni_command(direction);
    bool along = !it->stand;
    for (int i = 0; i < 3; ++i)
      along = along && (axis[i] == 0.0 ? it->command[i] == 0.0 : it->command[i] * axis[i] > 0.0);
    if (!along)
      return Status::error("command.segments[" + std::to_string(it - c.segments.begin()) +
                           "].command: '" + name + "' must command that direction alone");
  }
  out = c;
  return {};
}

nlohmann::json to_json(const CommandSchedule& c) {
  nlohmann::json segments = nlohmann::json::array();
  for (const CommandSegmentSpec& s : c.segments)
    segments.push_back(s.stand ? nlohmann::json{{"name", s.name}, {"stand", true}}
                               : nlohmann::json{{"name", s.name}, {"command", s.command}});
  return {{"start_s", c.start_s},
          {"hold_s", c.hold_s},
          {"measure_s", c.measure_s},
          {"stop_s", c.stop_s},
          {"segments", segments}};
}

}  // namespace stride::opt
