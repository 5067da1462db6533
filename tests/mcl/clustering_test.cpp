#include "pgmcl/mcl/clustering.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "pgmcl/common/random.hpp"
#include "pgmcl/mcl/pose_estimate.hpp"

namespace pgmcl {
namespace {

constexpr double kPi = std::numbers::pi;

struct Cloud {
  std::vector<float> x, y, theta;
  std::vector<double> w;
  void add(double px, double py, double pt, double pw) {
    x.push_back(static_cast<float>(px));
    y.push_back(static_cast<float>(py));
    theta.push_back(static_cast<float>(wrap_angle(pt)));
    w.push_back(pw);
  }
  void blob(Rng& rng, int n, double cx, double cy, double ct, double sxy, double st,
            double total_w) {
    for (int i = 0; i < n; ++i) {
      add(cx + rng.normal(sxy), cy + rng.normal(sxy), ct + rng.normal(st), total_w / n);
    }
  }
  [[nodiscard]] Cloud subset(std::span<const std::uint32_t> labels, std::uint32_t k) const {
    Cloud c;
    for (std::size_t i = 0; i < w.size(); ++i) {
      if (labels[i] == k) c.add(x[i], y[i], theta[i], w[i]);
    }
    return c;
  }
};

TEST(Clustering, HeaviestOfTwoBlobsIsBest) {
  Rng rng(1);
  Cloud c;
  c.blob(rng, 400, 2.0, 3.0, 0.5, 0.1, 0.05, 0.3);
  c.blob(rng, 600, 8.0, -1.0, -2.0, 0.1, 0.05, 0.7);
  ParticleClusterer clusterer({0.25, 0.3});
  const auto& cl = clusterer.cluster(c.x, c.y, c.theta, c.w);
  ASSERT_EQ(cl.size(), 2u);
  EXPECT_NEAR(cl[0].weight, 0.7, 1e-12);
  EXPECT_NEAR(cl[1].weight, 0.3, 1e-12);
  EXPECT_EQ(cl[0].count, 600u);
  EXPECT_EQ(cl[1].count, 400u);
  EXPECT_NEAR(cl[0].mean.x, 8.0, 0.02);
  EXPECT_NEAR(cl[0].mean.y, -1.0, 0.02);
  EXPECT_NEAR(cl[0].mean.theta, -2.0, 0.01);
  // The cluster's moments are those of its particles alone (oracle: estimate_pose).
  for (std::uint32_t k = 0; k < 2; ++k) {
    const Cloud s = c.subset(clusterer.labels(), k);
    const PoseEstimate e = estimate_pose(s.x, s.y, s.theta, s.w, 1);
    EXPECT_NEAR(cl[k].mean.x, e.mean.x, 1e-12);
    EXPECT_NEAR(cl[k].mean.y, e.mean.y, 1e-12);
    EXPECT_NEAR(cl[k].mean.theta, e.mean.theta, 1e-12);
    EXPECT_LT((cl[k].covariance - e.covariance).norm(), 1e-12);
    EXPECT_NEAR(cl[k].heading_concentration, e.heading_concentration, 1e-12);
  }
  // The overall mean sits between the blobs, where no particle is: why clusters matter.
  const PoseEstimate all = estimate_pose(c.x, c.y, c.theta, c.w, 1);
  EXPECT_GT(std::hypot(all.mean.x - cl[0].mean.x, all.mean.y - cl[0].mean.y), 1.0);
}

TEST(Clustering, BlobAcrossPiStaysOneCluster) {
  Rng rng(2);
  Cloud c;
  c.blob(rng, 500, -0.3, -0.2, kPi, 0.08, 0.1, 1.0);  // headings on both sides of +/-pi
  int positive = 0;
  for (const float t : c.theta) positive += t > 0 ? 1 : 0;
  ASSERT_GT(positive, 100);
  ASSERT_LT(positive, 400);
  const auto cl = cluster_particles(c.x, c.y, c.theta, c.w, {0.25, 0.3});
  ASSERT_EQ(cl.size(), 1u);
  EXPECT_NEAR(std::abs(cl[0].mean.theta), kPi, 0.03);
  EXPECT_LT(cl[0].covariance(2, 2), 0.02);  // ~0.1^2, not a heading spread of ~pi^2
  EXPECT_NEAR(cl[0].weight, 1.0, 1e-12);
}

TEST(Clustering, SeparationAlongEachAxis) {
  // Single linkage at the cell scale: within one cell always joined, beyond two cells in
  // one dimension never joined without occupied cells between.
  const ClusterConfig cfg{0.5, 0.5};
  const double step = 2 * kPi / std::round(2 * kPi / 0.5);
  struct Case {
    double dx, dy, dt;
    std::size_t expected;
  };
  for (const Case& k : {Case{0.3, 0, 0, 1}, Case{1.1, 0, 0, 2}, Case{0, 0.3, 0, 1},
                        Case{0, 1.1, 0, 2}, Case{0, 0, 0.2, 1}, Case{0, 0, 2.2 * step, 2}}) {
    Cloud c;
    c.add(0.1, 0.1, 0.01, 1.0);
    c.add(0.1 + k.dx, 0.1 + k.dy, 0.01 + k.dt, 1.0);
    EXPECT_EQ(cluster_particles(c.x, c.y, c.theta, c.w, cfg).size(), k.expected)
        << k.dx << " " << k.dy << " " << k.dt;
  }
  // A chain of particles half a cell apart is one cluster however long it is.
  Cloud chain;
  for (int i = 0; i < 200; ++i) chain.add(-20.0 + 0.25 * i, 3.0, 0.0, 1.0);
  EXPECT_EQ(cluster_particles(chain.x, chain.y, chain.theta, chain.w, cfg).size(), 1u);
}

/// Oracle: O(N^2) flood fill over particles, two particles adjacent when their cell
/// indices differ by at most one in x, y and (cyclically) heading.
std::vector<int> brute_force_labels(const Cloud& c, double cell, double cell_theta) {
  const auto n = c.w.size();
  const double sectors = std::round(2 * kPi / cell_theta);
  std::vector<long> ix(n), iy(n), is(n);
  // Same floating-point expressions as the library, so cell edges round identically.
  const double inv = 1.0 / cell, per_radian = sectors / (2 * kPi);
  for (std::size_t i = 0; i < n; ++i) {
    ix[i] = static_cast<long>(std::floor(c.x[i] * inv));
    iy[i] = static_cast<long>(std::floor(c.y[i] * inv));
    is[i] = static_cast<long>(std::floor((wrap_angle(double{c.theta[i]}) + kPi) * per_radian)) %
            static_cast<long>(sectors);
  }
  std::vector<int> label(n, -1);
  int next = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (label[s] >= 0) continue;
    std::vector<std::size_t> stack{s};
    label[s] = next;
    while (!stack.empty()) {
      const std::size_t a = stack.back();
      stack.pop_back();
      for (std::size_t b = 0; b < n; ++b) {
        if (label[b] >= 0) continue;
        const long ds = std::labs(is[a] - is[b]);
        const bool near = std::labs(ix[a] - ix[b]) <= 1 && std::labs(iy[a] - iy[b]) <= 1 &&
                          (ds <= 1 || ds == static_cast<long>(sectors) - 1);
        if (near) {
          label[b] = next;
          stack.push_back(b);
        }
      }
    }
    ++next;
  }
  return label;
}

TEST(Clustering, SamePartitionAsBruteForce) {
  Rng rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    Cloud c;
    const int blobs = 1 + static_cast<int>(rng.below(6));
    for (int b = 0; b < blobs; ++b) {
      c.blob(rng, 20 + static_cast<int>(rng.below(100)), rng.uniform(-4, 4), rng.uniform(-4, 4),
             rng.uniform(-kPi, kPi), rng.uniform(0.05, 0.6), rng.uniform(0.05, 1.0),
             rng.uniform(0.1, 1.0));
    }
    const double cell = rng.uniform(0.2, 0.8), cell_theta = rng.uniform(0.2, 1.0);
    ParticleClusterer clusterer({cell, cell_theta});
    const auto& cl = clusterer.cluster(c.x, c.y, c.theta, c.w);
    const auto oracle = brute_force_labels(c, cell, cell_theta);
    // Same partition: the label maps are bijective.
    std::map<int, std::uint32_t> fwd;
    std::map<std::uint32_t, int> bwd;
    for (std::size_t i = 0; i < c.w.size(); ++i) {
      const auto [it1, new1] = fwd.emplace(oracle[i], clusterer.labels()[i]);
      const auto [it2, new2] = bwd.emplace(clusterer.labels()[i], oracle[i]);
      ASSERT_EQ(it1->second, clusterer.labels()[i]) << "trial " << trial << " particle " << i;
      ASSERT_EQ(it2->second, oracle[i]) << "trial " << trial << " particle " << i;
    }
    ASSERT_EQ(fwd.size(), cl.size());
    double total = 0.0;
    std::size_t count = 0;
    for (std::size_t k = 0; k < cl.size(); ++k) {
      total += cl[k].weight;
      count += cl[k].count;
      if (k > 0) {
        EXPECT_GE(cl[k - 1].weight, cl[k].weight);
      }
      EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cl[k].covariance).eigenvalues()(0),
                0.0);
    }
    EXPECT_NEAR(total, 1.0, 1e-12);
    EXPECT_EQ(count, c.w.size());
  }
}

TEST(Clustering, ZeroWeightClusterIsFinite) {
  Cloud c;
  c.add(0, 0, 0, 1.0);
  c.add(10, 10, 1.0, 0.0);
  c.add(10.1, 10, 1.1, 0.0);
  const auto cl = cluster_particles(c.x, c.y, c.theta, c.w);
  ASSERT_EQ(cl.size(), 2u);
  EXPECT_EQ(cl[1].weight, 0.0);
  EXPECT_NEAR(cl[1].mean.x, 10.05, 1e-6);  // its particles count equally
  EXPECT_FALSE(cl[1].covariance.hasNaN());
}

TEST(Clustering, RejectsBadInput) {
  EXPECT_THROW(ParticleClusterer({0.0, 0.5}), std::invalid_argument);
  EXPECT_THROW(ParticleClusterer({0.5, -1.0}), std::invalid_argument);
  EXPECT_THROW(ParticleClusterer({0.5, 1e-9}), std::invalid_argument);
  Cloud c;
  ParticleClusterer clusterer;
  EXPECT_THROW((void)clusterer.cluster(c.x, c.y, c.theta, c.w), std::invalid_argument);
  c.add(0, 0, 0, 0.0);
  EXPECT_THROW((void)clusterer.cluster(c.x, c.y, c.theta, c.w), std::invalid_argument);
  c.w[0] = 1.0;
  c.y.push_back(0.f);
  EXPECT_THROW((void)clusterer.cluster(c.x, c.y, c.theta, c.w), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl
