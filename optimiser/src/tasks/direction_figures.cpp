// The figures of the tasks that walk in every direction (see direction_figures.hpp).
#include "stride/optimiser/tasks/direction_figures.hpp"

#include <array>

namespace stride::opt {

void merge_direction_figures(const TaskFigures& next, TaskFigures& total) {
  const DirectionFigures* n = next.find<DirectionFigures>();
  if (n == nullptr) return;
  DirectionFigures& t = total.as<DirectionFigures>();
  for (std::size_t d = 0; d < t.segments.size(); ++d)
    if (n->segments[d].measured || n->segments[d].speed != 0.0) t.segments[d] = n->segments[d];
}

ValidationFigures direction_validation_figures(const std::vector<const EpisodeScore*>& seeds) {
  std::array<double, kOmniSegments> speeds{};
  for (const EpisodeScore* score : seeds) {
    const DirectionFigures figures = score->figures.read<DirectionFigures>();
    for (int d = 0; d < kOmniSegments; ++d)
      speeds[d] += figures.segments[d].speed / static_cast<double>(seeds.size());
  }
  ValidationFigures out;
  nlohmann::json by_name = nlohmann::json::object();
  for (int d = 0; d < kOmniSegments; ++d) {
    const char* name = to_string(static_cast<OmniDirection>(d));
    by_name[name] = speeds[d];
    out.table_row[name] = speeds[d];
  }
  out.cell["speeds"] = by_name;
  return out;
}

OmniSegments TaskType::direction_segments(const EpisodeScore& score) const {
  return score.figures.read<DirectionFigures>().segments;
}

bool every_direction_measured(const EpisodeScore& score) {
  return every_segment_measured(score.figures.read<DirectionFigures>().segments);
}

std::string direction_outcome_note(const EpisodeScore& score, double end_s) {
  return travel_note(score.fell, score.figures.read<DirectionFigures>().distance_m, end_s);
}

}  // namespace stride::opt
