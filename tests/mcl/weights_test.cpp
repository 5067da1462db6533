#include "pgmcl/mcl/weights.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "pgmcl/common/random.hpp"

namespace pgmcl {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double sum_of(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

TEST(Weights, LogSumExpSmallAndHuge) {
  const std::vector<double> small{std::log(1.0), std::log(2.0), std::log(3.0)};
  EXPECT_NEAR(log_sum_exp(small), std::log(6.0), 1e-15);
  // exp(1000) overflows; the shifted form does not.
  const std::vector<double> huge{1000.0, 1000.0};
  EXPECT_NEAR(log_sum_exp(huge), 1000.0 + std::log(2.0), 1e-12);
  EXPECT_EQ(log_sum_exp(std::vector<double>{}), -kInf);
  EXPECT_EQ(log_sum_exp(std::vector<double>{-kInf, -kInf}), -kInf);
  EXPECT_EQ(log_sum_exp(std::vector<double>{0.0, kInf}), kInf);
  EXPECT_NEAR(log_sum_exp(std::vector<double>{kNaN, 0.0, -kInf}), 0.0, 1e-15);
}

TEST(Weights, SumOf1081BeamsDoesNotUnderflow) {
  // Each particle's log weight is a sum of 1081 per-beam log-likelihoods of about -92,
  // so around -1e5 with a spread of +-50: exp() of any of them is 0 in double.
  constexpr int kParticles = 2000;
  constexpr int kBeams = 1081;
  Rng rng(3);
  std::vector<double> log_w(kParticles), w(kParticles);
  for (auto& l : log_w) {
    double s = 0.0;
    for (int b = 0; b < kBeams; ++b) s += -92.5 + 1.5 * rng.normal();
    l = s;
  }
  ASSERT_EQ(std::exp(log_w[0]), 0.0);
  const std::vector<double> in = log_w;
  // Oracle: shift by a round constant so the values are O(50) and sum exp() in long double.
  const double c = -1e5;
  long double oracle_sum = 0.0L;
  for (const double l : in) oracle_sum += std::exp(static_cast<long double>(l - c));
  const double oracle_lse = c + static_cast<double>(std::log(oracle_sum));

  const double lse = normalise_log_weights(log_w, w);
  EXPECT_NEAR(lse, oracle_lse, 1e-9 * std::abs(oracle_lse));
  EXPECT_NEAR(sum_of(w), 1.0, 1e-12);
  for (int i = 0; i < kParticles; ++i) {
    ASSERT_TRUE(std::isfinite(w[i]) && std::isfinite(log_w[i]));
    const double expected =
        static_cast<double>(std::exp(static_cast<long double>(in[i] - c)) / oracle_sum);
    EXPECT_NEAR(w[i], expected, 1e-12 + 1e-9 * expected);
    EXPECT_NEAR(log_w[i], in[i] - lse, 1e-9);
  }
  EXPECT_GT(effective_sample_size(w), 1.0);
}

TEST(Weights, AllEqualGiveUniform) {
  std::vector<double> log_w(500, -12345.678), w(500);
  const double lse = normalise_log_weights(log_w, w);
  EXPECT_NEAR(lse, -12345.678 + std::log(500.0), 1e-9);
  for (int i = 0; i < 500; ++i) {
    EXPECT_NEAR(w[i], 1.0 / 500, 1e-15);
    EXPECT_NEAR(log_w[i], -std::log(500.0), 1e-12);
  }
  EXPECT_NEAR(effective_sample_size(w), 500.0, 1e-9);
}

TEST(Weights, OneParticleCarriesEverything) {
  std::vector<double> log_w(100, -1000.0), w(100);
  log_w[37] = 0.0;
  const double lse = normalise_log_weights(log_w, w);
  EXPECT_NEAR(lse, 0.0, 1e-15);  // the others add exp(-1000) = 0
  EXPECT_EQ(w[37], 1.0);
  EXPECT_EQ(w[0], 0.0);
  EXPECT_NEAR(log_w[0], -1000.0, 1e-12);  // still finite in log space
  EXPECT_EQ(effective_sample_size(w), 1.0);
}

TEST(Weights, MinusInfinityEntriesGetZeroWeight) {
  std::vector<double> log_w{-kInf, std::log(0.25), -kInf, std::log(0.75), kNaN}, w(5);
  const double lse = normalise_log_weights(log_w, w);
  EXPECT_NEAR(lse, 0.0, 1e-15);
  EXPECT_EQ(w[0], 0.0);
  EXPECT_EQ(w[2], 0.0);
  EXPECT_EQ(w[4], 0.0);  // NaN counts as -inf
  EXPECT_NEAR(w[1], 0.25, 1e-15);
  EXPECT_NEAR(w[3], 0.75, 1e-15);
  EXPECT_EQ(log_w[0], -kInf);
  EXPECT_EQ(log_w[4], -kInf);
  EXPECT_NEAR(log_w[3], std::log(0.75), 1e-15);
}

TEST(Weights, AllMinusInfinityFallsBackToUniform) {
  std::vector<double> log_w(8, -kInf), w(8, 123.0);
  log_w[3] = kNaN;
  const double lse = normalise_log_weights(log_w, w);
  EXPECT_EQ(lse, -kInf);  // the documented flag
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(w[i], 0.125);
    EXPECT_NEAR(log_w[i], -std::log(8.0), 1e-15);
  }
  EXPECT_NEAR(effective_sample_size(w), 8.0, 1e-12);
}

TEST(Weights, PlusInfinityEntriesShareTheMass) {
  std::vector<double> log_w{0.0, kInf, -3.0, kInf}, w(4);
  EXPECT_EQ(normalise_log_weights(log_w, w), kInf);
  EXPECT_EQ(w[0], 0.0);
  EXPECT_EQ(w[1], 0.5);
  EXPECT_EQ(w[3], 0.5);
  EXPECT_EQ(log_w[0], -kInf);
}

TEST(Weights, SizeMismatchThrows) {
  std::vector<double> log_w(4, 0.0), w(3);
  EXPECT_THROW(normalise_log_weights(log_w, w), std::invalid_argument);
  std::vector<double> none;
  EXPECT_EQ(normalise_log_weights(none, none), -kInf);
}

TEST(Weights, EffectiveSampleSize) {
  EXPECT_NEAR(effective_sample_size(std::vector<double>{0.5, 0.25, 0.25}), 1.0 / 0.375, 1e-12);
  // Scale-free: unnormalised weights give the same figure.
  EXPECT_NEAR(effective_sample_size(std::vector<double>{2.0, 1.0, 1.0}), 1.0 / 0.375, 1e-12);
  EXPECT_EQ(effective_sample_size(std::vector<double>{}), 0.0);
  EXPECT_EQ(effective_sample_size(std::vector<double>{0.0, 0.0}), 0.0);
}

}  // namespace
}  // namespace pgmcl
