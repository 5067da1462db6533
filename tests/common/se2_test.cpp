// Property tests for the SE(2) maths of pgmcl/common/se2.hpp.

#include "pgmcl/common/se2.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "pgmcl/common/random.hpp"

namespace pgmcl {
namespace {

constexpr double kPi = std::numbers::pi;

Pose2 random_pose(Rng& rng, double extent) {
  return {rng.uniform(-extent, extent), rng.uniform(-extent, extent), rng.uniform(-kPi, kPi)};
}

void expect_pose_near(const Pose2& a, const Pose2& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(wrap_angle(a.theta - b.theta), 0.0, tol);
  EXPECT_TRUE(a.theta > -kPi && a.theta <= kPi) << a.theta;
}

TEST(Se2, ComposeWithInverseIsIdentity) {
  Rng rng(1);
  for (int i = 0; i < 10000; ++i) {
    const double extent = i % 2 == 0 ? 10.0 : 1e4;
    const Pose2 p = random_pose(rng, extent);
    const double tol = 1e-15 * extent * 8;
    expect_pose_near(p.compose(p.inverse()), Pose2{}, tol);
    expect_pose_near(p.inverse().compose(p), Pose2{}, tol);
    expect_pose_near(p.inverse().inverse(), p, tol);
  }
}

TEST(Se2, ComposeIsAssociativeAndBetweenRoundTrips) {
  Rng rng(2);
  for (int i = 0; i < 10000; ++i) {
    const Pose2 a = random_pose(rng, 50), b = random_pose(rng, 50), c = random_pose(rng, 50);
    expect_pose_near(a.compose(b).compose(c), a.compose(b.compose(c)), 1e-12);
    expect_pose_near(a.compose(a.between(b)), b, 1e-12);
    expect_pose_near(a.between(b).inverse(), b.between(a), 1e-12);
    double px = 0.0, py = 0.0;
    a.transform_point(b.x, b.y, px, py);
    const Pose2 ab = a.compose(b);
    EXPECT_NEAR(px, ab.x, 1e-12);
    EXPECT_NEAR(py, ab.y, 1e-12);
  }
}

TEST(Se2, KnownComposition) {
  // Quarter turn: (1, 0) in the frame at (1, 2, pi/2) is (1, 3) in the parent.
  const Pose2 r = Pose2{1, 2, kPi / 2}.compose({1, 0, kPi / 2});
  EXPECT_NEAR(r.x, 1.0, 1e-15);
  EXPECT_NEAR(r.y, 3.0, 1e-15);
  EXPECT_NEAR(r.theta, kPi, 1e-15);  // pi, not -pi
}

TEST(Se2, WrapAngleRangeIdempotenceAndCongruence) {
  Rng rng(3);
  for (int i = 0; i < 100000; ++i) {
    const double a = rng.uniform(-1e4, 1e4);
    const double w = wrap_angle(a);
    ASSERT_TRUE(w > -kPi && w <= kPi) << a;
    EXPECT_EQ(wrap_angle(w), w);
    // Congruent mod 2 pi (libm reduces sin/cos exactly, so this is an independent check).
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-11);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-11);
  }
  EXPECT_EQ(wrap_angle(kPi), kPi);
  EXPECT_EQ(wrap_angle(-kPi), kPi);  // the range is half-open: -pi maps to pi
  EXPECT_EQ(wrap_angle(0.0), 0.0);
  EXPECT_NEAR(wrap_angle(2 * kPi + 0.5), 0.5, 1e-15);
  EXPECT_NEAR(wrap_angle(-2 * kPi - 0.5), -0.5, 1e-15);
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::quiet_NaN())));
}

TEST(Se2, WrapAngleHugeAndSeamInputs) {
  Rng rng(4);
  for (int i = 0; i < 20000; ++i) {
    const double a = std::ldexp(rng.uniform(-1, 1), static_cast<int>(rng.below(1000)));
    const double w = wrap_angle(a);
    ASSERT_TRUE(w > -kPi && w <= kPi) << a;
    EXPECT_EQ(wrap_angle(w), w);
  }
  // Odd multiples of pi and their neighbours, in double and float. float(3 pi) used to
  // round to -float(pi), which is below -pi.
  for (long k = -20000; k <= 20000; ++k) {
    double a = kPi * static_cast<double>(2 * k + 1);
    for (int j = 0; j < 3; ++j, a = std::nextafter(a, 1e300)) {
      const double w = wrap_angle(a);
      ASSERT_TRUE(w > -kPi && w <= kPi) << a;
      const float wf = wrap_angle(static_cast<float>(a));
      ASSERT_TRUE(wf > -std::numbers::pi_v<float> && wf <= std::numbers::pi_v<float>) << a;
      EXPECT_EQ(wrap_angle(wf), wf);
    }
  }
}

TEST(Se2, CircularMeanAtPi) {
  CircularMean m;
  m.add(179.0 * kPi / 180.0);
  m.add(-179.0 * kPi / 180.0);
  EXPECT_NEAR(std::abs(m.mean()), kPi, 1e-12);  // 180 degrees, not 0
  EXPECT_NEAR(m.resultant_length(2.0), std::cos(kPi / 180.0), 1e-12);

  CircularMean weighted;  // 3:1 between 170 and -170 degrees -> 175 degrees
  weighted.add(170.0 * kPi / 180.0, 3.0);
  weighted.add(-170.0 * kPi / 180.0, 1.0);
  const double a = 170.0 * kPi / 180.0;
  const double expected =
      std::atan2(3 * std::sin(a) + std::sin(-a), 3 * std::cos(a) + std::cos(-a));
  EXPECT_NEAR(weighted.mean(), expected, 1e-12);
  EXPECT_GT(weighted.mean(), 170.0 * kPi / 180.0);

  CircularMean opposite;  // no preferred direction
  opposite.add(0.3);
  opposite.add(0.3 + kPi);
  EXPECT_NEAR(opposite.resultant_length(2.0), 0.0, 1e-12);
  EXPECT_EQ(CircularMean{}.resultant_length(0.0), 0.0);
}

}  // namespace
}  // namespace pgmcl
