// Motion models checked against closed-form moments by sampling (Probabilistic Robotics,
// Table 5.6). Tolerances are 5 standard errors of each sample statistic, with the standard
// error estimated from the same samples.

#include "pgmcl/common/motion_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace pgmcl {
namespace {

constexpr int kSamples = 200000;
constexpr double kSe = 5.0;  // tolerance in standard errors
constexpr double kPi = std::numbers::pi;

const MotionNoise kNoise{0.02, 0.01, 0.01, 0.005, 0.008};

using Sample = std::array<double, 3>;

struct Moments {
  Eigen::Vector3d mean, mean_se;
  Eigen::Matrix3d cov, cov_se;
};

// Plain loops rather than per-sample Eigen products: this runs 200k times per test, also
// in unoptimised sanitizer builds.
Moments moments_of(const std::vector<Sample>& s) {
  const auto n = static_cast<double>(s.size());
  double mean[3] = {0, 0, 0};
  for (const auto& v : s) {
    for (int i = 0; i < 3; ++i) mean[i] += v[i];
  }
  for (double& m : mean) m /= n;
  double cov[3][3] = {}, sq[3][3] = {};
  for (const auto& v : s) {
    const double d[3] = {v[0] - mean[0], v[1] - mean[1], v[2] - mean[2]};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double p = d[i] * d[j];
        cov[i][j] += p;
        sq[i][j] += p * p;
      }
    }
  }
  Moments m;
  for (int i = 0; i < 3; ++i) {
    m.mean(i) = mean[i];
    for (int j = 0; j < 3; ++j) {
      m.cov(i, j) = cov[i][j] / n;
      // Var of the product d_i d_j, so SE of its mean is sqrt((E[p^2] - E[p]^2) / n).
      m.cov_se(i, j) = std::sqrt(std::max(0.0, sq[i][j] / n - m.cov(i, j) * m.cov(i, j)) / n);
    }
  }
  for (int i = 0; i < 3; ++i) m.mean_se(i) = std::sqrt(m.cov(i, i) / n);
  return m;
}

void expect_moments(const Moments& m, const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(m.mean(i), mean(i), kSe * m.mean_se(i) + 1e-12) << "mean " << i;
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(m.cov(i, j), cov(i, j), kSe * m.cov_se(i, j) + 1e-12) << "cov " << i << j;
    }
  }
}

/// Exact moments of Table 5.6's output pose: x' = x + s T cos(phi), y' = y + s T sin(phi),
/// theta' = theta + rot1^ + rot2^, with phi = theta + rot1^, T, rot1^, rot2^ independent
/// Gaussians and s = -1 when backwards. Uses E[cos phi] = cos(mu) exp(-v/2),
/// E[cos^2 phi] = (1 + cos(2 mu) exp(-2v)) / 2, and Stein's lemma for Cov(cos phi, phi).
void diff_drive_pose_moments(const OdometryIncrement& inc, const MotionNoise& n, const Pose2& pose,
                             Eigen::Vector3d& mean, Eigen::Matrix3d& cov) {
  const double r1 = inc.rot1, t = inc.trans, r2 = inc.rot2, s = inc.backwards ? -1.0 : 1.0;
  const double v1 = n.a1 * r1 * r1 + n.a2 * t * t;
  const double vt = n.a3 * t * t + n.a4 * (r1 * r1 + r2 * r2);
  const double v2 = n.a1 * r2 * r2 + n.a2 * t * t;
  const double mu = pose.theta + r1;
  const double e1 = std::exp(-v1 / 2), e2 = std::exp(-2 * v1);
  const double ec = std::cos(mu) * e1, es = std::sin(mu) * e1;
  const double ecc = (1 + std::cos(2 * mu) * e2) / 2, ess = (1 - std::cos(2 * mu) * e2) / 2;
  const double ecs = std::sin(2 * mu) * e2 / 2;
  const double et2 = t * t + vt;
  mean << pose.x + s * t * ec, pose.y + s * t * es, pose.theta + r1 + r2;
  cov(0, 0) = et2 * ecc - t * t * ec * ec;
  cov(1, 1) = et2 * ess - t * t * es * es;
  cov(0, 1) = cov(1, 0) = et2 * ecs - t * t * ec * es;
  cov(2, 2) = v1 + v2;
  cov(0, 2) = cov(2, 0) = s * t * (-v1 * es);
  cov(1, 2) = cov(2, 1) = s * t * (v1 * ec);
}

/// Samples poses; the heading is stored as mean_theta + wrap(theta - mean_theta) so the
/// statistics are taken on the unwrapped circle around the expected heading.
std::vector<Sample> sample_poses(MotionModelKind kind, const MotionNoise& noise, const Pose2& prev,
                                 const Pose2& now, const Pose2& pose, double mean_theta,
                                 std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Sample> out;
  out.reserve(kSamples);
  int unwrapped = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Pose2 p = sample_motion(kind, noise, prev, now, pose, rng);
    unwrapped += (p.theta > -kPi && p.theta <= kPi) ? 0 : 1;
    out.push_back({p.x, p.y, mean_theta + wrap_angle(p.theta - mean_theta)});
  }
  EXPECT_EQ(unwrapped, 0);
  return out;
}

TEST(MotionModel, DecomposesForwardMotion) {
  const Pose2 prev{1.0, 2.0, 0.5};
  const Pose2 now = prev.compose({0.8, 0.3, -0.2});
  const OdometryIncrement inc = decompose_odometry(prev, now);
  EXPECT_FALSE(inc.backwards);
  EXPECT_NEAR(inc.trans, std::hypot(0.8, 0.3), 1e-12);
  EXPECT_NEAR(inc.rot1, std::atan2(0.3, 0.8), 1e-12);
  EXPECT_NEAR(inc.rot2, -0.2 - std::atan2(0.3, 0.8), 1e-12);
}

TEST(MotionModel, PureRotationHasNoTranslationDirection) {
  // Crosses +/-pi: 3.0 -> -3.0 is a rotation of +0.283 rad, not -6.0.
  const OdometryIncrement inc = decompose_odometry({1.0, 2.0, 3.0}, {1.0, 2.0, -3.0});
  EXPECT_FALSE(inc.backwards);
  EXPECT_EQ(inc.rot1, 0.0);
  EXPECT_EQ(inc.trans, 0.0);
  EXPECT_NEAR(inc.rot2, 2 * kPi - 6.0, 1e-12);
}

TEST(MotionModel, BackwardMotionUsesReversedHeading) {
  const Pose2 prev{1.0, 1.0, 0.3};
  const Pose2 now = prev.compose({-2.0, 0.2, 0.1});
  const OdometryIncrement inc = decompose_odometry(prev, now);
  EXPECT_TRUE(inc.backwards);
  EXPECT_NEAR(inc.trans, std::hypot(2.0, 0.2), 1e-12);
  EXPECT_NEAR(inc.rot1, std::atan2(-0.2, 2.0), 1e-12);  // small, not ~pi
  EXPECT_NEAR(inc.rot2, 0.1 - std::atan2(-0.2, 2.0), 1e-12);
}

TEST(MotionModel, NoiselessSampleReproducesOdometry) {
  Rng gen(7);
  const MotionNoise zero{0, 0, 0, 0, 0};
  for (const auto kind : {MotionModelKind::kDifferentialDrive, MotionModelKind::kOmnidirectional}) {
    for (int i = 0; i < 2000; ++i) {
      const Pose2 prev{gen.uniform(-5, 5), gen.uniform(-5, 5), gen.uniform(-kPi, kPi)};
      // Mix forward, backward, sideways and pure rotations, across the +/-pi seam.
      const double scale = (i % 4 == 0) ? 0.0 : 1.0;
      const Pose2 delta{scale * gen.uniform(-1, 1), scale * gen.uniform(-1, 1),
                        gen.uniform(-kPi, kPi)};
      const Pose2 now = prev.compose(delta);
      const Pose2 pose{gen.uniform(-5, 5), gen.uniform(-5, 5), gen.uniform(-kPi, kPi)};
      const Pose2 expected = pose.compose(prev.between(now));
      const Pose2 got = sample_motion(kind, zero, prev, now, pose, gen);
      EXPECT_NEAR(got.x, expected.x, 1e-9);
      EXPECT_NEAR(got.y, expected.y, 1e-9);
      EXPECT_NEAR(wrap_angle(got.theta - expected.theta), 0.0, 1e-9);
      EXPECT_TRUE(got.theta > -kPi && got.theta <= kPi);
    }
  }
}

TEST(MotionModel, ZeroMotionAddsNoNoiseAndDrawsNothing) {
  // Every variance term is a multiple of rot1^2, trans^2 or rot2^2, so zero motion is
  // deterministic: the particle stays put and the stream is untouched.
  const Pose2 odom{4.0, -1.0, 2.0};
  const Pose2 pose{0.5, 0.25, -3.1};
  for (const auto kind : {MotionModelKind::kDifferentialDrive, MotionModelKind::kOmnidirectional}) {
    Rng rng(11), copy(11);
    const Pose2 got = sample_motion(kind, kNoise, odom, odom, pose, rng);
    EXPECT_EQ(got.x, pose.x);
    EXPECT_EQ(got.y, pose.y);
    EXPECT_EQ(got.theta, pose.theta);
    EXPECT_EQ(rng.next_u64(), copy.next_u64());
  }
}

TEST(MotionModel, DiffDriveNoiseMatchesTable56Variances) {
  const Pose2 prev{0, 0, 0};
  const Pose2 now = prev.compose({1.0, 0.4, 0.7});
  const OdometryIncrement inc = decompose_odometry(prev, now);
  Rng rng(21);
  std::vector<Sample> s;
  s.reserve(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    // From the identity the output is the noisy increment; invert Table 5.6 lines 8-10.
    const Pose2 p = sample_motion(MotionModelKind::kDifferentialDrive, kNoise, inc, {}, rng);
    const double r1 = std::atan2(p.y, p.x);
    s.push_back({r1, std::hypot(p.x, p.y), wrap_angle(p.theta - r1)});
  }
  const double r1 = inc.rot1, t = inc.trans, r2 = inc.rot2;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov(0, 0) = kNoise.a1 * r1 * r1 + kNoise.a2 * t * t;
  cov(1, 1) = kNoise.a3 * t * t + kNoise.a4 * (r1 * r1 + r2 * r2);
  cov(2, 2) = kNoise.a1 * r2 * r2 + kNoise.a2 * t * t;
  expect_moments(moments_of(s), {r1, t, r2}, cov);
}

TEST(MotionModel, DiffDrivePoseMatchesClosedFormAcrossPi) {
  // Heading 3.0 + rot1 crosses the +/-pi seam during the step.
  const Pose2 prev{2, -1, 1.0};
  const Pose2 now = prev.compose({0.6, 0.25, 0.35});
  const Pose2 pose{-3.0, 4.0, 3.0};
  const OdometryIncrement inc = decompose_odometry(prev, now);
  Eigen::Vector3d mean;
  Eigen::Matrix3d cov;
  diff_drive_pose_moments(inc, kNoise, pose, mean, cov);
  const auto s =
      sample_poses(MotionModelKind::kDifferentialDrive, kNoise, prev, now, pose, mean(2), 22);
  expect_moments(moments_of(s), mean, cov);
}

TEST(MotionModel, BackwardMotionIsNotRotatePiDriveRotatePi) {
  const Pose2 prev{0, 0, 0};
  const Pose2 now{-1.0, 0.0, 0.0};
  const Pose2 pose{1.0, 1.0, 0.5};
  const OdometryIncrement inc = decompose_odometry(prev, now);
  ASSERT_TRUE(inc.backwards);
  Eigen::Vector3d mean;
  Eigen::Matrix3d cov;
  diff_drive_pose_moments(inc, kNoise, pose, mean, cov);
  // Heading variance is 2 a2 trans^2 = 0.02; a rotate-pi reading would add 2 a1 pi^2 = 0.39.
  EXPECT_NEAR(cov(2, 2), 2 * kNoise.a2, 1e-15);
  const auto s =
      sample_poses(MotionModelKind::kDifferentialDrive, kNoise, prev, now, pose, mean(2), 23);
  const Moments m = moments_of(s);
  expect_moments(m, mean, cov);
  // It moved back along its heading.
  const double along =
      (m.mean(0) - pose.x) * std::cos(pose.theta) + (m.mean(1) - pose.y) * std::sin(pose.theta);
  EXPECT_LT(along, -0.9);
}

TEST(MotionModel, PureRotationSpreadsOnlyAlongHeading) {
  const Pose2 prev{0, 0, 0.2};
  const Pose2 now{0, 0, 1.1};
  const Pose2 pose{1.0, 2.0, -0.4};
  const OdometryIncrement inc = decompose_odometry(prev, now);
  Eigen::Vector3d mean;
  Eigen::Matrix3d cov;
  diff_drive_pose_moments(inc, kNoise, pose, mean, cov);
  EXPECT_NEAR(cov(2, 2), kNoise.a1 * 0.81, 1e-15);
  const auto s =
      sample_poses(MotionModelKind::kDifferentialDrive, kNoise, prev, now, pose, mean(2), 24);
  expect_moments(moments_of(s), mean, cov);
}

TEST(MotionModel, OmniNoiseAlongAcrossAndRotation) {
  const Pose2 prev{0, 0, 0};
  const Pose2 now = prev.compose({0.3, -0.9, 0.5});  // mostly sideways
  const OdometryIncrement inc = decompose_odometry(prev, now);
  const double dir = inc.backwards ? inc.rot1 + kPi : inc.rot1;
  const double c = std::cos(dir), sn = std::sin(dir);
  Rng rng(31);
  std::vector<Sample> s;
  s.reserve(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const Pose2 p = sample_motion(MotionModelKind::kOmnidirectional, kNoise, inc, {}, rng);
    s.push_back({c * p.x + sn * p.y, -sn * p.x + c * p.y, p.theta});
  }
  const double t = std::hypot(0.3, 0.9), rot = 0.5;
  const Eigen::Matrix3d cov = Eigen::Vector3d(kNoise.a3 * t * t + kNoise.a4 * rot * rot,
                                              kNoise.a5 * t * t + kNoise.a4 * rot * rot,
                                              kNoise.a1 * rot * rot + kNoise.a2 * t * t)
                                  .asDiagonal();
  expect_moments(moments_of(s), {t, 0.0, rot}, cov);
}

TEST(MotionModel, OmniPoseIsGaussianRotatedIntoTheParticleFrame) {
  const Pose2 prev{1, 1, -2.0};
  const Pose2 now = prev.compose({-0.7, 0.2, -0.3});  // backwards and sideways
  const Pose2 pose{0.0, 0.0, -3.0};
  const OdometryIncrement inc = decompose_odometry(prev, now);
  ASSERT_TRUE(inc.backwards);
  const double t = inc.trans, rot = -0.3;
  const double va = kNoise.a3 * t * t + kNoise.a4 * rot * rot;
  const double vc = kNoise.a5 * t * t + kNoise.a4 * rot * rot;
  const double vr = kNoise.a1 * rot * rot + kNoise.a2 * t * t;
  // Linear in the along/across noise: mean is pose o delta, covariance R diag(va, vc) R^T.
  const Pose2 m = pose.compose({-0.7, 0.2, -0.3});
  const double ang = pose.theta + std::atan2(0.2, -0.7);
  Eigen::Matrix2d r;
  r << std::cos(ang), -std::sin(ang), std::sin(ang), std::cos(ang);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.topLeftCorner<2, 2>() = r * Eigen::Vector2d(va, vc).asDiagonal() * r.transpose();
  cov(2, 2) = vr;
  const auto s = sample_poses(MotionModelKind::kOmnidirectional, kNoise, prev, now, pose,
                              pose.theta + rot, 32);
  expect_moments(moments_of(s), {m.x, m.y, pose.theta + rot}, cov);
}

TEST(MotionModel, NoisyIncrementIsASampleFromTheIdentity) {
  const Pose2 prev{3, 1, 2.5};
  const Pose2 now = prev.compose({0.5, 0.05, 0.9});
  for (const auto kind : {MotionModelKind::kDifferentialDrive, MotionModelKind::kOmnidirectional}) {
    Rng a(41), b(41);
    for (int i = 0; i < 100; ++i) {
      const Pose2 inc = sample_noisy_increment(kind, kNoise, prev, now, a);
      const Pose2 ref = sample_motion(kind, kNoise, prev, now, {}, b);
      EXPECT_EQ(inc.x, ref.x);
      EXPECT_EQ(inc.y, ref.y);
      EXPECT_EQ(inc.theta, ref.theta);
    }
  }
  // And its moments are those of Table 5.6 from the identity.
  Eigen::Vector3d mean;
  Eigen::Matrix3d cov;
  diff_drive_pose_moments(decompose_odometry(prev, now), kNoise, {}, mean, cov);
  Rng rng(42);
  std::vector<Sample> s;
  s.reserve(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const Pose2 p =
        sample_noisy_increment(MotionModelKind::kDifferentialDrive, kNoise, prev, now, rng);
    s.push_back({p.x, p.y, mean(2) + wrap_angle(p.theta - mean(2))});
  }
  expect_moments(moments_of(s), mean, cov);
}

}  // namespace
}  // namespace pgmcl
