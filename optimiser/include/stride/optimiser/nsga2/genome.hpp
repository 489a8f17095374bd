// Genomes and the shape of a problem: real genes with [min, max] limits, binary genes of a given
// number of bits decoded linearly onto [min, max], and the numbers of objectives and constraints.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stride::opt {

/// Limits of one real gene: min < max, both finite.
struct RealLimits {
  double min = 0.0;
  double max = 1.0;
};

/// One binary gene: `bits` bits (1..52), most significant first, decoded onto [min, max].
struct BinaryGene {
  int bits = 1;
  double min = 0.0;
  double max = 1.0;
};

/// What NSGA-II must know about a problem (Appendix B's objectives, constraints, realVars,
/// realLimits, binVars, binBits, binLimits).
struct ProblemShape {
  std::vector<RealLimits> reals;
  std::vector<BinaryGene> binaries;
  int objectives = 2;
  int constraints = 0;

  int total_bits() const;
};

/// A candidate solution: real genes, and the bits of all binary genes concatenated (each 0/1).
struct Genome {
  std::vector<double> reals;
  std::vector<std::uint8_t> bits;

  bool operator==(const Genome&) const = default;
};

/// Decodes the binary genes of `genome` onto their limits, one value per binary gene.
std::vector<double> decode_binaries(const ProblemShape& shape, const Genome& genome);

/// The exact bits of a genome as a byte string (a set key for reports).
std::string genome_key(const Genome& genome);

/// Hash of a genome's exact bits (the doubles' bit patterns and the bits), for hashed containers.
struct GenomeBitsHash {
  std::size_t operator()(const Genome& genome) const noexcept;
};
/// True when two genomes have the same bits: unlike ==, 0.0 and -0.0 differ (as in genome_key).
struct GenomeSameBits {
  bool operator()(const Genome& a, const Genome& b) const noexcept;
};

/// A genome with its GenomeBitsHash, computed once: the key of the evaluation cache.
struct HashedGenome {
  std::size_t hash = 0;
  Genome genome;
};
/// A borrowed genome with its hash: looks the cache up without copying the genome.
struct HashedGenomeRef {
  std::size_t hash = 0;
  const Genome* genome = nullptr;
};
/// Transparent hash and equality over HashedGenome and HashedGenomeRef (the stored hash is used,
/// never recomputed).
struct HashedGenomeHash {
  using is_transparent = void;
  std::size_t operator()(const HashedGenome& g) const noexcept { return g.hash; }
  std::size_t operator()(const HashedGenomeRef& g) const noexcept { return g.hash; }
};
struct HashedGenomeSameBits {
  using is_transparent = void;
  static const Genome& of(const HashedGenome& g) { return g.genome; }
  static const Genome& of(const HashedGenomeRef& g) { return *g.genome; }
  template <class A, class B>
  bool operator()(const A& a, const B& b) const noexcept {
    return a.hash == b.hash && GenomeSameBits{}(of(a), of(b));
  }
};

/// "0101..." text of the bits (used in logs and checkpoints).
std::string bits_to_text(const std::vector<std::uint8_t>& bits);
/// Parses bits_to_text's output; false if a character is not 0 or 1.
bool bits_from_text(const std::string& text, std::vector<std::uint8_t>& bits);

}  // namespace stride::opt
