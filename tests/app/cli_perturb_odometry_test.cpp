// `pgmcl perturb` odometry conditions: heading and translation glitches, the textbook model.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "perturb_test_util.hpp"

namespace pgmcl::perturb_test {
namespace {

struct PerturbRun {
  RunResult result;
  Output out;
};

/// Runs perturb on in.log with `extra` options; expects success.
PerturbRun perturb(const TempDir& dir, const std::string& noise, const std::string& extra) {
  PerturbRun run;
  run.result = run_perturb(dir, "--odom-noise " + noise + " --seed 9 " + extra);
  EXPECT_EQ(run.result.code, 0) << run.result.err;
  run.out = read_output(dir);
  return run;
}

TEST(CliPerturbGlitch, EveryStepGetsABoundedHeadingErrorAtItsStart) {
  TempDir dir("cli_perturb_glitch");
  const auto poses = zigzag(60, 0.3, 0.4, -0.5);
  write_log(dir, poses);
  const PerturbRun run = perturb(dir, "0,0,0,0", "--glitch 1,30");
  EXPECT_NE(run.result.out.find("59 heading and 0 translation glitch(es)"), std::string::npos)
      << run.result.out;
  const std::vector<Pose2> inc = odometry_increments(run.out);
  ASSERT_EQ(inc.size(), poses.size() - 1);
  int negative = 0;
  for (std::size_t i = 0; i < inc.size(); ++i) {
    const Pose2 t = poses[i].between(poses[i + 1]);
    const double g = wrap_angle(inc[i].theta - t.theta);
    EXPECT_GE(std::abs(g), 24.0 * kDeg - 1e-9) << i;
    EXPECT_LE(std::abs(g), 30.0 * kDeg + 1e-9) << i;
    // Applied at the start of the step: the translation direction turns by g as well.
    EXPECT_NEAR(wrap_angle(std::atan2(inc[i].y, inc[i].x) - std::atan2(t.y, t.x) - g), 0.0, 1e-9)
        << i;
    EXPECT_NEAR(std::hypot(inc[i].x, inc[i].y), std::hypot(t.x, t.y), 1e-9) << i;
    negative += g < 0.0 ? 1 : 0;
  }
  EXPECT_GT(negative, 10);  // both signs, about half each
  EXPECT_LT(negative, 49);
}

TEST(CliPerturbGlitch, ZeroRateReproducesTheCaseWithoutGlitches) {
  TempDir dir("cli_perturb_glitch_zero");
  write_log(dir, zigzag(80, 0.1, 0.5, 0.05));
  const std::string noise = "0.01,0.001,0.01,0.001";
  const Output plain = perturb(dir, noise, "").out;
  const std::string truth = cli_test::read_text(dir.file("truth.tum"));
  for (const std::string extra :
       {"--glitch 0,30", "--translation-glitch 0,1", "--glitch 0,5 --translation-glitch 0,0.2"}) {
    SCOPED_TRACE(extra);
    const Output o = perturb(dir, noise, extra).out;
    ASSERT_EQ(o.raw.odometry.size(), plain.raw.odometry.size());
    for (std::size_t i = 0; i < o.raw.odometry.size(); ++i) {
      EXPECT_EQ(o.raw.odometry[i].pose.x, plain.raw.odometry[i].pose.x) << i;
      EXPECT_EQ(o.raw.odometry[i].pose.y, plain.raw.odometry[i].pose.y) << i;
      EXPECT_EQ(o.raw.odometry[i].pose.theta, plain.raw.odometry[i].pose.theta) << i;
      EXPECT_EQ(o.raw.scans[i].laser_pose.x, plain.raw.scans[i].laser_pose.x) << i;
    }
    EXPECT_EQ(cli_test::read_text(dir.file("truth.tum")), truth);
  }
}

TEST(CliPerturbGlitch, TranslationGlitchAddsAJumpOfFixedLength) {
  TempDir dir("cli_perturb_slip");
  const auto poses = zigzag(201, 0.2, 0.3, -0.1);
  write_log(dir, poses);
  const PerturbRun run = perturb(dir, "0,0,0,0", "--translation-glitch 0.5,0.25");
  const std::vector<Pose2> inc = odometry_increments(run.out);
  ASSERT_EQ(inc.size(), 200u);
  int jumps = 0, left = 0;
  for (std::size_t i = 0; i < inc.size(); ++i) {
    const Pose2 t = poses[i].between(poses[i + 1]);
    EXPECT_NEAR(wrap_angle(inc[i].theta - t.theta), 0.0, 1e-9) << i;
    const double jx = inc[i].x - t.x, jy = inc[i].y - t.y;
    const double len = std::hypot(jx, jy);
    if (len < 1e-9) continue;
    EXPECT_NEAR(len, 0.25, 1e-9) << i;
    ++jumps;
    left += jy > 0.0 ? 1 : 0;
  }
  // 200 steps at rate 0.5: 100 +- 4 sigma (sigma ~7); random directions, both sides.
  EXPECT_NEAR(jumps, 100, 28);
  EXPECT_NEAR(left, jumps / 2, 4 * std::sqrt(jumps / 4.0) + 1);
  EXPECT_NE(
      run.result.out.find("0 heading and " + std::to_string(jumps) + " translation glitch(es)"),
      std::string::npos)
      << run.result.out;
}

/// RMS per-step heading error of the odometry against the truth increments.
double heading_rms(const Output& o, const std::vector<Pose2>& poses) {
  const std::vector<Pose2> inc = odometry_increments(o);
  double s = 0.0;
  for (std::size_t i = 0; i < inc.size(); ++i) {
    const double e = wrap_angle(inc[i].theta - poses[i].between(poses[i + 1]).theta);
    s += e * e;
  }
  return std::sqrt(s / static_cast<double>(inc.size()));
}

// Table 5.6 as printed measures rot1 from the heading: a 3 cm backward step has
// rot1 = pi and rot2 = -pi, so rot1 and rot2 each get sqrt(a1) * pi = 12.7 deg of noise
// (a1 = 0.005). pgmcl's model flips backward motion (rot1 = 0) and fades rot1 below 5 cm.
TEST(CliPerturbModel, TextbookModelGlitchesOnShortBackwardMovesAndPgmclDoesNot) {
  TempDir dir("cli_perturb_textbook");
  const std::string noise = "0.005,0.0005,0.005,0.0005";
  const auto back = zigzag(401, std::numbers::pi, 0.03, -std::numbers::pi);
  write_log(dir, back);
  const double textbook = heading_rms(perturb(dir, noise, "--odom-model textbook").out, back);
  const double pgmcl = heading_rms(perturb(dir, noise, "--odom-model pgmcl").out, back);
  // Expected: sqrt(2 a1) pi = 18 deg for the textbook model, sqrt(a2) * 3 cm = 0.04 deg.
  EXPECT_GT(textbook, 14.0 * kDeg);
  EXPECT_LT(textbook, 22.0 * kDeg);
  EXPECT_LT(pgmcl, 0.5 * kDeg);
  // Zero noise: the textbook decomposition still reproduces the backward moves exactly.
  const Output exact = perturb(dir, "0,0,0,0", "--odom-model textbook").out;
  const std::vector<Pose2> inc = odometry_increments(exact);
  for (std::size_t i = 0; i < inc.size(); ++i) {
    const Pose2 t = back[i].between(back[i + 1]);
    EXPECT_NEAR(inc[i].x, t.x, 1e-12) << i;
    EXPECT_NEAR(inc[i].y, t.y, 1e-12) << i;
    EXPECT_NEAR(wrap_angle(inc[i].theta - t.theta), 0.0, 1e-12) << i;
  }
}

// On long forward steps both models are Table 5.6 and agree in distribution.
TEST(CliPerturbModel, ModelsAgreeOnForwardSteps) {
  TempDir dir("cli_perturb_forward");
  const std::string noise = "0.005,0.0005,0.005,0.0005";
  const auto fwd = zigzag(1001, 0.2, 0.5, -0.1);
  write_log(dir, fwd, 1);
  const double textbook =
      heading_rms(perturb(dir, noise, "--odom-model textbook --quiet").out, fwd);
  const double pgmcl = heading_rms(perturb(dir, noise, "--quiet").out, fwd);
  EXPECT_NEAR(textbook / pgmcl, 1.0, 0.15);
}

}  // namespace
}  // namespace pgmcl::perturb_test
