// `pgmcl eval`: ATE and relations figures against exact oracles.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "cli_test_util.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl {
namespace {

using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

io::Trajectory circle(int n) {
  io::Trajectory t;
  for (int i = 0; i < n; ++i) {
    const double a = 0.05 * i;
    t.push_back({10.0 + i * 0.5, {3.0 * std::cos(a), 3.0 * std::sin(a), wrap_angle(a + 1.5708)}});
  }
  return t;
}

/// Writes est.tum and truth.tum into `dir` and runs `pgmcl eval` on them into m.yaml.
RunResult eval_to_yaml(const TempDir& dir, const io::Trajectory& est, const io::Trajectory& truth) {
  io::write_tum(dir.file("truth.tum"), truth);
  io::write_tum(dir.file("est.tum"), est);
  return run_pgmcl("eval --estimate est.tum --truth truth.tum --out m.yaml", dir);
}

TEST(CliEval, ShiftedEstimateGivesTheShiftAsAteAndZeroRelationsError) {
  TempDir dir("cli_eval_shift");
  const io::Trajectory truth = circle(100);
  io::Trajectory est = truth;
  for (auto& p : est) {
    p.pose.x += 0.06;
    p.pose.y -= 0.08;  // |shift| = 0.1 m, the same for every pose
  }
  est[10].pose.theta = wrap_angle(est[10].pose.theta + 0.1);  // one heading error of 0.1 rad
  io::write_tum(dir.file("truth.tum"), truth);
  io::write_tum(dir.file("est.tum"), est);
  // Relations between truth poses, stamped +100 s (needs --time-offset 100).
  std::string rel;
  for (int i = 20; i + 5 < 100; i += 5) {
    const Pose2 d = truth[i].pose.between(truth[i + 5].pose);
    char line[256];
    std::snprintf(line, sizeof line, "%.6f %.6f %.17g %.17g 0 0 0 %.17g\n", truth[i].stamp + 100,
                  truth[i + 5].stamp + 100, d.x, d.y, d.theta);
    rel += line;
  }
  cli_test::write_text(dir.file("r.relations"), rel);

  const RunResult r = run_pgmcl(
      "eval --estimate est.tum --truth truth.tum --relations r.relations --time-offset 100 "
      "--out out/eval.yaml",
      dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(dir.file("out/eval.yaml"));
  EXPECT_NEAR(y["ate_rmse_m"].as<double>(), 0.1, 1e-6);
  EXPECT_NEAR(y["ate_max_m"].as<double>(), 0.1, 1e-6);
  EXPECT_NEAR(y["heading_rmse_deg"].as<double>(), 0.1 * 180 / M_PI / std::sqrt(100.0), 1e-4);
  EXPECT_EQ(y["truth_matched"].as<int>(), 100);
  EXPECT_EQ(y["relations_used"].as<int>(), 15);
  EXPECT_NEAR(y["relations_trans_m"].as<double>(), 0.0, 1e-6);
  EXPECT_NEAR(y["relations_rot_deg"].as<double>(), 0.0, 1e-4);
  EXPECT_FALSE(y["updates"]);  // no filter figures for a trajectory file
  EXPECT_NE(r.out.find("ate_rmse_m"), std::string::npos);
}

TEST(CliEval, BadTrajectoryLineNamesFileLineAndField) {
  TempDir dir("cli_eval_bad");
  io::write_tum(dir.file("truth.tum"), circle(10));
  cli_test::write_text(dir.file("est.tum"), "# header\n1.0 0 0 0 0 0 0 1\n2.0 0 zero 0 0 0 0 1\n");
  const RunResult r = run_pgmcl("eval --estimate est.tum --truth truth.tum", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("pgmcl: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("est.tum:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("ty"), std::string::npos) << r.err;
}

TEST(CliEval, NoOverlapInTimeIsAnErrorBeforeAnyFigure) {
  TempDir dir("cli_eval_overlap");
  io::Trajectory late = circle(10);
  for (auto& p : late) p.stamp += 1000.0;
  io::write_tum(dir.file("truth.tum"), circle(10));
  io::write_tum(dir.file("est.tum"), late);
  const RunResult r = run_pgmcl("eval --estimate est.tum --truth truth.tum", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no estimate pose matched"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--truth-offset"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("ate_rmse_m"), std::string::npos) << r.out;  // no "ate_rmse_m 0"
}

TEST(CliEval, APartialMatchWarnsAndReportsTheMatchedFraction) {
  // 100 estimate poses, the last 40 past the truth's end: 60 are scored.
  TempDir dir("cli_eval_partial");
  const io::Trajectory est = circle(100);
  const RunResult r = eval_to_yaml(dir, est, io::Trajectory(est.begin(), est.begin() + 60));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pgmcl: warning: est.tum: only 60 of 100 estimate poses (60 %) have a "
                       "ground-truth pose"),
            std::string::npos)
      << r.err;
  const YAML::Node y = YAML::LoadFile(dir.file("m.yaml"));
  EXPECT_EQ(y["truth_matched"].as<int>(), 60);
  EXPECT_DOUBLE_EQ(y["truth_matched_fraction"].as<double>(), 0.6);
  // A whole match: no warning, fraction 1.
  const RunResult whole =
      run_pgmcl("eval --estimate truth.tum --truth truth.tum --out w.yaml", dir);
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_EQ(whole.err.find("warning"), std::string::npos) << whole.err;
  EXPECT_EQ(YAML::LoadFile(dir.file("w.yaml"))["truth_matched_fraction"].as<double>(), 1.0);
  EXPECT_EQ(YAML::LoadFile(dir.file("w.yaml"))["truth_covered_fraction"].as<double>(), 1.0);
}

TEST(CliEval, AnEstimateOfPartOfTheTruthWarnsAndReportsTheCoveredFraction) {
  // Every one of the 20 estimate poses matches, but they span 19 of the truth's 99 steps.
  TempDir dir("cli_eval_covered");
  const io::Trajectory truth = circle(100);
  const RunResult r =
      eval_to_yaml(dir, io::Trajectory(truth.begin() + 30, truth.begin() + 50), truth);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pgmcl: warning: est.tum: the matched estimate poses cover only 19 % of "
                       "the ground truth's time span (25.000 to 34.500 s of 10.000 to 59.500 s)"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("estimate poses ("), std::string::npos) << "every estimate pose matched";
  const YAML::Node y = YAML::LoadFile(dir.file("m.yaml"));
  EXPECT_DOUBLE_EQ(y["truth_matched_fraction"].as<double>(), 1.0);
  EXPECT_NEAR(y["truth_covered_fraction"].as<double>(), 19.0 / 99.0, 1e-6);
}

TEST(CliEval, TimeOffsetWithoutRelationsAndToleranceShiftAndWidenTheTruthMatch) {
  TempDir dir("cli_eval_offset");
  const io::Trajectory truth = circle(100);
  io::Trajectory est = truth;
  for (auto& p : est) p.stamp += 0.2;  // the estimate's clock is 0.2 s ahead
  io::write_tum(dir.file("truth.tum"), truth);
  io::write_tum(dir.file("est.tum"), est);
  RunResult r = run_pgmcl("eval --estimate est.tum --truth truth.tum --out a.yaml", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(YAML::LoadFile(dir.file("a.yaml"))["ate_rmse_m"].as<double>(), 0.01);
  for (const char* opt : {"--time-offset -0.2", "--truth-offset -0.2"}) {
    r = run_pgmcl(std::string("eval --estimate est.tum --truth truth.tum --out b.yaml ") + opt,
                  dir);
    ASSERT_EQ(r.code, 0) << opt << r.err;
    const YAML::Node y = YAML::LoadFile(dir.file("b.yaml"));
    EXPECT_NEAR(y["ate_rmse_m"].as<double>(), 0.0, 1e-9) << opt;
    EXPECT_EQ(y["truth_matched"].as<int>(), 100) << opt;
  }
  // Truth every 2 s (gaps too long to interpolate), estimate 0.3 s after each truth pose:
  // nothing within the default 0.05 s, everything within --tolerance 0.5.
  io::Trajectory sparse, late;
  for (int i = 0; i < 20; ++i) {
    sparse.push_back({10.0 + 2.0 * i, {1.0 * i, 0.0, 0.0}});
    late.push_back({10.3 + 2.0 * i, {1.0 * i, 0.0, 0.0}});
  }
  io::write_tum(dir.file("sparse.tum"), sparse);
  io::write_tum(dir.file("late.tum"), late);
  r = run_pgmcl("eval --estimate late.tum --truth sparse.tum", dir);
  EXPECT_EQ(r.code, 1) << r.out;
  r = run_pgmcl("eval --estimate late.tum --truth sparse.tum --tolerance 0.5 --out c.yaml", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(YAML::LoadFile(dir.file("c.yaml"))["truth_matched"].as<int>(), 20);
}

TEST(CliEval, SaysWhatLockOnAndConvergenceMean) {
  // 10 m off for the first 10 poses, then 0.02 m: locked on at the 11th pose (5 s).
  TempDir dir("cli_eval_lock");
  const io::Trajectory truth = circle(100);
  io::Trajectory est = truth;
  for (int i = 0; i < 100; ++i) est[i].pose.x += i < 10 ? 10.0 : 0.02;
  io::write_tum(dir.file("truth.tum"), truth);
  io::write_tum(dir.file("est.tum"), est);
  const RunResult r = run_pgmcl("eval --estimate est.tum --truth truth.tum", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("eval: locked on (within 1 m from then on) at 5.0 s"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("from then on ATE RMSE 0.020 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("converged_after_s 5.0: from then on every error is within 0.5 m and "
                       "10 deg"),
            std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace pgmcl
