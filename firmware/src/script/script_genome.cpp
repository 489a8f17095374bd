// Script genomes: parameter names and bounds of a script's frame targets (see the header).
#include "stride/firmware/script/script_genome.hpp"

#include <algorithm>
#include <cmath>

#include "stride/firmware/servo_table.hpp"

namespace stride::fw {

std::string script_position_parameter(std::string_view script_name, std::size_t frame_index,
                                      std::string_view servo_name) {
  std::string name = "script.";
  name += script_name;
  name += ".frame" + std::to_string(frame_index + 1) + ".";
  name += servo_name;
  name += ".position";
  return name;
}

std::string script_duration_parameter(std::string_view script_name, std::size_t frame_index) {
  std::string name = "script.";
  name += script_name;
  name += ".frame" + std::to_string(frame_index + 1) + ".duration_ms";
  return name;
}

Status script_genome(const ParameterStore& params, const Script& script, int first_frame,
                     int last_frame, double delta, std::vector<ScriptGene>& out) {
  const int frames = static_cast<int>(script.frames.size());
  if (first_frame < 1 || last_frame > frames || first_frame > last_frame) {
    return Status::error("script '" + script.name + "': genome frames " +
                         std::to_string(first_frame) + ".." + std::to_string(last_frame) +
                         " outside 1.." + std::to_string(frames) + " or empty");
  }
  if (!(delta > 0.0) || !std::isfinite(delta)) {
    return Status::error("script '" + script.name + "': genome delta must be positive, got " +
                         format_number(delta));
  }
  std::vector<ScriptGene> genes;
  const ServoTable& servos = ServoTable::defaults();
  for (int f = first_frame - 1; f < last_frame; ++f) {
    for (const ScriptTarget& t : script.frames[static_cast<std::size_t>(f)].targets) {
      ScriptGene gene;
      gene.parameter =
          script_position_parameter(script.name, static_cast<std::size_t>(f), servos[t.servo].name);
      const auto handle = params.find(gene.parameter);
      if (!handle) return Status::error("unknown parameter '" + gene.parameter + "'");
      const ParamSpec& spec = params.spec(*handle);
      gene.seed = t.position_rad;
      gene.min = std::max(spec.min, t.position_rad - delta);
      gene.max = std::min(spec.max, t.position_rad + delta);
      genes.push_back(std::move(gene));
    }
  }
  out = std::move(genes);
  return {};
}

Status kick_genome(const ParameterStore& params, const Script& script, std::vector<ScriptGene>& out,
                   double delta) {
  const int frames = static_cast<int>(script.frames.size());
  if (frames < 3) {
    return Status::error("script '" + script.name + "': a kick genome needs at least 3 frames");
  }
  return script_genome(params, script, 2, frames - 1, delta, out);
}

Status genome_writes(const std::vector<ScriptGene>& genes, const std::vector<double>& reals,
                     std::vector<ParamWrite>& out) {
  if (genes.size() != reals.size()) {
    return Status::error("genome: expected " + std::to_string(genes.size()) + " reals, got " +
                         std::to_string(reals.size()));
  }
  std::vector<ParamWrite> writes;
  writes.reserve(genes.size());
  for (std::size_t i = 0; i < genes.size(); ++i) {
    if (!(reals[i] >= genes[i].min && reals[i] <= genes[i].max)) {
      return Status::error("genome gene " + std::to_string(i) + " (" + genes[i].parameter +
                           "): " + format_number(reals[i]) + " outside [" +
                           format_number(genes[i].min) + ", " + format_number(genes[i].max) + "]");
    }
    writes.emplace_back(genes[i].parameter, reals[i]);
  }
  out = std::move(writes);
  return {};
}

Status genome_from_store(const ParameterStore& params, const std::vector<ScriptGene>& genes,
                         std::vector<double>& reals) {
  std::vector<double> values(genes.size());
  for (std::size_t i = 0; i < genes.size(); ++i) {
    if (Status s = params.get(genes[i].parameter, values[i]); !s) return s;
  }
  reals = std::move(values);
  return {};
}

}  // namespace stride::fw
