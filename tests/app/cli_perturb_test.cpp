// `pgmcl perturb`: noisy odometry from ground-truth increments.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "perturb_test_util.hpp"
#include "pgmcl/common/motion_model.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::perturb_test {
namespace {

TEST(CliPerturb, ZeroNoiseReproducesTruthIncrements) {
  TempDir dir("cli_perturb_zero");
  const auto poses = zigzag(50, 0.3, 0.4, -0.5);
  write_log(dir, poses);
  const RunResult r = run_perturb(dir, "--odom-noise 0,0,0,0 --seed 3");
  ASSERT_EQ(r.code, 0) << r.err;
  const Output o = read_output(dir);
  ASSERT_EQ(o.truth.size(), poses.size());
  ASSERT_EQ(o.raw.scans.size(), poses.size());
  ASSERT_EQ(o.raw.odometry.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(o.truth[i].pose.x, poses[i].x, 1e-12);
    EXPECT_NEAR(o.truth[i].pose.theta, poses[i].theta, 1e-12);
    EXPECT_DOUBLE_EQ(o.raw.odometry[i].stamp, o.raw.scans[i].stamp);
    if (i == 0) continue;
    const Pose2 t = poses[i - 1].between(poses[i]);
    for (const Pose2 odom_inc : {o.raw.scans[i - 1].odom_pose.between(o.raw.scans[i].odom_pose),
                                 o.raw.scans[i - 1].laser_pose.between(o.raw.scans[i].laser_pose),
                                 o.raw.odometry[i - 1].pose.between(o.raw.odometry[i].pose)}) {
      EXPECT_NEAR(odom_inc.x, t.x, 1e-9) << i;
      EXPECT_NEAR(odom_inc.y, t.y, 1e-9) << i;
      EXPECT_NEAR(wrap_angle(odom_inc.theta - t.theta), 0.0, 1e-9) << i;
    }
  }
  // Same scans: the ranges are copied through.
  EXPECT_EQ(o.raw.scans[7].scan.ranges,
            cli_test::room_log(cli_test::Room{}, poses, 5).scans[7].scan.ranges);
}

TEST(CliPerturb, SeededRunsAreReproducible) {
  TempDir dir("cli_perturb_seed");
  write_log(dir, zigzag(40, 0.1, 0.5, 0.05));
  const std::string noise = "--odom-noise 0.01,0.001,0.01,0.001 ";
  ASSERT_EQ(run_perturb(dir, noise + "--seed 11").code, 0);
  const std::string a = cli_test::read_text(dir.file("raw.log"));
  ASSERT_EQ(run_perturb(dir, noise + "--seed 11").code, 0);
  EXPECT_EQ(cli_test::read_text(dir.file("raw.log")), a);
  ASSERT_EQ(run_perturb(dir, noise + "--seed 12").code, 0);
  EXPECT_NE(cli_test::read_text(dir.file("raw.log")), a);
}

// The increments' errors have the variances of Probabilistic Robotics Table 5.6.
TEST(CliPerturb, IncrementNoiseMatchesTheAlphaModel) {
  TempDir dir("cli_perturb_stats");
  const double rot1 = 0.2, trans = 0.5, rot2 = -0.1;
  const int n = 3001;
  write_log(dir, zigzag(n, rot1, trans, rot2), 1);
  const double a1 = 0.01, a2 = 0.002, a3 = 0.01, a4 = 0.004;
  const RunResult r = run_perturb(dir, "--odom-noise 0.01,0.002,0.01,0.004 --seed 5 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const Output o = read_output(dir);
  ASSERT_EQ(o.raw.odometry.size(), static_cast<std::size_t>(n));
  double s1 = 0, st = 0, s2 = 0, m1 = 0, mt = 0, m2 = 0;
  for (int i = 1; i < n; ++i) {
    const OdometryIncrement inc =
        decompose_odometry(o.raw.odometry[i - 1].pose, o.raw.odometry[i].pose);
    ASSERT_FALSE(inc.backwards);
    const double e1 = wrap_angle(inc.rot1 - rot1), et = inc.trans - trans,
                 e2 = wrap_angle(inc.rot2 - rot2);
    m1 += e1, mt += et, m2 += e2;
    s1 += e1 * e1, st += et * et, s2 += e2 * e2;
  }
  const double m = n - 1;
  const double v1 = a1 * rot1 * rot1 + a2 * trans * trans;
  const double vt = a3 * trans * trans + a4 * (rot1 * rot1 + rot2 * rot2);
  const double v2 = a1 * rot2 * rot2 + a2 * trans * trans;
  // 3000 samples: the sample variance is within ~8 % (3 sigma) of the truth.
  EXPECT_NEAR(s1 / m / v1, 1.0, 0.1);
  EXPECT_NEAR(st / m / vt, 1.0, 0.1);
  EXPECT_NEAR(s2 / m / v2, 1.0, 0.1);
  EXPECT_NEAR(m1 / m, 0.0, 4.0 * std::sqrt(v1 / m));
  EXPECT_NEAR(mt / m, 0.0, 4.0 * std::sqrt(vt / m));
  EXPECT_NEAR(m2 / m, 0.0, 4.0 * std::sqrt(v2 / m));
}

TEST(CliPerturb, BiasScalesTranslationAndDriftsHeading) {
  TempDir dir("cli_perturb_bias");
  const auto poses = zigzag(20, 0.0, 0.5, 0.1);
  write_log(dir, poses);
  const RunResult r =
      run_perturb(dir, "--odom-noise 0,0,0,0 --seed 1 --scale-bias 0.02 --yaw-drift 0.5");
  ASSERT_EQ(r.code, 0) << r.err;
  const Output o = read_output(dir);
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const Pose2 d = o.raw.odometry[i - 1].pose.between(o.raw.odometry[i].pose);
    EXPECT_NEAR(std::hypot(d.x, d.y), 0.5 * 1.02, 1e-9);
    EXPECT_NEAR(d.theta, 0.1 + 0.5 * 0.5 * std::numbers::pi / 180.0, 1e-9);
  }
}

TEST(CliPerturb, BadArgumentsAreUsageErrors) {
  TempDir dir("cli_perturb_bad");
  write_log(dir, zigzag(5, 0.1, 0.5, 0.0));
  RunResult r = run_pgmcl(
      "perturb --log in.log --odom-noise 0.1,0.1,0.1 --seed 1 --out raw.log --truth-out t.tum",
      dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--odom-noise: expected A1,A2,A3,A4"), std::string::npos) << r.err;
  r = run_pgmcl(
      "perturb --log in.log --odom-noise 0.1,-0.1,0.1,0 --seed 1 --out raw.log --truth-out t.tum",
      dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("A2 must be in [0, 100]"), std::string::npos) << r.err;
  r = run_pgmcl("perturb --log in.log --odom-noise 0,0,0,0 --out raw.log --truth-out t.tum", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--seed"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pgmcl::perturb_test
