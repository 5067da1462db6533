// `pgmcl simulate` and `pgmcl run EXPERIMENT.yaml` on a small synthetic world.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

#include "cli_test_util.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl {
namespace {

using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

/// room.yaml (the synthetic room, mapped) and a short scenario driving a loop in it.
void prepare(const TempDir& dir) {
  ASSERT_EQ(cli_test::map_room(dir, 40, "maps/room.yaml").code, 0);
  cli_test::write_text(dir.file("scenario.yaml"),
                       "name: room-loop\n"
                       "map: maps/room.yaml\n"
                       "seed: 3\n"
                       "duration: 8.0\n"
                       "scan_rate: 5.0\n"
                       "sensor: {profile: sick_lms_1deg, range_max: 20.0}\n"
                       "robot:\n"
                       "  start: [2.0, 1.6, 0.0]\n"
                       "  limits: {max_v: 0.5, max_omega: 1.0}\n"
                       "  waypoints:\n"
                       "    points: [[4.6, 1.6], [4.6, 3.4], [2.0, 3.4]]\n"
                       "    loop: true\n"
                       "odometry:\n"
                       "  alphas: {a1: 0.0025, a2: 0.0003, a3: 0.0025, a4: 0.0003}\n");
}

TEST(CliRun, SimulateWritesAReplayableLogAndTruth) {
  TempDir dir("cli_run_simulate");
  prepare(dir);
  const RunResult r =
      run_pgmcl("simulate scenario.yaml --out sim/sim.log --truth-out sim/truth.tum", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("room-loop: 41 scans"), std::string::npos) << r.out;
  const io::CarmenLog log = io::read_carmen(dir.file("sim/sim.log"));
  const io::Trajectory truth = io::read_tum(dir.file("sim/truth.tum"));
  EXPECT_EQ(log.scans.size(), 41u);  // t = 0, 0.2, ..., 8.0
  ASSERT_EQ(truth.size(), log.scans.size());
  EXPECT_NEAR(truth.front().pose.x, 2.0, 1e-9);
  EXPECT_GT(truth.back().pose.x - truth.front().pose.x, 0.5);  // it drove

  const RunResult again = run_pgmcl(
      "simulate scenario.yaml --out sim/sim2.log --truth-out sim/truth2.tum --quiet", dir);
  ASSERT_EQ(again.code, 0);
  EXPECT_EQ(cli_test::read_text(dir.file("sim/sim.log")),
            cli_test::read_text(dir.file("sim/sim2.log")));  // seeded: identical

  std::string text = cli_test::read_text(dir.file("scenario.yaml"));
  text.replace(text.find("duration: 8.0"), 13, "duration: -1.0");
  cli_test::write_text(dir.file("bad.yaml"), text);
  const RunResult bad = run_pgmcl("simulate bad.yaml --out x.log", dir);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("pgmcl: error: bad.yaml:4: duration"), std::string::npos) << bad.err;
}

TEST(CliRun, ExperimentWithAScenarioSimulatesAndLocalises) {
  TempDir dir("cli_run_scenario");
  prepare(dir);
  std::filesystem::create_directories(dir.file("exp"));
  cli_test::write_text(dir.file("exp/room.yaml"),
                       "name: room\n"
                       "data:\n"
                       "  scenario: ../scenario.yaml\n"
                       "filter:\n"
                       "  filter: {particles: 300, global_particles: 3000}\n"
                       "  seed: 9\n"
                       "out: ../results/room\n");
  const RunResult r = run_pgmcl("run exp/room.yaml --quiet --set gating.enabled=false", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("room: localize: 41 updates", 0), 0u) << r.out;
  for (const char* f : {"trajectory.tum", "metrics.yaml", "config.yaml", "overlay.png", "error.png",
                        "sim.log.gz", "truth.tum"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.file(std::string("results/room/") + f))) << f;
  }
  const YAML::Node m = YAML::LoadFile(dir.file("results/room/metrics.yaml"));
  EXPECT_LT(m["ate_rmse_m"].as<double>(), 0.05);
  const YAML::Node c = YAML::LoadFile(dir.file("results/room/config.yaml"));
  EXPECT_EQ(c["filter"]["particles"].as<int>(), 300);
  EXPECT_EQ(c["seed"].as<int>(), 9);
  EXPECT_FALSE(c["gating"]["enabled"].as<bool>());
}

TEST(CliRun, ExperimentWithALogAndOverrides) {
  TempDir dir("cli_run_log");
  prepare(dir);
  ASSERT_EQ(run_pgmcl("perturb --log corrected.log --odom-noise 0.005,0.0005,0.005,0.0005 "
                      "--seed 2 --out raw.log --truth-out truth.tum --quiet",
                      dir)
                .code,
            0);
  cli_test::write_text(dir.file("exp.yaml"),
                       "map: maps/room.yaml\n"
                       "data: {log: raw.log, truth: truth.tum}\n"
                       "init: {pose: [4.95, 2.6, 1.6], sigma: [0.1, 0.1, 0.05]}\n"
                       "filter: {filter: {particles: 300}}\n");
  const RunResult r = run_pgmcl("run exp.yaml --out elsewhere --quiet --set name=renamed", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("renamed: ", 0), 0u) << r.out;
  const YAML::Node m = YAML::LoadFile(dir.file("elsewhere/metrics.yaml"));
  EXPECT_LT(m["ate_rmse_m"].as<double>(), 0.05);
}

TEST(CliRun, ExperimentErrorsNameFileLineAndKey) {
  TempDir dir("cli_run_errors");
  prepare(dir);
  cli_test::write_text(dir.file("both.yaml"),
                       "map: maps/room.yaml\ndata:\n  log: a.log\n  scenario: scenario.yaml\n");
  RunResult r = run_pgmcl("run both.yaml", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("both.yaml:3: data: needs exactly one of data.log and data.scenario"),
            std::string::npos)
      << r.err;
  cli_test::write_text(dir.file("typo.yaml"),
                       "data:\n  scenario: scenario.yaml\nfilter:\n  gating:\n    dmin: 1\n");
  r = run_pgmcl("run typo.yaml", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("typo.yaml:5: filter.gating.dmin: unknown key"), std::string::npos) << r.err;
  cli_test::write_text(dir.file("init.yaml"), "data: {scenario: scenario.yaml}\ninit: somewhere\n");
  r = run_pgmcl("run init.yaml", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("init.yaml:2: init: expected global, truth"), std::string::npos) << r.err;
  r = run_pgmcl("run init.yaml --set bogus=1", dir);
  EXPECT_EQ(r.code, 1);  // the file error comes first
  cli_test::write_text(dir.file("ok.yaml"), "data: {scenario: scenario.yaml}\n");
  r = run_pgmcl("run ok.yaml --set bogus=1", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--set bogus=1: bogus: unknown key"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pgmcl
