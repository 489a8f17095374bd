#include "seeds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <utility>

namespace stride::test {

Figures::Figures(std::string what, std::vector<std::uint64_t> seeds, std::vector<double> values)
    : what_(std::move(what)), seeds_(std::move(seeds)), values_(std::move(values)) {}

double Figures::quantile(double q) const {
  if (values_.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted = values_;
  std::sort(sorted.begin(), sorted.end());
  const double at = std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(at));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (at - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

int Figures::count_above(double limit) const {
  return static_cast<int>(
      std::count_if(values_.begin(), values_.end(), [&](double v) { return v > limit; }));
}

int Figures::count_at_most(double limit) const {
  return static_cast<int>(values_.size()) - count_above(limit);
}

std::string Figures::summary() const {
  char seeds[64] = "";
  if (!seeds_.empty()) {
    std::snprintf(seeds, sizeof seeds, " (%llu-%llu)",
                  static_cast<unsigned long long>(seeds_.front()),
                  static_cast<unsigned long long>(seeds_.back()));
  }
  char text[320];
  std::snprintf(text, sizeof text,
                "%s: median %.6g, IQR %.3g (%.6g..%.6g), min %.6g, max %.6g over %zu %s%s",
                what_.c_str(), median(), iqr(), quantile(0.25), quantile(0.75), min(), max(),
                values_.size(), seeds_.empty() ? "runs" : "seeds", seeds);
  return text;
}

int seed_count(int n) {
  const char* text = std::getenv("STRIDE_TEST_SEEDS");
  if (text == nullptr) return n;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  return end != text && *end == '\0' && value >= 1 ? static_cast<int>(value) : n;
}

int count_limit(double measured_share, int n) {
  return static_cast<int>(std::floor(measured_share * n + 1e-9)) - 1;
}

Seeds::Seeds(int n, std::uint64_t first) : n_(seed_count(n)), first_(first) {}

Figures Seeds::run(const std::string& what,
                   const std::function<double(std::uint64_t)>& figure) const {
  return run(std::vector<std::string>{what},
             [&](std::uint64_t seed) { return std::vector<double>{figure(seed)}; })[0];
}

std::vector<Figures> Seeds::run(
    const std::vector<std::string>& names,
    const std::function<std::vector<double>(std::uint64_t)>& episode) const {
  std::vector<std::uint64_t> seeds;
  std::vector<std::vector<double>> values(names.size());
  for (int i = 0; i < n_; ++i) {
    const std::uint64_t seed = first_ + static_cast<std::uint64_t>(i);
    const std::vector<double> figures = episode(seed);
    seeds.push_back(seed);
    std::printf("  seed %llu:", static_cast<unsigned long long>(seed));
    for (std::size_t k = 0; k < names.size(); ++k) {
      const double v = k < figures.size() ? figures[k] : std::numeric_limits<double>::quiet_NaN();
      values[k].push_back(v);
      std::printf(" %s %.6g;", names[k].c_str(), v);
    }
    std::printf("\n");
  }
  std::vector<Figures> out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    out.emplace_back(names[k], seeds, std::move(values[k]));
    std::printf("  %s\n", out.back().summary().c_str());
  }
  std::fflush(stdout);
  return out;
}

Count Seeds::count(const std::string& what, const std::function<bool(std::uint64_t)>& holds) const {
  Count c;
  for (int i = 0; i < n_; ++i) {
    const std::uint64_t seed = first_ + static_cast<std::uint64_t>(i);
    ++c.n;
    if (holds(seed)) {
      ++c.k;
    } else {
      c.failed.push_back(seed);
    }
  }
  std::printf("  %s: %d of %d seeds (%llu-%llu)", what.c_str(), c.k, c.n,
              static_cast<unsigned long long>(first_),
              static_cast<unsigned long long>(first_ + static_cast<std::uint64_t>(n_ - 1)));
  if (!c.failed.empty()) {
    std::printf("; not:");
    for (const std::uint64_t s : c.failed) std::printf(" %llu", static_cast<unsigned long long>(s));
  }
  std::printf("\n");
  std::fflush(stdout);
  return c;
}

}  // namespace stride::test
