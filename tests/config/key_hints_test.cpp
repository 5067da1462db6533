// Unknown filter keys: the keys valid at that level, the nearest one, the pgmcl key of an
// AMCL parameter name (or why there is none), the full path of a key at the wrong level;
// and experiment files whose input paths are missing or the wrong kind of file.

#include "pgmcl/config/key_hints.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "pgmcl/config/config_yaml.hpp"
#include "pgmcl/config/experiment_yaml.hpp"
#include "pgmcl/io/values.hpp"
#include "temp_files.hpp"

namespace pgmcl::io {
namespace {

/// The message of the ConfigError `--set key=value` throws.
std::string set_error(const std::string& key, const std::string& value = "1") {
  LocalizerConfig c;
  try {
    apply_localizer_override(key, value, c);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(KeyHints, UnknownKeysListTheKeysAtTheirLevel) {
  LocalizerConfig c;
  try {
    parse_localizer_config("filter:\n  particles: 100\n  particels: 5\n", "f.yaml", c);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "f.yaml:3: filter.particels: unknown key (did you mean 'particles'?); keys under "
              "filter: global_particles, kld, particles, recovery, resample_threshold");
  }
  EXPECT_NE(set_error("filtr.particles")
                .find("; keys at the top: adaptive_threads, estimate, filter, gating, "
                      "hypotheses, likelihood, motion, seed, threads, "
                      "time_backwards"),
            std::string::npos);
}

TEST(KeyHints, AmclNamesNameThePgmclKeyOrWhyThereIsNone) {
  // The list, at the top level and where AMCL users tend to put them.
  const std::pair<const char*, const char*> mapped[] = {
      {"alpha1", "motion.noise.a1"},
      {"alpha2", "motion.noise.a2"},
      {"alpha3", "motion.noise.a3"},
      {"alpha4", "motion.noise.a4"},
      {"alpha5", "motion.noise.a5"},
      {"min_particles", "filter.kld.min_particles"},
      {"max_particles", "filter.kld.max_particles"},
      {"z_hit", "likelihood.beam.w_hit"},
      {"z_rand", "likelihood.beam.w_rand"},
      {"sigma_hit", "likelihood.beam.sigma_along, likelihood.beam.sigma_across"},
      {"update_min_d", "gating.d_min"},
      {"update_min_a", "gating.theta_min"},
      {"laser_max_beams", "likelihood.selection.max_beams"},
      {"recovery_alpha_slow", "filter.recovery.alpha_slow"},
      {"recovery_alpha_fast", "filter.recovery.alpha_fast"},
      {"laser_model_type", "likelihood.table.kind"},
      {"odom_alpha3", "motion.noise.a3"},  // ROS 1's prefix
  };
  for (const auto& [amcl, key] : mapped) {
    for (const std::string at : {"", "filter."}) {
      const std::string m = set_error(at + amcl);
      EXPECT_NE(m.find(std::string("unknown key: AMCL's ") + amcl + " is pgmcl's " + key),
                std::string::npos)
          << m;
    }
  }
  const std::string m = set_error("resample_interval", "2");
  EXPECT_NE(m.find("AMCL's resample_interval has no pgmcl key: pgmcl resamples when the "
                   "effective sample size drops below filter.resample_threshold"),
            std::string::npos)
      << m;
  EXPECT_NE(set_error("z_short").find("has no pgmcl key"), std::string::npos);
  // A nav2 parameters file given whole.
  for (const std::string k : {"amcl.ros__parameters.alpha1", "ros__parameters.alpha1"}) {
    EXPECT_NE(set_error(k).find("unknown key: this looks like a ROS amcl parameters file "
                                "(amcl: ros__parameters: ...); pgmcl's keys have other names "
                                "and places: `pgmcl config --amcl`"),
              std::string::npos)
        << set_error(k);
  }
}

TEST(KeyHints, EveryKeyInTheAmclTableExists) {
  const std::vector<std::string> keys = localizer_config_keys();
  EXPECT_EQ(keys.front(), "motion.kind");
  EXPECT_EQ(keys.back(), "seed");
  for (const AmclParameter& p : amcl_parameters()) {
    std::string list = p.pgmcl;
    if (list.empty() || list.rfind("--", 0) == 0) continue;
    for (std::size_t start = 0; start < list.size();) {
      std::size_t end = list.find(", ", start);
      if (end == std::string::npos) end = list.size();
      const std::string k = list.substr(start, end - start);
      EXPECT_NE(std::find(keys.begin(), keys.end(), k), keys.end()) << p.amcl << ": " << k;
      start = end + 2;
    }
  }
}

TEST(KeyHints, PgmclKeysAtTheWrongLevelGetTheirFullPath) {
  EXPECT_NE(set_error("particles").find("unknown key: pgmcl's key is filter.particles;"),
            std::string::npos);
  EXPECT_NE(set_error("filter.alpha_slow", "0.01")
                .find("unknown key: pgmcl's key is filter.recovery.alpha_slow;"),
            std::string::npos);
  EXPECT_NE(set_error("kld.enabled", "true").find("pgmcl's key is filter.kld;"), std::string::npos);
  // max_beams lives in two places.
  EXPECT_EQ(localizer_key_hint("filter.max_beams").find("AMCL's max_beams"), 0u);
  EXPECT_EQ(localizer_key_hint("search.leaf_size"), "pgmcl's key is hypotheses.search.leaf_size");
  EXPECT_EQ(localizer_key_hint("no_such_thing"), "");
}

TEST(KeyHints, InAnExperimentTheKeysNamedAreTheFilesOwn) {
  testkit::TempDir dir("key_hints");
  std::ofstream(dir.file("m.yaml")) << "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  std::ofstream(dir.file("a.log")) << "ODOM 0 0 0 0 0 0 1.0 h 1.0\n";
  std::ofstream(dir.file("e.yaml")) << "map: m.yaml\ndata: {log: a.log}\nfilter:\n"
                                       "  particles: 5\n";
  try {
    (void)read_experiment(dir.file("e.yaml"));
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(":4: filter.particles: unknown key: pgmcl's key is "
                                         "filter.filter.particles;"),
              std::string::npos)
        << e.what();
  }
}

TEST(KeyHints, NearestKeyIsWithinAThirdOfTheKeysLength) {
  EXPECT_EQ(nearest_key("nme", {"map", "name", "out"}), "name");
  EXPECT_EQ(nearest_key("partciles", {"particles", "global_particles"}), "particles");  // a swap
  EXPECT_EQ(nearest_key("xyz", {"name", "map"}), "");
  EXPECT_EQ(nearest_key("anything", {}), "");
}

TEST(KeyHints, ExperimentSetSuggestsTheNearestExperimentOrFilterKey) {
  testkit::TempDir dir("exp_set_hints");
  std::ofstream(dir.file("m.yaml")) << "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  std::ofstream(dir.file("a.log")) << "ODOM 0 0 0 0 0 0 1.0 h 1.0\n";
  std::ofstream(dir.file("e.yaml")) << "map: m.yaml\ndata: {log: a.log}\n";
  const auto set_error = [&](const std::string& assignment) -> std::string {
    try {
      (void)read_experiment(dir.file("e.yaml"), {assignment});
    } catch (const UsageError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(set_error("nme=x").rfind("--set nme=x: nme: unknown key (did you mean 'name'?); keys "
                                     "at the top: ",
                                     0),
            0u)
      << set_error("nme=x");
  EXPECT_NE(set_error("nme=x").find("; experiment keys: name, map, out, init, data.log"),
            std::string::npos);
  EXPECT_NE(set_error("data.lgo=a.log").find("(did you mean 'data.log'?)"), std::string::npos);
  EXPECT_NE(set_error("seeed=3").find("(did you mean 'seed'?)"), std::string::npos);
  // The filter's own hints stay: an AMCL name gets its pgmcl key, not a guess.
  const std::string amcl = set_error("alpha1=0.2");
  EXPECT_NE(amcl.find("AMCL's alpha1 is pgmcl's motion.noise.a1"), std::string::npos) << amcl;
  EXPECT_EQ(amcl.find("did you mean"), std::string::npos) << amcl;
}

TEST(KeyHints, ExperimentFilesNameAMisspeltKeyBeforeAMissingOne) {
  testkit::TempDir dir("exp_file_hints");
  std::ofstream(dir.file("m.yaml")) << "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  std::ofstream(dir.file("a.log")) << "ODOM 0 0 0 0 0 0 1.0 h 1.0\n";
  const auto file_error = [&](const std::string& text) -> std::string {
    std::ofstream(dir.file("e.yaml")) << text;
    try {
      (void)read_experiment(dir.file("e.yaml"));
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(file_error("name: x\nmapp: m.yaml\ndata:\n  log: a.log\n"),
            dir.file("e.yaml") +
                ":2: mapp: unknown key (did you mean 'map'?); keys at the top: data, filter, "
                "init, map, name, out");
  EXPECT_NE(file_error("map: m.yaml\ndata:\n  lgo: a.log\n")
                .find(":3: data.lgo: unknown key (did you mean 'log'?)"),
            std::string::npos);
  EXPECT_NE(file_error("map: m.yaml\ndata: {log: a.log}\ninit: {pos: [0, 0, 0]}\n")
                .find("init.pos: unknown key (did you mean 'pose'?)"),
            std::string::npos);
  // With nothing misspelt, the missing key is still named.
  EXPECT_NE(file_error("name: x\ndata:\n  log: a.log\n").find(":1: map: missing required key"),
            std::string::npos);
}

TEST(KeyHints, ExperimentPathsThatDoNotExistNameTheKeyAndTheFolder) {
  testkit::TempDir dir("exp_paths");
  std::filesystem::create_directories(dir.path() / "cfg");
  std::ofstream(dir.file("m.yaml")) << "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
  std::ofstream(dir.file("cfg/e.yaml")) << "name: x\nmap: ../m.yaml\ndata:\n"
                                           "  log: ../out/raw.log.gz\n";
  const std::string e = dir.file("cfg/e.yaml");
  try {
    (void)read_experiment(e);
    FAIL();
  } catch (const ConfigError& err) {
    EXPECT_EQ(std::string(err.what()),
              e + ":4: data.log: '" + dir.file("out/raw.log.gz") +
                  "' does not exist (written '../out/raw.log.gz', resolved against the "
                  "experiment's folder '" +
                  dir.file("cfg") + "')");
  }
  // A --set path is the command line's, relative to the current directory.
  try {
    (void)read_experiment(e, {"data.log=nope.log"});
    FAIL();
  } catch (const UsageError& err) {
    EXPECT_EQ(std::string(err.what()),
              "--set data.log=nope.log: 'nope.log' does not exist (paths on the command line "
              "are relative to the current directory)");
  }
  // The wrong kind of file under a key.
  try {
    (void)read_experiment(e, {"data.log=" + dir.file("m.yaml")});
    FAIL();
  } catch (const UsageError& err) {
    EXPECT_NE(std::string(err.what()).find("' is a map YAML (map_server), not a CARMEN log"),
              std::string::npos)
        << err.what();
  }
}

}  // namespace
}  // namespace pgmcl::io
