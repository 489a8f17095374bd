// Genome helpers: binary decoding, cache keys, bit text.
#include "stride/optimiser/nsga2/genome.hpp"

#include <cstring>

namespace stride::opt {

int ProblemShape::total_bits() const {
  int total = 0;
  for (const BinaryGene& b : binaries) total += b.bits;
  return total;
}

std::vector<double> decode_binaries(const ProblemShape& shape, const Genome& genome) {
  std::vector<double> values;
  values.reserve(shape.binaries.size());
  std::size_t pos = 0;
  for (const BinaryGene& gene : shape.binaries) {
    std::uint64_t word = 0;
    for (int b = 0; b < gene.bits; ++b) {
      word = (word << 1) | (pos < genome.bits.size() && genome.bits[pos] != 0 ? 1u : 0u);
      ++pos;
    }
    const double top = static_cast<double>((std::uint64_t{1} << gene.bits) - 1);
    values.push_back(gene.min + (gene.max - gene.min) * static_cast<double>(word) / top);
  }
  return values;
}

std::string genome_key(const Genome& genome) {
  std::string key(genome.reals.size() * sizeof(double) + genome.bits.size(), '\0');
  if (!genome.reals.empty()) {
    std::memcpy(key.data(), genome.reals.data(), genome.reals.size() * sizeof(double));
  }
  std::size_t pos = genome.reals.size() * sizeof(double);
  for (const std::uint8_t bit : genome.bits) key[pos++] = static_cast<char>(bit != 0 ? 1 : 0);
  return key;
}

std::string bits_to_text(const std::vector<std::uint8_t>& bits) {
  std::string text;
  text.reserve(bits.size());
  for (const std::uint8_t bit : bits) text.push_back(bit != 0 ? '1' : '0');
  return text;
}

bool bits_from_text(const std::string& text, std::vector<std::uint8_t>& bits) {
  bits.clear();
  for (const char c : text) {
    if (c != '0' && c != '1') return false;
    bits.push_back(c == '1' ? 1 : 0);
  }
  return true;
}

}  // namespace stride::opt
