// The wrong kind of file in the wrong place: each option names what it got and what it
// wants, before any work, with exit code 2 (a bad command line).
#include <gtest/gtest.h>

#include <string>

#include "cli_test_util.hpp"

namespace pgmcl::cli_test {
namespace {

/// A directory with a map (YAML + PGM), a CARMEN log, a TUM file, an experiment, a scenario.
struct Inputs {
  TempDir dir{"cli_kinds"};
  Inputs() {
    write_text(dir.file("map.pgm"), "P2\n2 2\n255\n255 0\n0 255\n");
    write_text(dir.file("map.yaml"),
               "image: map.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\n"
               "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
    write_text(dir.file("run.log"), "ODOM 0 0 0 0 0 0 1.0 h 1.0\nODOM 1 0 0 0 0 0 2.0 h 2.0\n");
    write_text(dir.file("truth.tum"), "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n");
    write_text(dir.file("exp.yaml"), "name: e\nmap: map.yaml\ndata:\n  log: run.log\n");
    write_text(dir.file("scene.yaml"),
               "map: map.yaml\nduration: 2\nrobot:\n  start: [0.5, 0.5, 0]\n");
  }
};

void expect_usage_error(const RunResult& r, const std::string& text) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
}

TEST(CliInputKinds, APgmAsTheMap) {
  const Inputs in;
  expect_usage_error(run_pgmcl("localize --map map.pgm --log run.log", in.dir),
                     "--map: 'map.pgm' is a PGM image, not a map YAML (map_server: image, "
                     "resolution, origin); a map is its YAML (image:, resolution:, origin:)");
  expect_usage_error(run_pgmcl("perturb-map --map map.pgm --out o.yaml --blur 1", in.dir),
                     "--map: 'map.pgm' is a PGM image");
}

TEST(CliInputKinds, ACarmenLogAsTheEstimate) {
  const Inputs in;
  expect_usage_error(run_pgmcl("eval --estimate run.log --truth truth.tum", in.dir),
                     "--estimate: 'run.log' is a CARMEN log, not a TUM trajectory");
  // As --truth, a log is fine (a corrected log's poses); a map is not.
  expect_usage_error(run_pgmcl("eval --estimate truth.tum --truth map.yaml", in.dir),
                     "--truth: 'map.yaml' is a map YAML (map_server), not a TUM trajectory or a "
                     "corrected CARMEN log");
}

TEST(CliInputKinds, AnExperimentAsTheConfig) {
  const Inputs in;
  expect_usage_error(run_pgmcl("localize --map map.yaml --log run.log --config exp.yaml", in.dir),
                     "--config: 'exp.yaml' is an experiment file (pgmcl run), not a filter "
                     "configuration (configs/filters/); run it with `pgmcl run exp.yaml`");
  expect_usage_error(run_pgmcl("config --config exp.yaml", in.dir), "is an experiment file");
}

TEST(CliInputKinds, AScenarioGivenToRunAndAnExperimentToSimulate) {
  const Inputs in;
  expect_usage_error(run_pgmcl("run scene.yaml", in.dir),
                     "'scene.yaml' is a simulated scenario (pgmcl simulate), not an experiment "
                     "file (map + data + filter; configs/experiments/); simulate it with `pgmcl "
                     "simulate scene.yaml --out LOG`, or run it from an experiment file with "
                     "data: {scenario: scene.yaml}");
  expect_usage_error(run_pgmcl("simulate exp.yaml --out s.log", in.dir),
                     "'exp.yaml' is an experiment file (pgmcl run), not a scenario "
                     "(configs/scenarios/); run it with `pgmcl run exp.yaml`");
}

TEST(CliInputKinds, LogsMapsAndTrajectoriesSwapped) {
  const Inputs in;
  expect_usage_error(run_pgmcl("localize --map map.yaml --log truth.tum", in.dir),
                     "--log: 'truth.tum' is a TUM trajectory (8 numbers per line), not a CARMEN "
                     "log");
  expect_usage_error(run_pgmcl("localize --map run.log --log run.log", in.dir),
                     "--map: 'run.log' is a CARMEN log, not a map YAML");
  expect_usage_error(run_pgmcl("map --log map.yaml --resolution 0.05 --out m2.yaml", in.dir),
                     "--log: 'map.yaml' is a map YAML (map_server), not a CARMEN log");
}

TEST(CliInputKinds, ExperimentInputsAreCheckedWithTheirKeys) {
  const Inputs in;
  write_text(in.dir.file("bad.yaml"), "name: b\nmap: map.yaml\ndata:\n  log: truth.tum\n");
  expect_usage_error(run_pgmcl("run bad.yaml", in.dir),
                     "bad.yaml:4: data.log: 'truth.tum' is a TUM trajectory (8 numbers per "
                     "line), not a CARMEN log");
}

}  // namespace
}  // namespace pgmcl::cli_test
