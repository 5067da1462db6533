#include "pgmcl/mcl/resampling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace pgmcl {
namespace {

std::vector<double> random_weights(std::size_t n, Rng& rng, bool normalise = true) {
  std::vector<double> w(n);
  for (auto& x : w) x = rng.uniform() * rng.uniform();  // skewed towards small weights
  if (normalise) {
    const double s = std::accumulate(w.begin(), w.end(), 0.0);
    for (auto& x : w) x /= s;
  }
  return w;
}

std::vector<int> counts_of(const std::vector<std::uint32_t>& idx, std::size_t n) {
  std::vector<int> c(n, 0);
  for (const auto i : idx) ++c.at(i);
  return c;
}

/// Each particle's copies lie in {floor(n w_i / W), ceil(n w_i / W)} (up to round-off on
/// the expected count), and the copies add up to n_out.
void expect_floor_ceil(const std::vector<double>& w, std::size_t n_out,
                       const std::vector<std::uint32_t>& idx) {
  ASSERT_EQ(idx.size(), n_out);
  EXPECT_TRUE(std::is_sorted(idx.begin(), idx.end()));
  const double total = std::accumulate(w.begin(), w.end(), 0.0);
  const auto c = counts_of(idx, w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double expected = static_cast<double>(n_out) * w[i] / total;
    EXPECT_GE(c[i], std::floor(expected - 1e-9)) << "particle " << i;
    EXPECT_LE(c[i], std::ceil(expected + 1e-9)) << "particle " << i;
  }
}

TEST(Resampling, ChiSquareUnbiased) {
  // Copies summed over R independent resamplings are compared with R n w_i by Pearson's
  // statistic. Under multinomial draws it is chi-square with K - 1 = 19 degrees of freedom;
  // systematic resampling has smaller per-particle variance, so the test is conservative
  // (it cannot reject a correct implementation more often than stated) but a biased
  // offset or an off-by-one in the walk shifts every run and is caught.
  constexpr std::size_t kK = 20, kN = 50;
  constexpr int kRuns = 4000;
  constexpr double kCritical = 43.820;  // chi-square(19) upper 0.1% point
  Rng wrng(5);
  const auto w = random_weights(kK, wrng);
  Rng rng(6);
  std::vector<std::uint32_t> idx;
  std::vector<double> observed(kK, 0.0);
  for (int r = 0; r < kRuns; ++r) {
    systematic_resample(w, kN, rng, idx);
    for (const auto i : idx) observed[i] += 1.0;
  }
  double chi2 = 0.0;
  for (std::size_t i = 0; i < kK; ++i) {
    const double e = kRuns * static_cast<double>(kN) * w[i];
    chi2 += (observed[i] - e) * (observed[i] - e) / e;
  }
  EXPECT_LT(chi2, kCritical);
}

TEST(Resampling, CopiesAreFloorOrCeilOfExpected) {
  Rng rng(7);
  std::vector<std::uint32_t> idx;
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 1 + rng.below(300);
    const auto w = random_weights(n, rng, trial % 2 == 0);  // also unnormalised weights
    systematic_resample(w, n, rng, idx);
    expect_floor_ceil(w, n, idx);
  }
}

TEST(Resampling, OutputSizeDifferentFromInput) {
  Rng rng(8);
  const auto w = random_weights(100, rng);
  std::vector<std::uint32_t> idx;
  for (const std::size_t n_out : {1u, 7u, 33u, 250u, 1000u}) {
    systematic_resample(w, n_out, rng, idx);
    expect_floor_ceil(w, n_out, idx);
  }
  systematic_resample(w, 0, rng, idx);
  EXPECT_TRUE(idx.empty());
}

TEST(Resampling, SingleParticle) {
  Rng rng(9);
  std::vector<std::uint32_t> idx;
  systematic_resample(std::vector<double>{0.3}, 1, rng, idx);
  EXPECT_EQ(idx, std::vector<std::uint32_t>{0});
  systematic_resample(std::vector<double>{1.0}, 5, rng, idx);
  EXPECT_EQ(idx, std::vector<std::uint32_t>(5, 0));
}

TEST(Resampling, ZeroWeightsAreNeverDrawn) {
  Rng rng(10);
  // Zeros at the start, the middle and the end (the end tests the round-off clamp).
  std::vector<double> w{0.0, 0.0, 0.1, 0.0, 0.2, 0.0, 0.7, 0.0, 0.0};
  std::vector<std::uint32_t> idx;
  for (int r = 0; r < 1000; ++r) {
    systematic_resample(w, 1 + rng.below(40), rng, idx);
    for (const auto i : idx) EXPECT_GT(w[i], 0.0) << "index " << i;
  }
}

TEST(Resampling, ReproducibleForASeed) {
  Rng wrng(11);
  const auto w = random_weights(64, wrng);
  std::vector<std::uint32_t> a, b;
  Rng r1(12), r2(12);
  systematic_resample(w, 64, r1, a);
  systematic_resample(w, 64, r2, b);
  EXPECT_EQ(a, b);
}

TEST(Resampling, RejectsBadWeights) {
  Rng rng(13);
  std::vector<std::uint32_t> idx;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(systematic_resample(std::vector<double>{0.5, -0.1}, 2, rng, idx),
               std::invalid_argument);
  EXPECT_THROW(systematic_resample(std::vector<double>{0.5, nan}, 2, rng, idx),
               std::invalid_argument);
  EXPECT_THROW(systematic_resample(std::vector<double>{0.5, inf}, 2, rng, idx),
               std::invalid_argument);
  EXPECT_THROW(systematic_resample(std::vector<double>{0.0, 0.0}, 2, rng, idx),
               std::invalid_argument);
  EXPECT_THROW(systematic_resample(std::vector<double>{}, 2, rng, idx), std::invalid_argument);
}

TEST(Resampling, GatherAppliesIndices) {
  const std::vector<float> x{10.f, 11.f, 12.f, 13.f};
  const std::vector<std::uint32_t> idx{3, 3, 0, 2, 1};
  std::vector<float> out(idx.size());
  gather<float>(x, idx, out);
  EXPECT_EQ(out, (std::vector<float>{13.f, 13.f, 10.f, 12.f, 11.f}));
  std::vector<float> wrong(2);
  EXPECT_THROW(gather<float>(x, idx, wrong), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl
