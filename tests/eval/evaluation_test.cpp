// ATE against ground truth: known offsets, interpolation, headings across +-pi, convergence.

#include "pgmcl/eval/evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io_test_util.hpp"
#include "pgmcl/io/carmen.hpp"

namespace pgmcl::io {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Straight line along x at 1 m/s, heading ~pi (so errors straddle the wrap), 1 Hz.
Trajectory line_truth(std::size_t n) {
  Trajectory t;
  for (std::size_t i = 0; i < n; ++i) {
    t.push_back({static_cast<double>(i), {static_cast<double>(i), 1.0, std::numbers::pi - 0.01}});
  }
  return t;
}

TEST(Ate, KnownOffsetGivesExactRmseAndHeading) {
  const Trajectory truth = line_truth(20);
  Trajectory est = truth;
  for (StampedPose& p : est) {
    p.pose.x += 0.3;
    p.pose.y -= 0.4;                                       // 0.5 m
    p.pose.theta = wrap_angle(p.pose.theta + 5.0 * kDeg);  // crosses +pi
  }
  AteOptions opt;
  opt.converged_translation = 0.6;  // above the constant 0.5 m error
  const AteResult r = evaluate_ate(est, truth, opt);
  EXPECT_EQ(r.matched, 20u);
  EXPECT_EQ(r.unmatched, 0u);
  EXPECT_NEAR(r.translation.rms, 0.5, 1e-12);
  EXPECT_NEAR(r.translation.max, 0.5, 1e-12);
  EXPECT_NEAR(r.heading.rms, 5.0, 1e-9);
  EXPECT_NEAR(r.heading.max, 5.0, 1e-9);
  ASSERT_TRUE(r.converged_after_s.has_value());
  EXPECT_EQ(*r.converged_after_s, 0.0);
  opt.converged_translation = 0.4;
  EXPECT_FALSE(evaluate_ate(est, truth, opt).converged_after_s.has_value());
}

TEST(Ate, InterpolatesTruthBetweenStampsOrTakesTheNearest) {
  const Trajectory truth = line_truth(10);
  Trajectory est;  // on the true line at half-second stamps, plus one past the end
  for (double t = 0.5; t < 9.0; t += 1.0) est.push_back({t, {t, 1.0, std::numbers::pi - 0.01}});
  est.push_back({9.02, {9.02, 1.0, std::numbers::pi - 0.01}});
  est.push_back({12.0, {12.0, 1.0, 0.0}});  // 3 s past the truth: unmatched
  AteResult r = evaluate_ate(est, truth);
  EXPECT_EQ(r.matched, 10u);
  EXPECT_EQ(r.unmatched, 1u);
  EXPECT_NEAR(r.translation.max, 0.02, 1e-9);  // the 9.02 s pose, matched to 9 s
  EXPECT_NEAR(r.heading.max, 0.0, 1e-9);

  AteOptions nearest;
  nearest.association = Association::kNearest;
  nearest.tolerance = 0.6;
  r = evaluate_ate(est, truth, nearest);
  EXPECT_EQ(r.matched, 10u);
  EXPECT_NEAR(r.translation.max, 0.5, 1e-9);  // half a second off a 1 m/s truth

  AteOptions shifted;  // estimate clock 100 s behind the truth clock
  shifted.time_offset = 100.0;
  Trajectory late = truth;
  for (StampedPose& p : late) p.stamp -= 100.0;
  r = evaluate_ate(late, truth, shifted);
  EXPECT_EQ(r.matched, 10u);
  EXPECT_NEAR(r.translation.max, 0.0, 1e-12);
}

TEST(Ate, ConvergedAfterTheLastBadPose) {
  const Trajectory truth = line_truth(30);
  Trajectory est = truth;
  for (std::size_t i = 0; i < est.size(); ++i) {
    if (i < 8) est[i].pose.y += 2.0;                // lost, in translation
    if (i == 11) est[i].pose.theta += 15.0 * kDeg;  // one late heading outlier
    if (i >= 12) est[i].pose.x += 0.2;              // tracking within 0.5 m
  }
  AteOptions opt;
  opt.converged_translation = 0.5;
  opt.converged_rotation_deg = 10.0;
  AteResult r = evaluate_ate(est, truth, opt);
  ASSERT_TRUE(r.converged_after_s.has_value());
  EXPECT_DOUBLE_EQ(*r.converged_after_s, 12.0);
  opt.converged_rotation_deg = 20.0;  // the heading outlier no longer counts
  r = evaluate_ate(est, truth, opt);
  EXPECT_DOUBLE_EQ(*r.converged_after_s, 8.0);
  est.back().pose.y += 1.0;  // diverged at the end: never converged
  EXPECT_FALSE(evaluate_ate(est, truth, opt).converged_after_s.has_value());
  EXPECT_NEAR(evaluate_ate(est, truth, opt).translation.max, 2.0, 1e-12);
}

TEST(Ate, IntelGroundTruthAgainstItselfAndAShiftedCopy) {
  const CarmenLog log = read_carmen(test::data_path("logs/intel-corrected.log.gz"));
  const Trajectory truth = scan_truth(log);
  EXPECT_EQ(evaluate_ate(truth, truth).translation.max, 0.0);
  Trajectory est = truth;
  for (StampedPose& p : est) p.pose = p.pose.compose({0.1, 0.0, 0.0});  // 10 cm forward
  const AteResult r = evaluate_ate(est, truth);
  EXPECT_EQ(r.matched, 910u);
  EXPECT_NEAR(r.translation.rms, 0.1, 1e-9);
  EXPECT_NEAR(r.heading.rms, 0.0, 1e-9);
}

}  // namespace
}  // namespace pgmcl::io
