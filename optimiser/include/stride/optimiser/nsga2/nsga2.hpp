// Nsga2: the NSGA-II engine with an ask/tell interface (problem-agnostic).
//
// Life cycle: create() builds the initial population (uniform random, or around a start genome)
// as the first batch. ask() returns the members of the current batch that still need an
// evaluation; tell() accepts their results in any order (failures included); once every member
// has a result, advance() integrates the batch (the first: ranks and crowding of the initial
// population; later ones: elitist survival from parents + children by fronts then crowding) and,
// unless the run is finished, builds the next batch of children (tournaments in groups of four,
// SBX / single-point crossover, polynomial / bit-flip mutation).
//
// Determinism: every random draw happens inside create() and advance(), from one seeded Rng, so
// the order in which results are told changes nothing. A genome already evaluated (same bits)
// is not handed out again: its cached result is reused; a genome occurring twice in one batch
// is handed out once.
//
// Resampling (Nsga2Settings::resample, for noisy problems): each batch carries its draw of the
// problem's noise; the cache then holds one draw only, and from the second generation on the
// batch is the children followed by the parents again, and survival picks from that batch
// alone, so that every result compared in one survival comes from the same draw.
//
// Checkpoints: checkpoint() after advance() captures everything (population with ranks and
// crowding, the next batch, the Rng state, counters); restore() with the evaluations made up to
// that point (for the cache) continues exactly as the uninterrupted run would. Doubles are
// stored as hexadecimal floating-point text, so they round-trip bit for bit.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/nsga2/evaluation.hpp"
#include "stride/optimiser/nsga2/genome.hpp"
#include "stride/optimiser/nsga2/rng.hpp"
#include "stride/optimiser/nsga2/settings.hpp"

namespace stride::opt {

struct Individual {
  std::uint64_t id = 0;  ///< serial number, unique within a run
  Genome genome;
  std::size_t genome_hash = 0;  ///< GenomeBitsHash of genome (set when the batch is resolved)
  Result result;
  bool evaluated = false;
  bool from_cache = false;  ///< result reused from an earlier identical genome
  int rank = 0;             ///< 0-based front under constraint domination
  double crowding = 0.0;    ///< crowding distance within its front (may be +inf)
};

struct Candidate {
  std::uint64_t id = 0;
  Genome genome;
  std::uint64_t draw = 0;  ///< the draw of the problem's noise to evaluate on (Problem)
};

struct Nsga2Counters {
  std::uint64_t evaluations = 0;  ///< results told
  std::uint64_t failures = 0;     ///< of which failed (infeasible by failure)
  std::uint64_t cache_hits = 0;   ///< batch members served from the cache (integrated batches)

  bool operator==(const Nsga2Counters&) const = default;
};

class Nsga2 {
 public:
  /// Validates everything and builds the first batch. `start` seeds the initial population.
  static Status create(const Nsga2Settings& settings, const ProblemShape& shape,
                       const std::optional<Genome>& start, std::unique_ptr<Nsga2>& out);
  /// As above with several start genomes: the first members of the initial population are
  /// the starts unmutated, the others are mutated copies of the starts in turn (one start
  /// gives exactly the population of the single-start create()). At most pop_size starts.
  static Status create(const Nsga2Settings& settings, const ProblemShape& shape,
                       const std::vector<Genome>& starts, std::unique_ptr<Nsga2>& out);
  /// Continues from checkpoint() output. `known` holds every evaluation made up to that
  /// checkpoint (genome and sanitised result), which refills the cache.
  static Status restore(const nlohmann::json& checkpoint, const ProblemShape& shape,
                        const std::vector<std::pair<Genome, Result>>& known,
                        std::unique_ptr<Nsga2>& out);

  /// Members of the current batch still waiting for a result (empty when none).
  std::vector<Candidate> ask() const;
  /// The draw the current batch is evaluated on: its generation's index with
  /// settings().resample (0 for the initial population), else always 0.
  std::uint64_t batch_draw() const;
  /// Records the result of batch member `id`; an unknown id or a second result is an error.
  Status tell(std::uint64_t id, EvaluationOutcome outcome);
  bool batch_complete() const;
  /// Integrates the complete batch and builds the next one (see the file comment).
  Status advance();
  /// Raises the run's total to `generations` (at least the current total): a finished run
  /// builds its next batch, so that the run goes on exactly as one started with that total
  /// would have (the batch draws from the generator where the longer run would).
  Status extend(int generations);

  bool finished() const { return completed_ >= settings_.generations; }
  /// Generations completed (the initial population is generation 1).
  int completed_generations() const { return completed_; }
  const std::vector<Individual>& population() const { return population_; }
  const std::vector<Individual>& batch() const { return batch_; }
  /// The batch member with this id, or nullptr.
  const Individual* batch_member(std::uint64_t id) const;
  const Nsga2Counters& counters() const { return counters_; }
  const Nsga2Settings& settings() const { return settings_; }
  const ProblemShape& shape() const { return shape_; }
  std::size_t cache_size() const { return cache_.size(); }

  nlohmann::json checkpoint() const;

 private:
  Nsga2(const Nsga2Settings& settings, const ProblemShape& shape);
  void make_initial_batch(const std::vector<Genome>& starts);
  void add_reevaluations();
  void make_children();
  void resolve_batch();
  const Individual& tournament(const Individual& a, const Individual& b);
  void survive();

  Nsga2Settings settings_;
  ProblemShape shape_;
  Rng rng_;
  int completed_ = 0;
  std::uint64_t next_id_ = 0;
  Nsga2Counters counters_;
  std::vector<Individual> population_;
  std::vector<Individual> batch_;
  std::vector<Individual> merged_;  ///< survive(): population + batch (capacity kept)
  std::vector<Individual> spare_;   ///< survive()'s losers, whose genomes make_children() reuses
  std::vector<char> survived_;      ///< survive(): per merged_ member
  std::vector<int> alias_of_;       ///< per batch member: index of the identical member told for it
  int alias_count_ = 0;             ///< batch members with an alias (0: tell() skips the search)
  std::vector<std::pair<std::size_t, std::size_t>> pending_;  ///< resolve_batch(): (hash, index)
  /// Every result told so far, by exact genome bits.
  std::unordered_map<HashedGenome, Result, HashedGenomeHash, HashedGenomeSameBits> cache_;
};

/// Exact text of a double ("%a"), and its parser (false if malformed).
std::string exact_double(double value);
bool parse_exact_double(const nlohmann::json& text, double& value);

}  // namespace stride::opt
