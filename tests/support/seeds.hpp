// Seeds: a behavioural test's figures over several seeds or drawn worlds (tests/README.md), and
// their median, quartiles and counts, so that a test asserts a property of the walk, kick,
// get-up or fall rather than one trajectory of a chaotic system.
//
//   const test::Seeds seeds(5);  // seeds 1..5; STRIDE_TEST_SEEDS=20 runs 1..20 instead
//   const test::Figures speed = seeds.run("forward speed [m/s]", [](std::uint64_t seed) {
//     return walk(seed).speed;
//   });
//   EXPECT_GT(speed.median(), 0.15);  // 20 seeds: median 0.168, IQR 0.004 (seeds 1-20)
//
// Every run prints the figure per seed and its median, quartiles and IQR, so the comment beside
// a limit can be re-measured with STRIDE_TEST_SEEDS=20 and the test's filter.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace stride::test {

/// One figure over seeds: the values in seed order, with the order statistics a test asserts.
class Figures {
 public:
  Figures() = default;
  Figures(std::string what, std::vector<std::uint64_t> seeds, std::vector<double> values);

  const std::string& what() const { return what_; }
  const std::vector<std::uint64_t>& seeds() const { return seeds_; }
  const std::vector<double>& values() const { return values_; }
  std::size_t size() const { return values_.size(); }

  /// Quantile q in [0, 1], linear between order statistics (q = 0.5: the median); NaN if empty.
  double quantile(double q) const;
  double median() const { return quantile(0.5); }
  double iqr() const { return quantile(0.75) - quantile(0.25); }
  double min() const { return quantile(0.0); }
  double max() const { return quantile(1.0); }
  /// How many values are above `limit`, or at or below it.
  int count_above(double limit) const;
  int count_at_most(double limit) const;
  /// "what: median m, IQR i (q1..q3), min..max over seeds a-b".
  std::string summary() const;

 private:
  std::string what_;
  std::vector<std::uint64_t> seeds_;
  std::vector<double> values_;
};

/// A count k of N over seeds (for "stood up", "did not fall", "reached the goal").
struct Count {
  int k = 0, n = 0;
  std::vector<std::uint64_t> failed;  ///< the seeds that did not count
};

/// The seeds a behavioural test runs: `n` of them from `first` (the test's own N >= 5), or as
/// many as the environment variable STRIDE_TEST_SEEDS says (how the 20-seed figures in the
/// tests' comments are measured).
class Seeds {
 public:
  explicit Seeds(int n, std::uint64_t first = 1);

  int n() const { return n_; }
  std::uint64_t first() const { return first_; }

  /// `figure(seed)` for every seed; prints each value and the summary.
  Figures run(const std::string& what, const std::function<double(std::uint64_t)>& figure) const;
  /// Several figures of one episode per seed: `episode(seed)` returns them in the order of
  /// `names`; one Figures per name.
  std::vector<Figures> run(const std::vector<std::string>& names,
                           const std::function<std::vector<double>(std::uint64_t)>& episode) const;
  /// How many seeds `holds(seed)` is true for; prints the count and the seeds that failed.
  Count count(const std::string& what, const std::function<bool(std::uint64_t)>& holds) const;

 private:
  int n_;
  std::uint64_t first_;
};

/// The N of a test's runs: `n`, unless STRIDE_TEST_SEEDS holds a number >= 1.
int seed_count(int n);

/// The limit of a count over `n` runs whose share measured over 20 seeds was `measured_share`
/// (19 of 20: 0.95): the count expected of n runs, rounded down, less the one to spare.
int count_limit(double measured_share, int n);

}  // namespace stride::test
