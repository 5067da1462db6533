// Statistical sanity and stream properties of pgmcl/common/random.hpp. Tolerances are 5
// standard errors; chi-square tests use the stated upper 0.1% points.

#include "pgmcl/common/random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

namespace pgmcl {
namespace {

constexpr int kDraws = 200000;

TEST(Random, ReproducibleAndSeedDependent) {
  Rng a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t va = a.next_u64();
    EXPECT_EQ(va, b.next_u64());
    differs |= va != c.next_u64();
  }
  EXPECT_TRUE(differs);
  Rng r(7);
  const double first = r.normal();
  r.reseed(7);  // reseeding also drops the cached second normal
  EXPECT_EQ(r.normal(), first);
}

TEST(Random, BlockStreamsDifferAndAreReproducible) {
  std::set<std::uint64_t> seen;
  for (std::uint64_t seed : {1u, 2u}) {
    for (std::uint64_t step = 0; step < 10; ++step) {
      for (std::uint64_t block = 0; block < 200; ++block) {
        Rng s = Rng::for_block(seed, step, block);
        Rng again = Rng::for_block(seed, step, block);
        const std::uint64_t v = s.next_u64();
        EXPECT_EQ(v, again.next_u64());
        seen.insert(v);
      }
    }
  }
  EXPECT_EQ(seen.size(), 2u * 10u * 200u);  // every (seed, step, block) starts differently
}

TEST(Random, NeighbouringBlocksAreUncorrelated) {
  constexpr int kN = 20000;
  for (std::uint64_t block = 0; block < 8; ++block) {
    Rng s = Rng::for_block(9, 3, block), t = Rng::for_block(9, 3, block + 1);
    double sum = 0.0;
    for (int i = 0; i < kN; ++i) sum += (s.uniform() - 0.5) * (t.uniform() - 0.5);
    // Correlation of two independent U(0,1): the mean of the product has sd 1/(12 sqrt(n)).
    EXPECT_LT(std::abs(sum / kN), 5.0 / (12.0 * std::sqrt(double{kN}))) << block;
  }
}

TEST(Random, UniformRangeMeanAndHistogram) {
  Rng r(11);
  constexpr int kBins = 20;
  std::vector<double> counts(kBins, 0.0);
  double sum = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    counts[static_cast<int>(u * kBins)] += 1.0;
  }
  EXPECT_NEAR(sum / kDraws, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / kDraws));
  double chi2 = 0.0;
  const double e = static_cast<double>(kDraws) / kBins;
  for (const double c : counts) chi2 += (c - e) * (c - e) / e;
  EXPECT_LT(chi2, 43.820);  // chi-square(19), upper 0.1%
  for (int i = 0; i < 1000; ++i) {
    const double v = r.uniform(-2.0, 3.0);
    EXPECT_GE(v, -2.0);
    EXPECT_LT(v, 3.0);
  }
}

TEST(Random, BelowIsUniformOverItsRange) {
  Rng r(12);
  constexpr std::uint64_t kN = 7;
  std::vector<double> counts(kN, 0.0);
  for (int i = 0; i < kDraws; ++i) {
    const std::uint64_t v = r.below(kN);
    ASSERT_LT(v, kN);
    counts[v] += 1.0;
  }
  double chi2 = 0.0;
  const double e = static_cast<double>(kDraws) / kN;
  for (const double c : counts) chi2 += (c - e) * (c - e) / e;
  EXPECT_LT(chi2, 22.458);  // chi-square(6), upper 0.1%
  EXPECT_EQ(r.below(1), 0u);
}

TEST(Random, NormalMomentsAndScaling) {
  Rng r(13);
  double s1 = 0.0, s2 = 0.0, s4 = 0.0;
  for (int i = 0; i < kDraws; ++i) {
    const double z = r.normal();
    s1 += z;
    s2 += z * z;
    s4 += z * z * z * z;
  }
  const double n = kDraws;
  EXPECT_NEAR(s1 / n, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(s2 / n, 1.0, 5.0 * std::sqrt(2.0 / n));   // Var(z^2) = 2
  EXPECT_NEAR(s4 / n, 3.0, 5.0 * std::sqrt(96.0 / n));  // Var(z^4) = 105 - 9
  // P(|z| < 1.959964) = 0.95.
  int inside = 0;
  for (int i = 0; i < kDraws; ++i) inside += std::abs(r.normal()) < 1.959964 ? 1 : 0;
  EXPECT_NEAR(inside / n, 0.95, 5.0 * std::sqrt(0.95 * 0.05 / n));

  Rng a(14), b(14);
  for (int i = 0; i < 100; ++i) EXPECT_DOUBLE_EQ(a.normal(2.5), 2.5 * b.normal());
  Rng c(15), d(15);
  EXPECT_EQ(c.normal(0.0), 0.0);
  EXPECT_EQ(c.normal(-1.0), 0.0);
  EXPECT_EQ(c.next_u64(), d.next_u64());  // sigma <= 0 draws nothing
}

}  // namespace
}  // namespace pgmcl
