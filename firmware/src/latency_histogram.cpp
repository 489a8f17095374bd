// LatencyHistogram implementation.
#include "stride/firmware/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace stride::fw {

void LatencyHistogram::add(std::int64_t ns) noexcept {
  ns = std::max<std::int64_t>(ns, 0);
  std::size_t bucket;
  if (ns < kFineNs * static_cast<std::int64_t>(kFineBuckets)) {
    bucket = static_cast<std::size_t>(ns / kFineNs);
  } else {
    const auto coarse = static_cast<std::size_t>(
        (ns - kFineNs * static_cast<std::int64_t>(kFineBuckets)) / kCoarseNs);
    bucket = kFineBuckets + std::min(coarse, kCoarseBuckets - 1);
  }
  ++buckets_[bucket];
  ++count_;
  sum_ += ns;
  max_ = std::max(max_, ns);
}

std::int64_t LatencyHistogram::percentile(double fraction) const noexcept {
  if (count_ == 0) return 0;
  const auto target =
      static_cast<std::uint64_t>(std::ceil(std::clamp(fraction, 0.0, 1.0) * count_));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < buckets_.size(); ++i) {
    seen += buckets_[i];
    if (seen >= std::max<std::uint64_t>(target, 1)) {
      const std::int64_t upper =
          i < kFineBuckets ? static_cast<std::int64_t>(i + 1) * kFineNs
                           : kFineNs * static_cast<std::int64_t>(kFineBuckets) +
                                 static_cast<std::int64_t>(i - kFineBuckets + 1) * kCoarseNs;
      return std::min(upper, max_);
    }
  }
  return max_;
}

void LatencyHistogram::clear() noexcept {
  buckets_.fill(0);
  count_ = 0;
  sum_ = 0;
  max_ = 0;
}

}  // namespace stride::fw
