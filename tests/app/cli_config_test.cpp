// pgmcl config: the effective configuration after --config and --set, the generated key
// reference (configs/reference.md must be its current output), and typo suggestions.
#include <gtest/gtest.h>

#include <string>

#include "cli_test_util.hpp"

namespace pgmcl::cli_test {
namespace {

TEST(CliConfigCommand, ReferenceFileIsTheCurrentGeneratedTable) {
  const TempDir dir("pgmcl-config-ref");
  const RunResult r = run_pgmcl("config --reference", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string committed = read_text(PGMCL_SOURCE_DIR "/configs/reference.md");
  EXPECT_EQ(r.out, committed) << "configs/reference.md is stale: regenerate it with "
                                 "`pgmcl config --reference > configs/reference.md`";
  // Every key of the YAML the runs write is in the table.
  const RunResult yaml = run_pgmcl("config", dir);
  ASSERT_EQ(yaml.code, 0) << yaml.err;
  for (const char* key : {"`filter.kld.max_particles`", "`hypotheses.search.leaf_size`",
                          "`likelihood.table.kind`", "`seed`"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
}

TEST(CliConfigCommand, TheAmclTableInConfigsReadmeIsTheCurrentOne) {
  const TempDir dir("pgmcl-config-amcl");
  const RunResult r = run_pgmcl("config --amcl", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("| AMCL | pgmcl | notes |\n", 0), 0u) << r.out;
  const std::string readme = read_text(PGMCL_SOURCE_DIR "/configs/README.md");
  EXPECT_NE(readme.find(r.out), std::string::npos)
      << "configs/README.md's AMCL table is stale: replace it with `pgmcl config --amcl`";
  // An AMCL name in a filter file is an error that names the pgmcl key.
  write_text(dir.file("amcl.yaml"), "filter:\n  max_particles: 5000\n");
  const RunResult bad = run_pgmcl("config --config amcl.yaml", dir);
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("amcl.yaml:2: filter.max_particles: unknown key: AMCL's max_particles "
                         "is pgmcl's filter.kld.max_particles"),
            std::string::npos)
      << bad.err;
}

TEST(CliConfigCommand, PrintsTheConfigAfterFileAndOverrides) {
  const TempDir dir("pgmcl-config-eff");
  write_text(dir.file("f.yaml"), "filter:\n  particles: 777\ngating:\n  d_min: 0.25\n");
  const RunResult r =
      run_pgmcl("config --config f.yaml --set filter.particles=900 --set seed=7", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("particles: 900"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("d_min: 0.25"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("seed: 7"), std::string::npos) << r.out;
}

TEST(CliConfigCommand, TyposNameTheNearestKey) {
  const TempDir dir("pgmcl-config-typo");
  RunResult r = run_pgmcl("config --set filter.particels=5", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("filter.particels: unknown key (did you mean 'particles'?)"),
            std::string::npos)
      << r.err;
  write_text(dir.file("f.yaml"), "filtr:\n  particles: 5\n");
  r = run_pgmcl("config --config f.yaml", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("f.yaml:1: filtr: unknown key (did you mean 'filter'?)"), std::string::npos)
      << r.err;
  // Nothing near: no suggestion.
  r = run_pgmcl("config --set filter.zzzzzzzz=5", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown key"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pgmcl::cli_test
