// `pgmcl calibrate`: recovers known sigmas from simulated experiments and synthetic logs.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "cli_test_util.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/io/carmen_writer.hpp"

namespace pgmcl {
namespace {

using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

/// The first number after `label` in the output.
double figure(const std::string& out, const std::string& label) {
  const std::regex re(label + R"(\s+([-0-9.]+))");
  std::smatch m;
  if (!std::regex_search(out, m, re)) return NAN;
  return std::stod(m[1]);
}

/// A stationary 10-beam scanner: `fill(scan, beam, rng)` gives each reading.
template <class Fill>
void write_static_log(const std::string& path, int scans, Fill fill) {
  io::CarmenLog log;
  const io::BeamLayout layout = io::sick_beam_layout(10);
  Rng rng(77);
  for (int k = 0; k < scans; ++k) {
    io::CarmenScan s;
    s.stamp = 0.1 * k;
    s.scan.angle_min = layout.angle_min;
    s.scan.angle_increment = layout.angle_increment;
    s.scan.range_max = 30.0;
    for (int i = 0; i < 10; ++i) s.scan.ranges.push_back(static_cast<float>(fill(k, i, rng)));
    log.scans.push_back(s);
  }
  log.params["robot_front_laser_max"] = "30";
  io::write_carmen(path, log);
}

TEST(CliCalibrate, RangeSigmaFromASimulatedSurface) {
  TempDir dir("cli_calibrate_sim_range");
  const RunResult r = run_pgmcl("calibrate range --simulate --material cardboard_box", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const double model = figure(r.out, "model sigma");
  const double est = figure(r.out, "sigma_x");
  const double se = figure(r.out, "standard error");
  EXPECT_NEAR(model, 4.6533, 1e-4);  // Dekan et al., Table 2
  EXPECT_NEAR(est, model, 4.0 * se) << r.out;
}

TEST(CliCalibrate, RangeSigmaFromALog) {
  TempDir dir("cli_calibrate_log_range");
  // Beam 3 reads 2 m + N(0, 6 mm), with a different true distance in each quarter of the
  // log (the experiments' own means): the pooled estimate must not see the mean shifts.
  write_static_log(dir.file("static.log"), 2000, [](int k, int i, Rng& rng) {
    return i == 3 ? 2.0 + 0.01 * (k / 500) + rng.normal(0.006) : 5.0;
  });
  const RunResult r = run_pgmcl("calibrate range --log static.log --beam 3 --experiments 4", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(figure(r.out, "sigma_x"), 6.0, 4.0 * figure(r.out, "standard error")) << r.out;
  EXPECT_NE(r.out.find("2000 in 4 experiment(s)"), std::string::npos) << r.out;
}

TEST(CliCalibrate, SimulateRunsTheExperimentsAskedFor) {
  TempDir dir("cli_calibrate_sim_count");
  RunResult r = run_pgmcl("calibrate range --simulate --experiments 12 --readings 50", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("600 in 12 experiment(s)"), std::string::npos) << r.out;
  r = run_pgmcl("calibrate range --simulate --readings 50", dir);  // Dekan et al.'s 20
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("1000 in 20 experiment(s)"), std::string::npos) << r.out;
}

TEST(CliCalibrate, AMovingRobotIsCalledOut) {
  TempDir dir("cli_calibrate_moving");
  // The scanner drives away from a wall at 5 cm per scan: beam 3's range grows steadily.
  io::CarmenLog log;
  const io::BeamLayout layout = io::sick_beam_layout(10);
  Rng rng(3);
  for (int k = 0; k < 400; ++k) {
    io::CarmenScan s;
    s.stamp = 0.1 * k;
    s.scan.angle_min = layout.angle_min;
    s.scan.angle_increment = layout.angle_increment;
    s.scan.range_max = 30.0;
    for (int i = 0; i < 10; ++i)
      s.scan.ranges.push_back(static_cast<float>(2.0 + 0.05 * k + rng.normal(0.005)));
    s.laser_pose = s.odom_pose = {-0.05 * k, 0.0, 0.0};
    log.scans.push_back(s);
  }
  log.params["robot_front_laser_max"] = "30";
  io::write_carmen(dir.file("moving.log"), log);
  const RunResult r = run_pgmcl("calibrate range --log moving.log --beam 3", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pgmcl: warning: moving.log: the robot moved 19.950 m"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the readings are not a static scene's (lag-1 autocorrelation 0.99"),
            std::string::npos)
      << r.err;
  // A static scanner: no warning.
  write_static_log(dir.file("static.log"), 400,
                   [](int, int, Rng& g) { return 2.0 + g.normal(0.005); });
  const RunResult ok = run_pgmcl("calibrate range --log static.log --beam 3", dir);
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_EQ(ok.err.find("warning"), std::string::npos) << ok.err;
}

TEST(CliCalibrate, EdgeSigmaFromALogWithKnownJitter) {
  TempDir dir("cli_calibrate_log_edge");
  // Beam j is on the object (1 m) iff j + e < 4.3, e ~ N(0, 0.4 steps); else background 3 m.
  // One e per beam per scan, as in the model of sims::boundary_distribution.
  write_static_log(dir.file("edge.log"), 3000,
                   [](int, int i, Rng& rng) { return i + rng.normal(0.4) < 4.3 ? 1.0 : 3.0; });
  const RunResult r = run_pgmcl(
      "calibrate edge --log edge.log --first-beam 0 --split-range 2 --edge-fraction 0.3 "
      "--distance 1",
      dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::regex re(R"(sigma \(beam steps\)\s+([0-9.]+) from the change rate, ([0-9.]+))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, re)) << r.out;
  EXPECT_NEAR(std::stod(m[1]), 0.4, 0.04);
  EXPECT_NEAR(std::stod(m[2]), 0.4, 0.03);
}

TEST(CliCalibrate, EdgeSigmaFromTheSimulatedExperiment) {
  TempDir dir("cli_calibrate_sim_edge");
  const RunResult r = run_pgmcl("calibrate edge --simulate --distance 1.5 --runs 4", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  // The simulator's across-beam sigma is Dekan et al.'s 3 mm.
  EXPECT_NEAR(figure(r.out, R"(sigma_y = y / 3)"), 3.0, 0.3) << r.out;
}

TEST(CliCalibrate, MissingInputIsAUsageError) {
  TempDir dir("cli_calibrate_usage");
  RunResult r = run_pgmcl("calibrate range", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("give --log LOG or --simulate"), std::string::npos) << r.err;
  r = run_pgmcl("calibrate", dir);
  EXPECT_EQ(r.code, 2);
}

}  // namespace
}  // namespace pgmcl
