// LatencyHistogram: fixed-size histogram of durations for p50/p99/max without allocation.
// Buckets are 1 us wide up to 2 ms, then 100 us wide up to 102 ms; longer values land in the
// last bucket (the exact maximum is kept separately).
#pragma once

#include <array>
#include <cstdint>

namespace stride::fw {

class LatencyHistogram {
 public:
  /// Adds one sample [ns]; negative values count as 0. Real-time: yes.
  void add(std::int64_t ns) noexcept;
  /// Value [ns] below which `fraction` (0..1) of the samples lie (bucket upper edge); 0 if empty.
  std::int64_t percentile(double fraction) const noexcept;
  std::int64_t max() const noexcept { return max_; }
  std::uint64_t count() const noexcept { return count_; }
  double mean() const noexcept { return count_ ? static_cast<double>(sum_) / count_ : 0.0; }
  void clear() noexcept;

 private:
  static constexpr std::int64_t kFineNs = 1'000;
  static constexpr std::size_t kFineBuckets = 2'000;
  static constexpr std::int64_t kCoarseNs = 100'000;
  static constexpr std::size_t kCoarseBuckets = 1'001;
  std::array<std::uint32_t, kFineBuckets + kCoarseBuckets> buckets_{};
  std::uint64_t count_ = 0;
  std::int64_t sum_ = 0;
  std::int64_t max_ = 0;
};

}  // namespace stride::fw
