#include "pgmcl/mcl/pose_estimate.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "pgmcl/common/random.hpp"

namespace pgmcl {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

struct Cloud {
  std::vector<float> x, y, theta;
  std::vector<double> w;
  void add(double px, double py, double pt, double pw) {
    x.push_back(static_cast<float>(px));
    y.push_back(static_cast<float>(py));
    theta.push_back(static_cast<float>(pt));
    w.push_back(pw);
  }
  [[nodiscard]] PoseEstimate estimate(int threads = 1) const {
    return estimate_pose(x, y, theta, w, threads);
  }
};

/// Brute-force oracle in long double straight from the definitions (no reference shift).
PoseEstimate oracle(const Cloud& c) {
  long double sw = 0, sx = 0, sy = 0, sc = 0, ss = 0;
  for (std::size_t i = 0; i < c.w.size(); ++i) {
    sw += c.w[i];
    sx += c.w[i] * static_cast<long double>(c.x[i]);
    sy += c.w[i] * static_cast<long double>(c.y[i]);
    sc += c.w[i] * std::cos(static_cast<long double>(c.theta[i]));
    ss += c.w[i] * std::sin(static_cast<long double>(c.theta[i]));
  }
  PoseEstimate e;
  e.mean = {static_cast<double>(sx / sw), static_cast<double>(sy / sw),
            static_cast<double>(std::atan2(ss, sc))};
  e.heading_concentration = static_cast<double>(std::hypot(sc, ss) / sw);
  long double cov[3][3] = {};
  for (std::size_t i = 0; i < c.w.size(); ++i) {
    const long double d[3] = {c.x[i] - sx / sw, c.y[i] - sy / sw,
                              wrap_angle(static_cast<double>(c.theta[i]) - e.mean.theta)};
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) cov[r][k] += c.w[i] * d[r] * d[k];
    }
  }
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) e.covariance(r, k) = static_cast<double>(cov[r][k] / sw);
  }
  return e;
}

double min_eigenvalue(const Eigen::Matrix3d& c) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues()(0);
}

TEST(PoseEstimate, CircularMeanAcrossPi) {
  Cloud c;
  c.add(0, 0, 179 * kDeg, 1.0);
  c.add(0, 0, -179 * kDeg, 1.0);
  const PoseEstimate e = c.estimate();
  EXPECT_NEAR(std::abs(e.mean.theta), kPi, 1e-6);  // 180 degrees, not 0
  // (1 deg)^2, not (179 deg)^2; the float headings carry ~1e-7 rad of rounding.
  EXPECT_NEAR(e.covariance(2, 2), std::pow(1 * kDeg, 2), 1e-8);
  EXPECT_NEAR(e.heading_concentration, std::cos(1 * kDeg), 1e-7);
}

TEST(PoseEstimate, CollapsedCloudHasZeroCovariance) {
  Cloud c;
  for (int i = 0; i < 3000; ++i) c.add(1234.567, -89.01, 3.1, 1.0 / 3.0);
  for (const int threads : {1, 2}) {
    const PoseEstimate e = c.estimate(threads);
    EXPECT_EQ(e.mean.x, static_cast<double>(c.x[0]));
    EXPECT_EQ(e.mean.y, static_cast<double>(c.y[0]));
    EXPECT_EQ(e.mean.theta, static_cast<double>(c.theta[0]));
    EXPECT_TRUE(e.covariance.isZero(0.0)) << e.covariance;
    EXPECT_EQ(e.heading_concentration, 1.0);
  }
}

TEST(PoseEstimate, WeightsAreRespected) {
  Cloud c;
  c.add(1.0, 2.0, 0.1, 0.25 * 7);  // unnormalised on purpose
  c.add(3.0, -2.0, 0.5, 0.75 * 7);
  const PoseEstimate e = c.estimate();
  EXPECT_NEAR(e.mean.x, 0.25 * 1.0 + 0.75 * 3.0, 1e-12);
  EXPECT_NEAR(e.mean.y, 0.25 * 2.0 - 0.75 * 2.0, 1e-12);
  // Two points: var = w1 w2 (a - b)^2.
  EXPECT_NEAR(e.covariance(0, 0), 0.25 * 0.75 * 4.0, 1e-12);
  EXPECT_NEAR(e.covariance(1, 1), 0.25 * 0.75 * 16.0, 1e-12);
  EXPECT_NEAR(e.covariance(0, 1), -0.25 * 0.75 * 8.0, 1e-12);
  // Circular mean of 0.1 and 0.5 with weights 1:3 (float headings).
  const double t1 = static_cast<float>(0.1), t2 = static_cast<float>(0.5);
  EXPECT_NEAR(e.mean.theta,
              std::atan2(0.25 * std::sin(t1) + 0.75 * std::sin(t2),
                         0.25 * std::cos(t1) + 0.75 * std::cos(t2)),
              1e-12);
  // Zero-weight particles are ignored.
  c.add(-100.0, 100.0, -2.0, 0.0);
  const PoseEstimate e2 = c.estimate();
  EXPECT_NEAR(e2.mean.x, e.mean.x, 1e-12);
  EXPECT_NEAR(e2.covariance(1, 1), e.covariance(1, 1), 1e-12);
}

TEST(PoseEstimate, MatchesBruteForceAndIsPsdOnRandomClouds) {
  Rng rng(17);
  for (int trial = 0; trial < 60; ++trial) {
    Cloud c;
    const double cx = rng.uniform(-500, 500), cy = rng.uniform(-500, 500);
    const double ct = rng.uniform(-kPi, kPi), st = rng.uniform(0.01, 1.0);
    const int n = 1 + static_cast<int>(rng.below(2000));
    const bool collinear = trial % 4 == 0;  // rank-deficient: exercises the PSD repair
    for (int i = 0; i < n; ++i) {
      const double s = rng.normal();
      const double px = cx + (collinear ? s : rng.normal(0.7));
      const double py = cy + (collinear ? 2.0 * s : rng.normal(0.3));
      const double pt = wrap_angle(ct + (collinear ? 0.3 * s : rng.normal(st)));
      c.add(px, py, pt, rng.uniform());
    }
    const PoseEstimate e = c.estimate(trial % 2 == 0 ? 1 : 0);
    const PoseEstimate o = oracle(c);
    EXPECT_NEAR(e.mean.x, o.mean.x, 1e-9);
    EXPECT_NEAR(e.mean.y, o.mean.y, 1e-9);
    EXPECT_NEAR(wrap_angle(e.mean.theta - o.mean.theta), 0.0, 1e-9);
    EXPECT_NEAR(e.heading_concentration, o.heading_concentration, 1e-12);
    EXPECT_LE(e.heading_concentration, 1.0);
    const double scale = o.covariance.norm();
    EXPECT_LT((e.covariance - o.covariance).norm(), 1e-9 * scale + 1e-15);
    EXPECT_TRUE(e.covariance.isApprox(e.covariance.transpose(), 0.0));  // exactly symmetric
    EXPECT_GE(min_eigenvalue(e.covariance), 0.0) << "trial " << trial;
    EXPECT_FALSE(e.covariance.hasNaN());
  }
}

TEST(PoseEstimate, RankOneCloudsStayPsd) {
  // Two particles give an exactly rank-one covariance; about 1% of such clouds round to a
  // negative eigenvalue (~-1e-16) before the repair.
  Rng rng(19);
  for (int trial = 0; trial < 3000; ++trial) {
    Cloud c;
    const double s = rng.normal(), a = rng.uniform(-3, 3), b = rng.uniform(-0.3, 0.3);
    c.add(100.0, -50.0, 0.0, rng.uniform());
    c.add(100.0 + s, -50.0 + a * s, b * s, rng.uniform());
    const PoseEstimate e = c.estimate();
    EXPECT_GE(min_eigenvalue(e.covariance), 0.0) << "trial " << trial;
    const PoseEstimate o = oracle(c);
    EXPECT_LT((e.covariance - o.covariance).norm(), 1e-9 * o.covariance.norm() + 1e-15);
  }
}

TEST(PoseEstimate, SameBitsForAnyThreadCount) {
  Rng rng(18);
  Cloud c;
  for (int i = 0; i < 50000; ++i) {
    c.add(rng.normal(2.0), rng.normal(1.0), wrap_angle(3.0 + rng.normal(0.5)), rng.uniform());
  }
  const PoseEstimate ref = c.estimate(1);
  for (const int threads : {0, 2, 3}) {
    const PoseEstimate e = c.estimate(threads);
    EXPECT_EQ(e.mean.x, ref.mean.x);
    EXPECT_EQ(e.mean.y, ref.mean.y);
    EXPECT_EQ(e.mean.theta, ref.mean.theta);
    EXPECT_EQ(e.heading_concentration, ref.heading_concentration);
    EXPECT_TRUE(e.covariance == ref.covariance);
  }
}

TEST(PoseEstimate, RejectsBadInput) {
  Cloud c;
  EXPECT_THROW((void)c.estimate(), std::invalid_argument);  // empty
  c.add(0, 0, 0, 0.0);
  EXPECT_THROW((void)c.estimate(), std::invalid_argument);  // zero total weight
  c.w[0] = 1.0;
  c.x.push_back(1.0f);
  EXPECT_THROW((void)c.estimate(), std::invalid_argument);  // size mismatch
}

}  // namespace
}  // namespace pgmcl
