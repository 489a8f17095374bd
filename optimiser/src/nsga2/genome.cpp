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

std::size_t GenomeBitsHash::operator()(const Genome& genome) const noexcept {
  // Each 64-bit word (a double's bit pattern, or 64 packed bits) is rotated by its position and
  // multiplied by an odd constant; the products are summed (independent multiplies, so the CPU
  // overlaps them) and the sum goes through the splitmix64 finaliser. A few ns per gene and no
  // allocation (hashing genome_key's string cost a heap allocation per lookup).
  constexpr std::uint64_t kMul = 0x9E3779B97F4A7C15ULL;
  std::uint64_t h = genome.reals.size() * 0x100000001B3ULL + genome.bits.size();
  unsigned position = 0;
  auto mix_in = [&h, &position](std::uint64_t word) {
    const unsigned r = (position++ * 7u) % 64u;
    h += (r == 0 ? word : (word << r) | (word >> (64u - r))) * kMul + position;
  };
  for (const double value : genome.reals) {
    std::uint64_t word = 0;
    std::memcpy(&word, &value, sizeof word);
    mix_in(word);
  }
  std::uint64_t packed = 0;
  std::size_t count = 0;
  for (const std::uint8_t bit : genome.bits) {
    packed = (packed << 1) | (bit != 0 ? 1u : 0u);
    if (++count % 64 == 0) mix_in(packed);
  }
  if (count % 64 != 0) mix_in(packed);
  h ^= h >> 30;
  h *= 0xBF58476D1CE4E5B9ULL;
  h ^= h >> 27;
  h *= 0x94D049BB133111EBULL;
  h ^= h >> 31;
  return static_cast<std::size_t>(h);
}

bool GenomeSameBits::operator()(const Genome& a, const Genome& b) const noexcept {
  if (a.reals.size() != b.reals.size() || a.bits.size() != b.bits.size()) return false;
  if (!a.reals.empty() &&
      std::memcmp(a.reals.data(), b.reals.data(), a.reals.size() * sizeof(double)) != 0) {
    return false;
  }
  for (std::size_t i = 0; i < a.bits.size(); ++i) {
    if ((a.bits[i] != 0) != (b.bits[i] != 0)) return false;
  }
  return true;
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
