// Degenerate weight distributions and particle clouds: log-sum-exp normalisation and N_eff
// at the extremes (all equal, one particle carrying everything, spreads that underflow
// exp(), denormals, NaN/Inf entries) and the pose estimate of collapsed clouds, including
// clouds straddling the +-pi heading wrap and at UTM-scale magnitudes.

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "pgmcl/common/random.hpp"
#include "pgmcl/mcl/pose_estimate.hpp"
#include "pgmcl/mcl/weights.hpp"

namespace pgmcl {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr float kPiF = std::numbers::pi_v<float>;

#ifdef NDEBUG
constexpr std::size_t kMany = 1000000;
#else
constexpr std::size_t kMany = 100000;  // Debug/ASan: a tenth, same code paths
#endif

void expect_normalised(const std::vector<double>& log_w, const std::vector<double>& w) {
  double total = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    ASSERT_TRUE(std::isfinite(w[i]) && w[i] >= 0.0 && w[i] <= 1.0) << i << ": " << w[i];
    ASSERT_FALSE(std::isnan(log_w[i])) << i;
    total += w[i];
  }
  EXPECT_NEAR(total, 1.0, 1e-9);
  EXPECT_GE(effective_sample_size(w), 1.0 - 1e-9);
  EXPECT_LE(effective_sample_size(w), static_cast<double>(w.size()) * (1 + 1e-9));
}

TEST(StressWeights, AllEqualAtAnyMagnitudeIsUniform) {
  for (const double v : {0.0, -1e5, -1e300, -std::numeric_limits<double>::max(), 700.0, 1e300}) {
    std::vector<double> log_w(kMany, v), w(kMany);
    const double norm = normalise_log_weights(log_w, w);
    EXPECT_TRUE(std::isfinite(norm)) << v;
    expect_normalised(log_w, w);
    EXPECT_NEAR(effective_sample_size(w), static_cast<double>(kMany), 1e-6 * kMany) << v;
    EXPECT_DOUBLE_EQ(w[kMany / 2], 1.0 / static_cast<double>(kMany));
  }
}

TEST(StressWeights, OneParticleCarriesEverything) {
  // The heavy one sits far below zero; the rest lie 1e4 or 746 nats below it (exp() of
  // the difference underflows), or are -1e308, -inf or NaN.
  for (const double rest : {-4e4, -3e4 - 746.0, -1e308, -kInf, kNaN}) {
    std::vector<double> log_w(kMany, rest), w(kMany);
    log_w[kMany / 3] = -3e4;
    (void)normalise_log_weights(log_w, w);
    expect_normalised(log_w, w);
    EXPECT_EQ(w[kMany / 3], 1.0) << rest;
    EXPECT_EQ(effective_sample_size(w), 1.0) << rest;
    EXPECT_EQ(log_w[kMany / 3], 0.0);
  }
}

// 1081 beams x ~6 nats: scan log-likelihoods span 1e4 nats; spacings of 740..750 nats
// produce denormal weights; none of it may give NaN or lose normalisation.
TEST(StressWeights, SpreadsBeyondExpUnderflowAndDenormals) {
  Rng rng(3);
  std::vector<double> log_w(kMany), w(kMany);
  for (double& v : log_w) v = -7000.0 + 11000.0 * rng.uniform();
  (void)normalise_log_weights(log_w, w);
  expect_normalised(log_w, w);

  std::vector<double> d = {0.0, -700.0, -740.0, -745.0, -745.2, -750.0, -1e4}, dw(d.size());
  (void)normalise_log_weights(d, dw);
  expect_normalised(d, dw);
  EXPECT_GT(dw[3], 0.0) << "exp(-745) is a denormal, not zero";
  EXPECT_EQ(dw[6], 0.0);
}

TEST(StressWeights, NaNAndInfinitiesNeverLeakIntoWeights) {
  std::vector<double> log_w = {kNaN, -kInf, -1e300, 5.0, kNaN, 4.0}, w(log_w.size());
  (void)normalise_log_weights(log_w, w);
  expect_normalised(log_w, w);
  EXPECT_EQ(w[0], 0.0);
  EXPECT_EQ(w[1], 0.0);
  EXPECT_NEAR(w[3] / w[5], std::exp(1.0), 1e-12);

  std::vector<double> all_bad = {kNaN, -kInf, kNaN}, wb(3);
  EXPECT_FALSE(std::isfinite(normalise_log_weights(all_bad, wb)));  // documented flag
  expect_normalised(all_bad, wb);

  std::vector<double> plus_inf = {kInf, 0.0, kInf, kNaN}, wp(4);
  (void)normalise_log_weights(plus_inf, wp);
  expect_normalised(plus_inf, wp);
  EXPECT_EQ(wp[0], 0.5);
  EXPECT_EQ(wp[2], 0.5);
}

bool psd_and_finite(const Eigen::Matrix3d& c) {
  if (!c.allFinite() || (c - c.transpose()).cwiseAbs().maxCoeff() > 0.0) return false;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues().minCoeff() >= 0.0;
}

// A cloud collapsed onto one pose (what tau = 1 with 1081 beams does): the mean is that
// pose and the covariance exactly zero; at +-pi and at 1e5 m magnitudes too.
TEST(StressPoseEstimate, CollapsedCloudHasZeroCovarianceAndNoNaN) {
  for (const float theta : {0.3f, kPiF, -kPiF + 1e-7f}) {
    for (const float xy : {1.25f, 1e5f}) {
      const std::vector<float> x(kMany, xy), y(kMany, -xy), th(kMany, theta);
      const std::vector<double> w(kMany, 1.0 / kMany);
      const PoseEstimate e = estimate_pose(x, y, th, w, 0);
      EXPECT_EQ(e.mean.x, static_cast<double>(xy));
      EXPECT_EQ(e.mean.y, -static_cast<double>(xy));
      EXPECT_NEAR(std::abs(wrap_angle(e.mean.theta - theta)), 0.0, 1e-7);
      EXPECT_TRUE(e.covariance.isZero(0.0)) << e.covariance;
      EXPECT_TRUE(psd_and_finite(e.covariance));
      EXPECT_NEAR(e.heading_concentration, 1.0, 1e-12);
    }
  }
}

// Headings on both sides of the wrap: the circular mean is at pi, the heading variance
// tiny (not ~pi^2 as a linear mean of +pi and -pi would give).
TEST(StressPoseEstimate, CloudStraddlingThePiWrap) {
  Rng rng(9);
  std::vector<float> x(kMany), y(kMany), th(kMany);
  std::vector<double> w(kMany);
  for (std::size_t i = 0; i < kMany; ++i) {
    x[i] = static_cast<float>(2.0 + rng.normal(0.01));
    y[i] = static_cast<float>(3.0 + rng.normal(0.01));
    th[i] = wrap_angle(static_cast<float>(std::numbers::pi + rng.normal(0.02)));
    w[i] = rng.uniform();
  }
  const PoseEstimate e = estimate_pose(x, y, th, w, 0);
  EXPECT_LT(std::abs(wrap_angle(e.mean.theta - std::numbers::pi)), 1e-3);
  EXPECT_NEAR(std::sqrt(e.covariance(2, 2)), 0.02, 1e-3);
  EXPECT_NEAR(std::sqrt(e.covariance(0, 0)), 0.01, 1e-3);
  EXPECT_TRUE(psd_and_finite(e.covariance));
}

// One particle carries all the weight, the others are far away (and at the opposite
// heading): estimate = that particle, covariance zero. Denormal weights elsewhere change
// nothing measurable and give no NaN.
TEST(StressPoseEstimate, OneHeavyParticleAmongFarAwayOnes) {
  std::vector<float> x = {1.0f, 500.0f, -300.0f, 7.0f}, y = {2.0f, -40.0f, 9e3f, 7.0f};
  std::vector<float> th = {3.0f, -0.1f, 0.0f, -3.0f};
  for (const double tiny : {0.0, 1e-310, 1e-300}) {
    const std::vector<double> w = {1.0, tiny, tiny, tiny};
    const PoseEstimate e = estimate_pose(x, y, th, w, 1);
    EXPECT_NEAR(e.mean.x, 1.0, 1e-6) << tiny;
    EXPECT_NEAR(e.mean.y, 2.0, 1e-5) << tiny;
    EXPECT_NEAR(e.mean.theta, 3.0, 1e-9) << tiny;
    EXPECT_TRUE(psd_and_finite(e.covariance)) << e.covariance;
    EXPECT_LT(e.covariance.cwiseAbs().maxCoeff(), 1e-3) << tiny;
  }
}

TEST(StressPoseEstimate, BadWeightsAreRejectedNotAveraged) {
  const std::vector<float> x = {1.0f, 2.0f}, y = {1.0f, 2.0f}, th = {0.0f, 1.0f};
  for (const std::vector<double>& w :
       {std::vector<double>{0.0, 0.0}, {kNaN, 1.0}, {kInf, 1.0}, {1e308, 1e308}}) {
    EXPECT_THROW((void)estimate_pose(x, y, th, w, 1), std::invalid_argument)
        << w[0] << ", " << w[1];
  }
}

}  // namespace
}  // namespace pgmcl
