// Kümmerle et al. (2009) relative-pose metric on synthetic perturbations with known answers,
// and on the bundled Intel log against its benchmark relations.

#include "pgmcl/io/relations.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "io_test_util.hpp"
#include "pgmcl/eval/relations_error.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/errors.hpp"

namespace pgmcl::io {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A winding trajectory with headings across +-pi, stamped every 0.5 s from `t0`.
Trajectory winding(double t0, std::size_t n) {
  Trajectory t;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i);
    t.push_back({t0 + 0.5 * s,
                 {3.0 * std::cos(0.1 * s), 2.0 * std::sin(0.13 * s) + 0.05 * s,
                  wrap_angle(2.9 + 0.21 * s)}});
  }
  return t;
}

TEST(Relations, TranslationOffByExactlyTenCentimetres) {
  const double offset = 1000.0;  // relation clock = estimate clock + 1000 s
  const Trajectory truth = winding(0.0, 60);
  std::vector<Relation> rel;
  for (std::size_t i = 0; i + 7 < truth.size(); ++i) {
    const std::size_t j = i + 1 + i % 7;
    Relation r;
    // Stamps off by up to 4 ms: still the nearest pose within the 20 ms tolerance.
    r.t1 = truth[i].stamp + offset + 0.004;
    r.t2 = truth[j].stamp + offset - 0.003;
    r.delta = truth[i].pose.between(truth[j].pose);
    const double phi = 0.7 * static_cast<double>(i);  // any direction, exactly 0.1 m
    r.delta.x += 0.1 * std::cos(phi);
    r.delta.y += 0.1 * std::sin(phi);
    r.delta.theta = wrap_angle(r.delta.theta + (i % 2 == 0 ? 2.0 : -2.0) * kDeg);
    rel.push_back(r);
  }
  Relation far;  // no estimate pose near t2
  far.t1 = offset;
  far.t2 = offset + 0.25;
  rel.push_back(far);
  Relation close;  // ends 10 ms apart: cannot be told apart by stamp
  close.t1 = truth[4].stamp + offset;
  close.t2 = close.t1 + 0.01;
  close.delta = {0.3, 0, 0};
  rel.push_back(close);

  RelationOptions opt;
  opt.time_offset = offset;
  const RelationResult res = evaluate_relations(truth, rel, opt);
  EXPECT_EQ(res.relations, rel.size());
  EXPECT_EQ(res.unmatched, 1u);
  EXPECT_EQ(res.degenerate, 1u);
  ASSERT_EQ(res.matched, rel.size() - 2);
  EXPECT_NEAR(res.translation.mean, 0.1, 1e-9);
  EXPECT_NEAR(res.translation.stddev, 0.0, 1e-9);
  EXPECT_NEAR(res.translation_sq.mean, 0.01, 1e-9);
  EXPECT_NEAR(res.rotation.mean, 2.0, 1e-9);
  EXPECT_NEAR(res.rotation.stddev, 0.0, 1e-9);
  EXPECT_NEAR(res.rotation_sq.mean, 4.0, 1e-8);
  EXPECT_NEAR(res.max_time_error, 0.004, 1e-6);

  // Without the offset nothing matches.
  EXPECT_EQ(evaluate_relations(truth, rel).matched, 0u);
}

TEST(Relations, MixedErrorsGiveTheTableStatistics) {
  // Two relations with errors 0.1 m and 0.3 m: mean 0.2 +- 0.1414 (sample std), squared
  // mean 0.05 +- 0.0566.
  const Trajectory est = {{0, {0, 0, 0}}, {1, {1, 0, 0}}, {2, {2, 0, 0}}};
  std::vector<Relation> rel(2);
  rel[0] = {0, 1, {1.1, 0, 0}, 0, 0, 0, 0};
  rel[1] = {1, 2, {1, 0.3, 0}, 0, 0, 0, 0};
  const RelationResult res = evaluate_relations(est, rel);
  ASSERT_EQ(res.matched, 2u);
  EXPECT_NEAR(res.translation.mean, 0.2, 1e-12);
  EXPECT_NEAR(res.translation.stddev, std::sqrt(0.02), 1e-12);
  EXPECT_NEAR(res.translation_sq.mean, 0.05, 1e-12);
  EXPECT_NEAR(res.translation_sq.stddev, std::sqrt(2 * 0.04 * 0.04), 1e-12);
  EXPECT_NEAR(res.errors[1].translation, 0.3, 1e-12);
}

TEST(Relations, InterpolationReachesStampsBetweenPoses) {
  const Trajectory est = {{0, {0, 0, 0}}, {2, {2, 0, 0}}, {4, {2, 2, std::numbers::pi / 2}}};
  std::vector<Relation> rel(1);
  rel[0] = {1, 3, {1, 1, std::numbers::pi / 4}, 0, 0, 0, 0};  // (1,0,0) -> (2,1,pi/4)
  EXPECT_EQ(evaluate_relations(est, rel).matched, 0u);
  RelationOptions opt;
  opt.interpolate = true;
  opt.max_gap = 2.0;
  const RelationResult res = evaluate_relations(est, rel, opt);
  ASSERT_EQ(res.matched, 1u);
  EXPECT_NEAR(res.translation.mean, 0.0, 1e-12);
  EXPECT_NEAR(res.rotation.mean, 0.0, 1e-12);
  opt.max_gap = 1.5;
  EXPECT_EQ(evaluate_relations(est, rel, opt).matched, 0u);
}

TEST(Relations, ParseErrorsNameLineAndField) {
  const auto rel = parse_relations("# c\n1 2 0.5 0.25 0 0 0 3.5\n", "r");
  ASSERT_EQ(rel.size(), 1u);
  EXPECT_EQ(rel[0].line, 2u);
  EXPECT_NEAR(rel[0].delta.theta, 3.5 - 2 * std::numbers::pi, 1e-15);
  try {
    (void)parse_relations("1 2 0 0 0 0 0 0\n1 2 0 0 0 0 nan 0\n", "r.rel");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_EQ(std::string(e.what()), "r.rel:2: pitch: not finite: 'nan'");
  }
  EXPECT_THROW((void)parse_relations("1 2 0 0 0 0 0\n", "r"), FormatError);
}

// The gmapping-corrected Intel poses against the benchmark relations. Only relations whose
// two stamps both fall within 20 ms of one of the log's 910 scans can be scored, and 59 have
// stamps within 20 ms of each other (degenerate): 115 scored, 59 degenerate (both counted
// independently with python over the two files).
TEST(Relations, IntelCorrectedPosesAgainstBenchmark) {
  const auto rel = read_relations(test::data_path("relations/intel.relations.gz"));
  ASSERT_EQ(rel.size(), 2984u);
  const CarmenLog log = read_carmen(test::data_path("logs/intel-corrected.log.gz"));
  RelationOptions opt;
  opt.time_offset = kIntelRelationsTimeOffset;
  const RelationResult res = evaluate_relations(scan_truth(log), rel, opt);
  EXPECT_EQ(res.matched, 115u);
  EXPECT_EQ(res.degenerate, 59u);
  EXPECT_EQ(res.unmatched, 2984u - 115u - 59u);
  EXPECT_LE(res.max_time_error, 0.02);
  // A SLAM-corrected map scores centimetres and about a degree; a time offset 20 ms off
  // already doubles both (0.14 m, 3.6 deg) and a wrong frame convention gives metres.
  EXPECT_LT(res.translation.mean, 0.08);
  EXPECT_LT(res.rotation.mean, 2.0);
  opt.time_offset += 0.02;
  const RelationResult shifted = evaluate_relations(scan_truth(log), rel, opt);
  EXPECT_GT(shifted.translation.mean, 2 * res.translation.mean);
  RecordProperty("intel_trans_mean_m", std::to_string(res.translation.mean));
  RecordProperty("intel_rot_mean_deg", std::to_string(res.rotation.mean));
}

}  // namespace
}  // namespace pgmcl::io
