// One vocabulary across the commands: --threads, --seed and --set on every command that
// runs the filter or the simulator; the same filter key path in localize and run; --init's
// comma form in run; outputs named as outputs (--truth-out); units in option values.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "cli_test_util.hpp"

namespace pgmcl::cli_test {
namespace {

/// A mapped room, a raw log with truth, an experiment on them and a short scenario.
struct World {
  TempDir dir{"cli_vocabulary"};
  World() {
    EXPECT_EQ(map_room(dir, 40, "room.yaml").code, 0);
    EXPECT_EQ(run_pgmcl("perturb --log corrected.log --odom-noise 0.005,0.0005,0.005,0.0005 "
                        "--seed 2 --out raw.log --truth-out truth.tum --quiet",
                        dir)
                  .code,
              0);
    write_text(dir.file("exp.yaml"),
               "map: room.yaml\ndata: {log: raw.log, truth: truth.tum}\n"
               "filter: {filter: {particles: 300, global_particles: 3000}}\n");
    write_text(dir.file("scene.yaml"),
               "map: room.yaml\nseed: 3\nduration: 4.0\nscan_rate: 5.0\n"
               "sensor: {profile: sick_lms_1deg, range_max: 20.0}\n"
               "robot:\n  start: [2.0, 1.6, 0.0]\n  waypoints: {points: [[4.6, 1.6]]}\n");
  }
};

TEST(CliVocabulary, EveryCommandThatRunsTheFilterOrTheSimulatorTakesThreadsSeedAndSet) {
  const TempDir dir("cli_vocabulary_help");
  for (const char* command : {"localize", "run", "simulate"}) {
    const RunResult r = run_pgmcl(std::string(command) + " --help", dir);
    ASSERT_EQ(r.code, 0) << command;
    for (const char* flag : {"--threads", "--seed", "--set"})
      EXPECT_NE(r.out.find(flag), std::string::npos) << command << " " << flag;
  }
}

TEST(CliVocabulary, RunSetTakesTheFilterKeysAsLocalizeDoes) {
  const World w;
  RunResult r = run_pgmcl(
      "run exp.yaml --out a --quiet --set filter.particles=250 --set motion.noise.a1=0.02", w.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find("note"), std::string::npos) << r.err;
  const YAML::Node a = YAML::LoadFile(w.dir.file("a/config.yaml"));
  EXPECT_EQ(a["filter"]["particles"].as<int>(), 250);
  EXPECT_EQ(a["motion"]["noise"]["a1"].as<double>(), 0.02);
  // localize with the same --set writes the same filter keys.
  r = run_pgmcl("localize --map room.yaml --log raw.log --out b --quiet --set filter.particles=250",
                w.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(YAML::LoadFile(w.dir.file("b/config.yaml"))["filter"]["particles"].as<int>(), 250);
  // The old spelling still works, with a note.
  r = run_pgmcl("run exp.yaml --out c --quiet --set filter.filter.particles=260", w.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pgmcl: note: --set filter.filter.particles=260: the experiment's filter "
                       "keys have the same path as pgmcl localize's now: write --set "
                       "filter.particles=260"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(YAML::LoadFile(w.dir.file("c/config.yaml"))["filter"]["particles"].as<int>(), 260);
  // A key that is neither lists both kinds.
  r = run_pgmcl("run exp.yaml --set bogus=1", w.dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--set bogus=1: bogus: unknown key; keys at the top: "), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("; experiment keys: name, map, out, init, data.log"), std::string::npos)
      << r.err;
}

TEST(CliVocabulary, RunTakesThreadsSeedAndInitAsLocalizeDoes) {
  const World w;
  RunResult r =
      run_pgmcl("run exp.yaml --out a --threads 2 --seed 7 --set init=4.95,2.6,1.6", w.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("start: given pose (4.950, 2.600, 91.7 deg)"), std::string::npos) << r.err;
  const YAML::Node c = YAML::LoadFile(w.dir.file("a/config.yaml"));
  EXPECT_EQ(c["threads"].as<int>(), 2);
  EXPECT_EQ(c["seed"].as<int>(), 7);
  r = run_pgmcl("run exp.yaml --out b --quiet --set init=4.95,2.6,1.6,0.1,0.1,0.05", w.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_pgmcl("run exp.yaml --out b --quiet --set init=[4.95,2.6,1.6]", w.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_pgmcl("run exp.yaml --set init=1,2", w.dir);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--set init=1,2: "), std::string::npos) << r.err;
}

TEST(CliVocabulary, SimulateTakesSeedSetThreadsAndTruthOut) {
  const World w;
  auto sim = [&](const std::string& args) {
    const RunResult r = run_pgmcl("simulate scene.yaml --quiet " + args, w.dir);
    EXPECT_EQ(r.code, 0) << args << r.err;
    return r;
  };
  sim("--out base.log --truth-out base.tum");
  sim("--out seeded.log --seed 3 --threads 2");  // the file's seed, two threads: the same log
  EXPECT_EQ(read_text(w.dir.file("base.log")), read_text(w.dir.file("seeded.log")));
  sim("--out other.log --seed 4");
  sim("--out set.log --set seed=4");
  EXPECT_NE(read_text(w.dir.file("base.log")), read_text(w.dir.file("other.log")));
  EXPECT_EQ(read_text(w.dir.file("other.log")), read_text(w.dir.file("set.log")));
  const RunResult shorter = run_pgmcl("simulate scene.yaml --out s.log --set duration=2", w.dir);
  ASSERT_EQ(shorter.code, 0) << shorter.err;
  EXPECT_NE(shorter.out.find(": 11 scans"), std::string::npos) << shorter.out;  // 0..2 s at 5 Hz
  // The old output name works for one release, with a note.
  const RunResult old = sim("--out old.log --truth old.tum");
  EXPECT_NE(old.err.find("--truth is deprecated, use --truth-out"), std::string::npos) << old.err;
  EXPECT_EQ(read_text(w.dir.file("old.tum")), read_text(w.dir.file("base.tum")));
  // A bad override is the override's error.
  const RunResult bad = run_pgmcl("simulate scene.yaml --out x.log --set duration=-1", w.dir);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("pgmcl: error: --set duration=-1: duration: "), std::string::npos)
      << bad.err;
}

TEST(CliVocabulary, LengthsTakeUnits) {
  const TempDir dir("cli_vocabulary_units");
  const RunResult mm = run_pgmcl("kernel --cell 5 --sigma-x 5.6894", dir);
  const RunResult m = run_pgmcl("kernel --cell 0.005m --sigma-x 0.56894cm", dir);
  ASSERT_EQ(mm.code, 0) << mm.err;
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(mm.out, m.out);
  const RunResult bad = run_pgmcl("kernel --cell 5ft", dir);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--cell"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace pgmcl::cli_test
