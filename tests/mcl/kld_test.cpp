#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <tuple>

#include "pgmcl/common/random.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/mcl/kld_sampling.hpp"

namespace pgmcl {
namespace {

constexpr double kPi = std::numbers::pi;

double normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

TEST(NormalQuantile, KnownValues) {
  // Standard table values (to the digits given).
  EXPECT_NEAR(normal_quantile(0.975), 1.959963984540054, 1e-12);
  EXPECT_NEAR(normal_quantile(0.99), 2.326347874040841, 1e-12);
  EXPECT_NEAR(normal_quantile(0.95), 1.644853626951472, 1e-12);
  EXPECT_NEAR(normal_quantile(0.9), 1.281551565544601, 1e-12);
  EXPECT_NEAR(normal_quantile(0.999), 3.090232306167813, 1e-12);
  EXPECT_EQ(normal_quantile(0.5), 0.0);
  EXPECT_EQ(normal_quantile(0.0), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(normal_quantile(1.0), std::numeric_limits<double>::infinity());
}

/// Error of x as a quantile of p, to first order: (Phi(x) - p) / phi(x).
double quantile_error(double x, double p) {
  const double pdf = std::exp(-0.5 * x * x) / std::sqrt(2.0 * kPi);
  return (normal_cdf(x) - p) / pdf;
}

TEST(NormalQuantile, InvertsTheCdfAndIsSymmetric) {
  // Oracle: Phi via erfc. Covers Acklam's central and tail regions and the region seam at
  // p = 0.02425. Errors are measured on x (relative to max(1, |x|)): in the far tail a
  // one-ulp change of x moves Phi(x) by ~x^2 ulps, so p-space bounds would test rounding.
  for (double p = 1e-300; p < 0.5; p *= 1.7) {
    const double x = normal_quantile(p);
    EXPECT_LT(std::abs(quantile_error(x, p)), 1e-14 * std::max(1.0, std::abs(x))) << p;
  }
  for (double p = 0.001; p < 1.0; p += 0.001) {
    const double x = normal_quantile(p);
    EXPECT_LT(std::abs(quantile_error(x, p)), 1e-14 * std::max(1.0, std::abs(x))) << p;
    EXPECT_NEAR(normal_quantile(1.0 - p), -x, 1e-12) << "p = " << p;
  }
  EXPECT_TRUE(std::isfinite(normal_quantile(1e-320)));  // subnormal p: no overflow
  EXPECT_LT(normal_quantile(1e-320), normal_quantile(1e-300));
  // Monotone.
  double prev = -std::numeric_limits<double>::infinity();
  for (double p = 0.0005; p < 1.0; p += 0.0005) {
    const double x = normal_quantile(p);
    EXPECT_GT(x, prev);
    prev = x;
  }
}

TEST(NormalQuantile, RejectsOutsideUnitInterval) {
  EXPECT_THROW((void)normal_quantile(-0.1), std::invalid_argument);
  EXPECT_THROW((void)normal_quantile(1.5), std::invalid_argument);
  EXPECT_THROW((void)normal_quantile(std::numeric_limits<double>::quiet_NaN()),
               std::invalid_argument);
}

/// Fox 2003, Eq. (13), written out independently of the library.
double fox_bound(double k, double epsilon, double z) {
  const double a = 2.0 / (9.0 * (k - 1.0));
  const double c = 1.0 - a + std::sqrt(a) * z;
  return (k - 1.0) / (2.0 * epsilon) * c * c * c;
}

TEST(Kld, HandComputedValues) {
  const double z99 = normal_quantile(0.99);
  // k = 2: a = 2/9, bracket = 7/9 + sqrt(2)/3 * 2.326348 = 1.874428, cubed = 6.585773,
  // times 1 / 0.1 = 65.858 -> 66.
  EXPECT_EQ(kld_required_particles(2, 0.05, z99), 66u);
  // k = 10: a = 2/81, bracket = 1.2815, cubed * 9 / 0.1 = 216.966 -> 217.
  EXPECT_EQ(kld_required_particles(10, 0.05, z99), 217u);
  // k = 100: a = 2/891, bracket = 1.107974, cubed * 99 / 0.1 = 1346.55 -> 1347.
  EXPECT_EQ(kld_required_particles(100, 0.05, z99), 1347u);
}

TEST(Kld, MatchesFoxFormulaAndChiSquareTable) {
  const double z99 = normal_quantile(0.99);
  for (std::size_t k = 2; k < 5000; k += 7) {
    for (const double eps : {0.01, 0.05, 0.2}) {
      const double n = fox_bound(static_cast<double>(k), eps, z99);
      EXPECT_EQ(kld_required_particles(k, eps, z99), static_cast<std::size_t>(std::ceil(n)));
    }
  }
  // Wilson-Hilferty approximates n = chi2_{k-1, 1-delta} / (2 epsilon); printed table
  // values of the chi-square quantile agree within 1%.
  const std::tuple<std::size_t, double, double> table[] = {
      {2, 0.99, 6.635}, {10, 0.99, 21.666}, {100, 0.99, 134.642}, {3, 0.95, 5.991}};
  for (const auto& [k, q, chi2] : table) {
    const auto n = static_cast<double>(kld_required_particles(k, 0.05, normal_quantile(q)));
    EXPECT_NEAR(n, chi2 / 0.1, 0.01 * chi2 / 0.1) << "k = " << k;
  }
}

TEST(Kld, MonotoneInBinsAndDegenerateCases) {
  const double z = normal_quantile(0.99);
  std::size_t prev = 0;
  for (std::size_t k = 2; k < 20000; ++k) {
    const std::size_t n = kld_required_particles(k, 0.05, z);
    EXPECT_GE(n, prev);
    prev = n;
  }
  EXPECT_EQ(kld_required_particles(0, 0.05, z), 0u);
  EXPECT_EQ(kld_required_particles(1, 0.05, z), 0u);
  EXPECT_GT(kld_required_particles(2, 0.01, z), kld_required_particles(2, 0.05, z));
  EXPECT_THROW((void)kld_required_particles(10, 0.0, z), std::invalid_argument);
  EXPECT_THROW((void)kld_required_particles(10, 0.05, std::nan("")), std::invalid_argument);
}

TEST(KldBinner, CountsDistinctBinsLikeASet) {
  // Oracle: std::set of (floor(x / bx), floor(y / by), heading sector).
  const double bx = 0.2, by = 0.3, bt = 10.0 * kPi / 180.0;
  KldBinner binner(bx, by, bt);
  ASSERT_EQ(binner.theta_bins(), 36u);
  Rng rng(3);
  for (int round = 0; round < 3; ++round) {  // also checks clear() between rounds
    binner.clear();
    std::set<std::tuple<long, long, long>> oracle;
    for (int i = 0; i < 20000; ++i) {  // far past the initial 4096-bin capacity
      const double x = rng.uniform(-30, 30), y = rng.uniform(-20, 20);
      const double th = rng.uniform(-kPi, kPi);
      const auto key = std::make_tuple(static_cast<long>(std::floor(x / bx)),
                                       static_cast<long>(std::floor(y / by)),
                                       static_cast<long>(std::floor((th + kPi) / bt)) % 36);
      const bool fresh = oracle.insert(key).second;
      EXPECT_EQ(binner.insert(x, y, th), fresh);
    }
    EXPECT_EQ(binner.occupied(), oracle.size());
  }
}

TEST(KldBinner, HeadingSeamAndNegativeCoordinates) {
  KldBinner binner(0.5, 0.5, kPi / 18);
  EXPECT_TRUE(binner.insert(-0.1, -0.1, kPi));
  EXPECT_FALSE(binner.insert(-0.4, -0.2, -kPi));         // pi and -pi share a bin
  EXPECT_FALSE(binner.insert(-0.4, -0.2, -kPi + 0.01));  // first sector
  EXPECT_TRUE(binner.insert(-0.4, -0.2, kPi - 0.01));    // last sector
  EXPECT_TRUE(binner.insert(0.1, -0.1, kPi));            // x = 0 is an edge
  EXPECT_FALSE(binner.insert(-0.1, -0.1, 3 * kPi));      // wrapped heading
  EXPECT_EQ(binner.occupied(), 3u);
  binner.clear();
  EXPECT_EQ(binner.occupied(), 0u);
  EXPECT_TRUE(binner.insert(-0.1, -0.1, kPi));
}

TEST(KldBinner, RejectsBadBinSizes) {
  EXPECT_THROW(KldBinner(0.0, 0.2, 0.1), std::invalid_argument);
  EXPECT_THROW(KldBinner(0.2, -1.0, 0.1), std::invalid_argument);
  EXPECT_THROW(KldBinner(0.2, 0.2, std::nan("")), std::invalid_argument);
  EXPECT_THROW(KldBinner(0.2, 0.2, 1e-6), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl
