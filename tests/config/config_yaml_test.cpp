// The LocalizerConfig YAML adapter: every field round-trips, errors name file, line and key.
#include "pgmcl/config/config_yaml.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <string>

#include "pgmcl/config/experiment_yaml.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::io {
namespace {

/// A config with every field moved off its default.
LocalizerConfig everything_changed() {
  LocalizerConfig c;
  c.motion.kind = MotionModelKind::kOmnidirectional;
  c.motion.noise = {0.011, 0.012, 0.013, 0.014, 0.015};
  auto& l = c.likelihood;
  l.beam.sigma_along = 0.021;
  l.beam.sigma_across = 0.022;
  l.beam.model_mismatch = 0.023;
  l.beam.add_discretisation = !l.beam.add_discretisation;
  l.beam.w_hit = 0.8;
  l.beam.w_rand = 0.2;
  l.beam.max_range = 12.5;
  l.table.kind = maps::TableKind::kOffsetField;
  l.table.orientation_bins = 9;
  l.table.reach_sigmas = 3.5;
  l.table.isotropy_tolerance = 0.3;
  l.table.max_table_bytes = 123456789;
  l.effective_beams = 0.0;
  l.tempering = 0.25;
  l.min_ess_ratio = 0.3;
  l.selection.mode = BeamSelectionMode::kStride;
  l.selection.stride = 3;
  l.selection.max_beams = 77;
  l.expected_beams = 181;
  auto& f = c.filter;
  f.particles = 1234;
  f.global_particles = 5678;
  f.resample_threshold = 0.7;
  f.kld.enabled = false;
  f.kld.min_particles = 111;
  f.kld.max_particles = 9999;
  f.kld.epsilon = 0.07;
  f.kld.delta = 0.02;
  f.kld.bin_xy = 0.3;
  f.kld.bin_theta = 0.2;
  f.recovery.enabled = false;
  f.recovery.alpha_slow = 0.002;
  f.recovery.alpha_fast = 0.2;
  c.gating = {false, 0.2, 0.3};
  c.estimate = {0.6, 0.4, 0.8, 0.3, 0.2};
  c.time_backwards = TimeBackwardsPolicy::kReset;
  c.threads = 2;
  c.seed = 987654321;
  return c;
}

TEST(CliConfig, EveryFieldRoundTrips) {
  const LocalizerConfig c = everything_changed();
  const std::string yaml = localizer_config_yaml(c);
  LocalizerConfig back;  // defaults, overwritten by every key in the text
  parse_localizer_config(yaml, "roundtrip.yaml", back);
  EXPECT_EQ(localizer_config_yaml(back), yaml);
  // Spot checks of the struct itself (the text comparison covers the rest).
  EXPECT_EQ(back.motion.kind, MotionModelKind::kOmnidirectional);
  EXPECT_EQ(back.likelihood.table.kind, maps::TableKind::kOffsetField);
  EXPECT_EQ(back.likelihood.selection.mode, BeamSelectionMode::kStride);
  EXPECT_EQ(back.time_backwards, TimeBackwardsPolicy::kReset);
  EXPECT_EQ(back.filter.kld.max_particles, 9999u);
  EXPECT_EQ(back.seed, 987654321u);
  EXPECT_DOUBLE_EQ(back.motion.noise.a5, 0.015);
  EXPECT_EQ(back.likelihood.beam.add_discretisation, c.likelihood.beam.add_discretisation);
  // Defaults also round-trip.
  LocalizerConfig d, d2 = everything_changed();
  parse_localizer_config(localizer_config_yaml(d), "defaults.yaml", d2);
  EXPECT_EQ(localizer_config_yaml(d2), localizer_config_yaml(d));
  // Numbers are the shortest text that reads back exactly, readable by people and PyYAML.
  const std::string text = localizer_config_yaml(c);
  EXPECT_NE(text.find("a5: 0.015\n"), std::string::npos) << text;
  EXPECT_NE(text.find("sigma_along: 0.021\n"), std::string::npos) << text;
  for (std::size_t dot = text.find('.'); dot != std::string::npos; dot = text.find('.', dot + 1)) {
    std::size_t digits = 0;
    while (dot + 1 + digits < text.size() &&
           std::isdigit(static_cast<unsigned char>(text[dot + 1 + digits])))
      ++digits;
    EXPECT_LE(digits, 8u) << text.substr(dot - 10, 30);
  }
  EXPECT_NE(localizer_config_yaml(d).find("a2: 0.0005\n"), std::string::npos);
}

TEST(CliConfig, AbsentKeysKeepTheirValues) {
  LocalizerConfig c;
  parse_localizer_config("filter:\n  particles: 500\n", "partial.yaml", c);
  EXPECT_EQ(c.filter.particles, 500u);
  EXPECT_EQ(c.filter.global_particles, LocalizerConfig{}.filter.global_particles);
  parse_localizer_config("", "empty.yaml", c);
  EXPECT_EQ(c.filter.particles, 500u);
}

void expect_error(const std::string& yaml, std::size_t line, const std::string& field,
                  const std::string& words) {
  LocalizerConfig c;
  const LocalizerConfig before = c;
  try {
    parse_localizer_config(yaml, "f.yaml", c);
    FAIL() << "accepted: " << yaml;
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), "f.yaml");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind("f.yaml:" + std::to_string(line) + ": " + field, 0), 0u)
        << e.what();
  }
  // A failed read leaves the config untouched.
  EXPECT_EQ(localizer_config_yaml(c), localizer_config_yaml(before));
}

TEST(CliConfig, ErrorsNameFileLineAndKey) {
  expect_error("filter:\n  particles: 100\n  particels: 5\n", 3, "filter.particels", "unknown key");
  expect_error("motion:\n  noise:\n    a1: lots\n", 3, "motion.noise.a1", "expected a number");
  expect_error("filter:\n  kld:\n    enabled: maybe\n", 3, "filter.kld.enabled", "true or false");
  expect_error("likelihood:\n  table:\n    kind: hexagonal\n", 3, "likelihood.table.kind",
               "isotropic, oriented, offset");
  expect_error("threads: -2\n", 1, "threads", "must be in");
  expect_error("filter: 12\n", 1, "filter", "expected a mapping");
  // yaml-cpp notices the unclosed list at the end of the text (line 4).
  expect_error("seed: 1\nfilter:\n  particles: [1, 2\n", 4, "yaml", "not valid YAML");
  // validate() failures are reported at the key's line.
  expect_error("gating:\n  d_min: 0.1\nfilter:\n  resample_threshold: 1.5\n", 4,
               "filter.resample_threshold", "must be in [0, 1]");
  expect_error("motion:\n  noise:\n    a3: -0.1\n", 3, "motion.noise.a3", "must be in [0, 100]");
}

TEST(CliConfig, SetOverridesUseDottedKeys) {
  LocalizerConfig c;
  apply_localizer_overrides({"filter.particles=2000", "likelihood.table.kind=oriented",
                             "filter.kld.enabled=false", "motion.noise.a1 = 0.02"},
                            c);
  EXPECT_EQ(c.filter.particles, 2000u);
  EXPECT_EQ(c.likelihood.table.kind, maps::TableKind::kOrientedBins);
  EXPECT_FALSE(c.filter.kld.enabled);
  EXPECT_DOUBLE_EQ(c.motion.noise.a1, 0.02);
  try {
    apply_localizer_override("filter.particle", "3", c);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("--set filter.particle=3"), std::string::npos);
    EXPECT_EQ(e.field(), "filter.particle");
    EXPECT_NE(std::string(e.what()).find("unknown key"), std::string::npos);
  }
  try {  // a command-line value has no line: no ":0:" or ":1:" in the message
    apply_localizer_override("filter.particles", "many", c);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.line(), 0U);
    EXPECT_EQ(std::string(e.what()).rfind("--set filter.particles=many: filter.particles: ", 0), 0U)
        << e.what();
  }
  EXPECT_THROW(apply_localizer_override("filter..particles", "3", c), ConfigError);
  EXPECT_THROW(apply_localizer_overrides({"filter.particles"}, c), UsageError);
  EXPECT_EQ(c.filter.particles, 2000u);
}

TEST(CliConfig, BundledExamplesParse) {
  LocalizerConfig c;
  read_localizer_config(PGMCL_SOURCE_DIR "/configs/filters/tracking.yaml", c);
  EXPECT_EQ(c.filter.kld.max_particles, 20000u);
  const Experiment e = read_experiment(PGMCL_SOURCE_DIR "/configs/experiments/lab.yaml");
  EXPECT_EQ(e.name, "lab");
  EXPECT_EQ(e.init.kind, ExperimentInit::Kind::kTruth);
  EXPECT_TRUE(e.log.empty());
  EXPECT_NE(e.scenario.find("configs/scenarios/lab.yaml"), std::string::npos) << e.scenario;
  EXPECT_EQ(e.filter.filter.particles, 2000u);
  EXPECT_EQ(e.out, "pgmcl-out/lab");
}

}  // namespace
}  // namespace pgmcl::io
