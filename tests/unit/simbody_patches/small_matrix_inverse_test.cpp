// Simbody's small-matrix inverse (SimTK::Mat<M,M>::invert(), which the articulated-body
// recursion calls for every free body's 6x6 inertia) against reference LAPACK's dgetrf and
// dgetri called directly: the same bits for every finite input, and a singular matrix throws
// exactly when LAPACK reports it singular. toolchain/simbody-patches/0001 replaces those
// LAPACK calls with inline code that must keep every simulation result unchanged; with
// Debian's unpatched Simbody this checks the LAPACK path itself.
#include <gtest/gtest.h>

#include <SimTKcommon.h>

#include <cstdint>
#include <cstring>
#include <random>

namespace {

enum class Kind { kDense, kSparse, kWideRange, kSpatialInertia, kNearlySingular, kSingular };

template <int N>
SimTK::Mat<N, N> random_matrix(std::mt19937_64& rng, Kind kind) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SimTK::Mat<N, N> m;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      double v = u(rng);
      if (kind == Kind::kSparse && u(rng) < 0.0) v = 0.0;  // half the entries exactly zero
      if (kind == Kind::kWideRange) v = std::ldexp(v, static_cast<int>(u(rng) * 60));
      m(i, j) = v;
    }
  if (kind == Kind::kSpatialInertia) {  // symmetric positive definite with structural zeros
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < i; ++j) m(j, i) = m(i, j) = (i + j) % 3 == 0 ? 0.0 : m(i, j);
    for (int i = 0; i < N; ++i) m(i, i) = N + std::abs(m(i, i));
  }
  if (kind == Kind::kNearlySingular) m.col(N - 1) = m.col(0);             // singular up to rounding
  if (kind == Kind::kSingular) m.col(static_cast<int>(rng() % N)) = 0.0;  // exactly
  return m;
}

struct Tally {
  int compared = 0, singular = 0, differing = 0, wrong_throw = 0;
};

template <int N>
void compare(std::mt19937_64& rng, Kind kind, int count, Tally& tally) {
  for (int t = 0; t < count; ++t) {
    const SimTK::Mat<N, N> m = random_matrix<N>(rng, kind);
    double lapack[N * N];  // column-major
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) lapack[i + j * N] = m(i, j);
    int pivots[N], info = 0;
    double work[N];
    dgetrf_(N, N, lapack, N, pivots, info);
    if (info == 0) dgetri_(N, lapack, N, pivots, work, N, info);

    SimTK::Mat<N, N> simbody;
    bool threw = false;
    try {
      simbody = m.invert();
    } catch (const std::exception&) {
      threw = true;
    }
    if (threw != (info != 0)) {
      ++tally.wrong_throw;
      continue;
    }
    if (threw) {
      ++tally.singular;
      continue;
    }
    ++tally.compared;
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        if (std::memcmp(&lapack[i + j * N], &simbody(i, j), sizeof(double)) != 0) {
          ++tally.differing;
          i = j = N;  // count each matrix once
        }
  }
}

template <int N>
Tally compare_all_kinds(std::uint64_t seed, int per_kind) {
  std::mt19937_64 rng(seed);
  Tally tally;
  for (Kind kind : {Kind::kDense, Kind::kSparse, Kind::kWideRange, Kind::kSpatialInertia,
                    Kind::kNearlySingular, Kind::kSingular})
    compare<N>(rng, kind, per_kind, tally);
  return tally;
}

TEST(SimbodyInverse, SixBySixIsBitIdenticalToReferenceLapack) {
  const Tally t = compare_all_kinds<6>(1, 4000);
  EXPECT_EQ(t.wrong_throw, 0);
  EXPECT_EQ(t.differing, 0) << "of " << t.compared << " inverses";
  EXPECT_GE(t.compared, 12000);  // dense, wide-range and spatial inertias are invertible
  EXPECT_GE(t.singular, 4000);   // every kSingular matrix, and no fewer
}

TEST(SimbodyInverse, OtherLapackSizesAreBitIdenticalToReferenceLapack) {
  for (const Tally& t : {compare_all_kinds<4>(2, 1000), compare_all_kinds<5>(3, 1000),
                         compare_all_kinds<7>(4, 1000), compare_all_kinds<12>(5, 500)}) {
    EXPECT_EQ(t.wrong_throw, 0);
    EXPECT_EQ(t.differing, 0) << "of " << t.compared << " inverses";
    EXPECT_GT(t.compared, 0);
  }
}

}  // namespace
