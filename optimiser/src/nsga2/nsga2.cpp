// Nsga2 engine: batches, selection and variation, survival (see nsga2.hpp).
#include "stride/optimiser/nsga2/nsga2.hpp"

#include <algorithm>
#include <iterator>
#include <numeric>

#include "stride/optimiser/nsga2/operators.hpp"
#include "stride/optimiser/nsga2/sorting.hpp"

namespace stride::opt {
namespace {

/// Ranks (constraint domination) and crowding distances of a set of evaluated individuals.
void rank_and_crowd(std::vector<Individual>& group, std::vector<std::vector<int>>* fronts_out) {
  Points objectives;
  std::vector<double> violations;
  objectives.reserve(group.size());
  violations.reserve(group.size());
  // Borrow the objective vectors (moved back below) instead of copying them.
  for (Individual& ind : group) {
    objectives.push_back(std::move(ind.result.objectives));
    violations.push_back(ind.result.violation);
  }
  const std::vector<int> ranks = constrained_ranks(objectives, violations);
  std::vector<std::vector<int>> fronts = fronts_from_ranks(ranks);
  std::vector<double> distance(group.size(), 0.0);
  for (const auto& front : fronts) crowding_distances(objectives, front, distance);
  for (std::size_t i = 0; i < group.size(); ++i) {
    group[i].rank = ranks[i];
    group[i].crowding = distance[i];
    group[i].result.objectives = std::move(objectives[i]);
  }
  if (fronts_out != nullptr) *fronts_out = std::move(fronts);
}

}  // namespace

Nsga2::Nsga2(const Nsga2Settings& settings, const ProblemShape& shape)
    : settings_(settings), shape_(shape), rng_(settings.seed) {
  // One entry per evaluation at most: reserve for a whole run (capped) to avoid rehashing.
  cache_.reserve(static_cast<std::size_t>(
      std::min<std::int64_t>(std::int64_t{settings.pop_size} * settings.generations, 1 << 20)));
}

Status Nsga2::create(const Nsga2Settings& settings, const ProblemShape& shape,
                     const std::optional<Genome>& start, std::unique_ptr<Nsga2>& out) {
  return create(settings, shape, start ? std::vector<Genome>{*start} : std::vector<Genome>{}, out);
}

Status Nsga2::create(const Nsga2Settings& settings, const ProblemShape& shape,
                     const std::vector<Genome>& starts, std::unique_ptr<Nsga2>& out) {
  if (auto st = validate(settings); !st) return st;
  if (auto st = validate(shape); !st) return st;
  if (starts.size() > static_cast<std::size_t>(settings.pop_size))
    return Status::error(std::to_string(starts.size()) + " start genomes for a population of " +
                         std::to_string(settings.pop_size));
  for (std::size_t k = 0; k < starts.size(); ++k) {
    if (auto st = validate_genome(shape, starts[k]); !st)
      return starts.size() == 1
                 ? st
                 : Status::error("start " + std::to_string(k + 1) + ": " + st.message());
  }
  std::unique_ptr<Nsga2> engine(new Nsga2(settings, shape));
  engine->make_initial_batch(starts);
  out = std::move(engine);
  return {};
}

void Nsga2::make_initial_batch(const std::vector<Genome>& starts) {
  const auto n = static_cast<std::size_t>(settings_.pop_size);
  batch_.assign(n, Individual{});
  for (std::size_t i = 0; i < n; ++i) {
    Genome& g = batch_[i].genome;
    if (!starts.empty()) {
      // The starts themselves first, then mutated copies of each in turn.
      g = starts[i < starts.size() ? i : (i - starts.size()) % starts.size()];
      if (i < starts.size()) continue;
      for (std::size_t k = 0; k < g.reals.size(); ++k) {
        if (!rng_.chance(settings_.seed_mutation_fraction)) continue;
        g.reals[k] = polynomial_mutation_value(g.reals[k], shape_.reals[k].min, shape_.reals[k].max,
                                               settings_.eta_m, rng_.uniform01());
      }
      std::size_t first_bit = 0;
      for (const BinaryGene& gene : shape_.binaries) {
        const auto bits = static_cast<std::size_t>(gene.bits);
        if (rng_.chance(settings_.seed_mutation_fraction)) {
          std::uint8_t& bit = g.bits[first_bit + rng_.below(bits)];
          bit = bit != 0 ? 0 : 1;
        }
        first_bit += bits;
      }
    } else {
      g.reals.resize(shape_.reals.size());
      for (std::size_t k = 0; k < g.reals.size(); ++k) {
        const RealLimits& l = shape_.reals[k];
        g.reals[k] = std::min(l.max, l.min + rng_.uniform01() * (l.max - l.min));
      }
      g.bits.resize(static_cast<std::size_t>(shape_.total_bits()));
      for (std::uint8_t& bit : g.bits) bit = rng_.chance(0.5) ? 1 : 0;
    }
  }
  for (Individual& ind : batch_) ind.id = next_id_++;
  resolve_batch();
}

void Nsga2::resolve_batch() {
  alias_of_.assign(batch_.size(), -1);
  alias_count_ = 0;
  // Members not in the cache, sorted by (hash, index): identical genomes end up adjacent, and
  // the first of them (lowest index) is the one handed out. A sorted member vector instead of a
  // hash map: no allocation per generation.
  pending_.clear();
  for (std::size_t i = 0; i < batch_.size(); ++i) {
    Individual& ind = batch_[i];
    if (ind.evaluated) continue;
    ind.genome_hash = GenomeBitsHash{}(ind.genome);
    if (const auto hit = cache_.find(HashedGenomeRef{ind.genome_hash, &ind.genome});
        hit != cache_.end()) {
      ind.result = hit->second;
      ind.evaluated = true;
      ind.from_cache = true;
      continue;
    }
    pending_.emplace_back(ind.genome_hash, i);
  }
  std::sort(pending_.begin(), pending_.end());
  for (std::size_t k = 1; k < pending_.size(); ++k) {
    const std::size_t i = pending_[k].second;
    // Walk back over the members with the same hash to the first identical genome.
    for (std::size_t m = k; m-- > 0 && pending_[m].first == pending_[k].first;) {
      const std::size_t first = pending_[m].second;
      if (alias_of_[first] < 0 && GenomeSameBits{}(batch_[first].genome, batch_[i].genome)) {
        alias_of_[i] = static_cast<int>(first);
      }
    }
    if (alias_of_[i] >= 0) ++alias_count_;
  }
}

std::vector<Candidate> Nsga2::ask() const {
  std::vector<Candidate> out;
  out.reserve(batch_.size());
  for (std::size_t i = 0; i < batch_.size(); ++i) {
    if (batch_[i].evaluated || alias_of_[i] >= 0) continue;
    out.push_back(Candidate{batch_[i].id, batch_[i].genome, batch_draw()});
  }
  return out;
}

std::uint64_t Nsga2::batch_draw() const {
  return settings_.resample ? static_cast<std::uint64_t>(completed_) : 0;
}

const Individual* Nsga2::batch_member(std::uint64_t id) const {
  if (batch_.empty() || id < batch_.front().id) return nullptr;
  const std::uint64_t index = id - batch_.front().id;
  if (index >= batch_.size()) return nullptr;
  return &batch_[index];
}

Status Nsga2::tell(std::uint64_t id, EvaluationOutcome outcome) {
  const Individual* member = batch_member(id);
  if (member == nullptr) {
    return Status::error("genome " + std::to_string(id) + " is not in the current batch");
  }
  const auto index = static_cast<std::size_t>(member - batch_.data());
  if (alias_of_[index] >= 0) {
    return Status::error("genome " + std::to_string(id) + " was not handed out (duplicate of " +
                         std::to_string(batch_[static_cast<std::size_t>(alias_of_[index])].id) +
                         ")");
  }
  if (batch_[index].evaluated) {
    return Status::error("genome " + std::to_string(id) + " already has a result");
  }
  batch_[index].result = sanitise(shape_, std::move(outcome));
  const Result& result = batch_[index].result;
  ++counters_.evaluations;
  if (result.failed) ++counters_.failures;
  cache_.insert_or_assign(HashedGenome{batch_[index].genome_hash, batch_[index].genome}, result);
  batch_[index].evaluated = true;
  for (std::size_t j = 0; alias_count_ > 0 && j < batch_.size(); ++j) {
    if (alias_of_[j] == static_cast<int>(index)) {
      batch_[j].result = result;
      batch_[j].evaluated = true;
      batch_[j].from_cache = true;
    }
  }
  return {};
}

bool Nsga2::batch_complete() const {
  return std::all_of(batch_.begin(), batch_.end(),
                     [](const Individual& ind) { return ind.evaluated; });
}

Status Nsga2::advance() {
  if (finished()) return Status::error("the run is finished");
  if (!batch_complete()) {
    return Status::error("generation " + std::to_string(completed_ + 1) +
                         " is not complete: results are missing");
  }
  for (const Individual& ind : batch_) {
    if (ind.from_cache) ++counters_.cache_hits;
  }
  if (population_.empty()) {
    population_ = std::move(batch_);
    rank_and_crowd(population_, nullptr);
  } else if (settings_.resample) {
    population_.clear();  // re-evaluated in the batch, on the batch's draw
    survive();
  } else {
    survive();
  }
  batch_.clear();
  alias_of_.clear();
  ++completed_;
  if (!finished()) make_children();
  return {};
}

Status Nsga2::extend(int generations) {
  if (generations < settings_.generations)
    return Status::error("generations: " + std::to_string(generations) + " is below the run's " +
                         std::to_string(settings_.generations) + " (a run can only be extended)");
  const bool was_finished = finished();
  settings_.generations = generations;
  if (was_finished && !finished() && completed_ > 0) make_children();
  return {};
}

void Nsga2::add_reevaluations() {
  // The parents again, after the children, for the new draw (their old results are another
  // draw's): the cache is emptied for the same reason.
  const std::size_t children = batch_.size();
  batch_.resize(children + population_.size());
  for (std::size_t i = 0; i < population_.size(); ++i) {
    Individual& again = batch_[children + i];
    again = Individual{};
    again.genome = population_[i].genome;
    again.id = next_id_++;
  }
  cache_.clear();
}

void Nsga2::survive() {
  // merged_, population_ and spare_ keep their capacity from generation to generation, and the
  // members that do not survive lend their genome storage to the next children (spare_).
  std::vector<Individual>& merged = merged_;
  merged.clear();
  merged.reserve(population_.size() + batch_.size());
  std::move(population_.begin(), population_.end(), std::back_inserter(merged));
  std::move(batch_.begin(), batch_.end(), std::back_inserter(merged));
  std::vector<std::vector<int>> fronts;
  rank_and_crowd(merged, &fronts);
  const auto n = static_cast<std::size_t>(settings_.pop_size);
  population_.clear();
  population_.reserve(n);
  survived_.assign(merged.size(), 0);
  for (std::vector<int>& front : fronts) {
    if (population_.size() + front.size() > n) {
      // The last front that fits only partly: the least crowded members first.
      std::stable_sort(front.begin(), front.end(), [&](int a, int b) {
        return merged[static_cast<std::size_t>(a)].crowding >
               merged[static_cast<std::size_t>(b)].crowding;
      });
      front.resize(n - population_.size());
    }
    for (const int i : front) {
      population_.push_back(std::move(merged[static_cast<std::size_t>(i)]));
      survived_[static_cast<std::size_t>(i)] = 1;
    }
    if (population_.size() == n) break;
  }
  spare_.clear();
  for (std::size_t i = 0; i < merged.size(); ++i)
    if (survived_[i] == 0) spare_.push_back(std::move(merged[i]));
}

const Individual& Nsga2::tournament(const Individual& a, const Individual& b) {
  if (a.rank != b.rank) return a.rank < b.rank ? a : b;
  if (a.crowding > b.crowding) return a;
  if (b.crowding > a.crowding) return b;
  return rng_.chance(0.5) ? a : b;
}

void Nsga2::make_children() {
  const auto n = static_cast<std::size_t>(settings_.pop_size);
  std::vector<std::size_t> order_a(n);
  std::vector<std::size_t> order_b(n);
  std::iota(order_a.begin(), order_a.end(), std::size_t{0});
  std::iota(order_b.begin(), order_b.end(), std::size_t{0});
  for (auto* order : {&order_a, &order_b}) {
    for (std::size_t i = n - 1; i > 0; --i) std::swap((*order)[i], (*order)[rng_.below(i + 1)]);
  }
  // Children reuse the genome storage of last generation's losers (spare_) where there is some.
  batch_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    batch_[i] = Individual{};
    if (i < spare_.size()) batch_[i].genome = std::move(spare_[i].genome);
  }
  spare_.clear();
  auto cross = [&](const Individual& p1, const Individual& p2, Individual& c1, Individual& c2) {
    sbx_crossover(p1.genome.reals, p2.genome.reals, shape_.reals, settings_.real_cross_prob,
                  settings_.eta_c, rng_, c1.genome.reals, c2.genome.reals);
    binary_crossover(p1.genome.bits, p2.genome.bits, shape_.binaries, settings_.bin_cross_prob,
                     rng_, c1.genome.bits, c2.genome.bits);
  };
  // Groups of four: 8 parents (4 from each permutation), 4 tournaments, 2 crossovers.
  for (std::size_t i = 0; i < n; i += 4) {
    for (std::size_t half = 0; half < 2; ++half) {
      const std::vector<std::size_t>& order = half == 0 ? order_a : order_b;
      const Individual& p1 = tournament(population_[order[i]], population_[order[i + 1]]);
      const Individual& p2 = tournament(population_[order[i + 2]], population_[order[i + 3]]);
      cross(p1, p2, batch_[i + 2 * half], batch_[i + 2 * half + 1]);
    }
  }
  for (Individual& child : batch_) {
    polynomial_mutation(child.genome.reals, shape_.reals, settings_.real_mut_prob, settings_.eta_m,
                        rng_);
    bit_flip_mutation(child.genome.bits, settings_.bin_mut_prob, rng_);
    child.id = next_id_++;
  }
  if (settings_.resample) add_reevaluations();
  resolve_batch();
}

}  // namespace stride::opt
