// Script genomes: the seed's kick genome (igus.md 7.3) as a list of ParameterStore names.
//
// A genome gene is one target position of one frame, addressed by its parameter name
//   script.<script>.frame<k>.<servo>.position      (k 1-based, as in the seed's "frames 2..N-1")
// and bounded by the file's value +- delta, clipped to the servo's limits. Genes are ordered
// frame by frame, targets in file order, like the seed's reals (frames[i].targets[j].position).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/script/script.hpp"

namespace stride::fw {

/// Name of the position parameter of the target of `servo_name` in frame `frame_index`
/// (0-based; the name uses frame_index + 1).
std::string script_position_parameter(std::string_view script_name, std::size_t frame_index,
                                      std::string_view servo_name);
/// Name of the duration parameter of frame `frame_index` (0-based; the name uses
/// frame_index + 1): "script.get_up_back.frame3.duration_ms", the file's duration by default.
std::string script_duration_parameter(std::string_view script_name, std::size_t frame_index);

struct ScriptGene {
  std::string parameter;  ///< e.g. "script.kick_right.frame2.r_knee.position"
  double seed = 0.0;      ///< the file's value (the unmutated individual Ind_O)
  double min = 0.0;
  double max = 0.0;
};

/// Genes of frames first_frame..last_frame (1-based, inclusive) of `script`, bounds seed +- delta
/// clipped to each parameter's bounds in `params`. Errors name a bad frame range, a non-positive
/// delta or a parameter missing from the store (script not added to a ScriptEngine).
Status script_genome(const ParameterStore& params, const Script& script, int first_frame,
                     int last_frame, double delta, std::vector<ScriptGene>& out);

/// The seed's kick genome: frames 2..N-1 (first and last fixed), delta = 0.5 rad by default.
Status kick_genome(const ParameterStore& params, const Script& script, std::vector<ScriptGene>& out,
                   double delta = 0.5);

/// The parameter writes that set a genome (one real per gene, in gene order). Fails naming the
/// gene if the counts differ or a value is outside its gene's bounds.
Status genome_writes(const std::vector<ScriptGene>& genes, const std::vector<double>& reals,
                     std::vector<ParamWrite>& out);

/// Reads the live values of a genome's parameters back from the store, in gene order.
Status genome_from_store(const ParameterStore& params, const std::vector<ScriptGene>& genes,
                         std::vector<double>& reals);

}  // namespace stride::fw
