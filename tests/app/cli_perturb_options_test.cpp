// `pgmcl perturb` options: deprecated names, the header record, bad values.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "perturb_test_util.hpp"

namespace pgmcl::perturb_test {
namespace {

const std::string kBase = "perturb --log in.log --odom-noise 0.01,0.001,0.01,0.001 --seed 5 ";

TEST(CliPerturbOptions, DeprecatedNamesStillWorkWithANote) {
  TempDir dir("cli_perturb_deprecated");
  write_log(dir, zigzag(30, 0.1, 0.5, 0.05));
  RunResult r =
      run_pgmcl(kBase + "--scale-bias 0.02 --yaw-drift 0.5 --out new.log --truth-out new.tum", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  r = run_pgmcl(kBase + "--bias-scale 0.02 --bias-yaw-deg-per-m 0.5 --out old.log --truth old.tum",
                dir);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* note :
       {"pgmcl: warning: --truth is deprecated, use --truth-out\n",
        "pgmcl: warning: --bias-scale is deprecated, use --scale-bias\n",
        "pgmcl: warning: --bias-yaw-deg-per-m is deprecated, use --yaw-drift\n"}) {
    EXPECT_NE(r.err.find(note), std::string::npos) << r.err;
  }
  EXPECT_EQ(read_text(dir.file("old.tum")), read_text(dir.file("new.tum")));
  std::string a = read_text(dir.file("old.log")), b = read_text(dir.file("new.log"));
  EXPECT_EQ(a, b);
  // An old and a new name together are refused.
  r = run_pgmcl(kBase + "--out x.log --truth-out x.tum --truth y.tum", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--truth"), std::string::npos) << r.err;
  r = run_pgmcl(kBase + "--out x.log", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--truth-out is required"), std::string::npos) << r.err;
}

TEST(CliPerturbOptions, HeaderRecordsEveryConditionGiven) {
  TempDir dir("cli_perturb_header");
  write_log(dir, zigzag(30, 0.1, 0.5, 0.05));
  ASSERT_EQ(run_pgmcl(kBase + "--out plain.log --truth-out t.tum", dir).code, 0);
  EXPECT_EQ(read_text(dir.file("plain.log")).find("conditions"), std::string::npos);
  ASSERT_EQ(run_pgmcl(kBase + "--glitch 0.1,20 --min-scan-gap 0.6 --odom-model textbook "
                              "--beam-dropout 0.2 --out raw.log --truth-out t.tum",
                      dir)
                .code,
            0);
  const std::string text = read_text(dir.file("raw.log"));
  // In the order of `pgmcl perturb --help`, whatever the order on the command line.
  EXPECT_NE(text.find("# pgmcl perturb: conditions: --odom-model textbook --glitch 0.1,20 "
                      "--min-scan-gap 0.6 --beam-dropout 0.2\n"),
            std::string::npos)
      << text.substr(0, 600);
  EXPECT_NE(text.find("a1 0.01 a2 0.001 a3 0.01 a4 0.001), bias scale 0 yaw 0 deg/m, seed 5"),
            std::string::npos);
}

TEST(CliPerturbOptions, BadValuesNameTheOptionAndValueAndWriteNothing) {
  TempDir dir("cli_perturb_bad_values");
  write_log(dir, zigzag(10, 0.1, 0.5, 0.0));
  expect_usage_errors(
      dir, kBase + "--out raw.log --truth-out t.tum ",
      {
          {"--glitch 1.5,30", "--glitch: RATE must be in [0, 1], got 1.5"},
          {"--glitch -0.1,30", "--glitch: RATE must be in [0, 1], got -0.1"},
          {"--glitch 0.1,0", "--glitch: DEG must be in (0, 180], got 0"},
          {"--glitch 0.1,181", "--glitch: DEG must be in (0, 180], got 181"},
          {"--glitch 0.1", "--glitch: expected RATE,DEG, got '0.1'"},
          {"--glitch 0.1,nan", "--glitch: expected RATE,DEG, got '0.1,nan'"},
          {"--translation-glitch 0.1,-2", "--translation-glitch: M must be in [0, 100], got -2"},
          {"--translation-glitch 2,1", "--translation-glitch: RATE must be in [0, 1], got 2"},
          {"--min-scan-gap -1", "--min-scan-gap: S must be >= 0, got -1"},
          {"--min-scan-gap inf", "--min-scan-gap: expected S, got 'inf'"},
          {"--min-scan-travel -0.5", "--min-scan-travel: M must be >= 0, got -0.5"},
          {"--min-scan-travel 0.5,-3", "--min-scan-travel: DEG must be >= 0, got -3"},
          {"--min-scan-travel 0.5,3,4", "--min-scan-travel: expected M[,DEG], got '0.5,3,4'"},
          {"--beam-dropout 1", "--beam-dropout: FRACTION must be in [0, 1), got 1"},
          {"--beam-dropout 0.2,0", "--beam-dropout: SECTORS must be a whole number >= 1, got 0"},
          {"--beam-dropout 0.2,1.5",
           "--beam-dropout: SECTORS must be a whole number >= 1, got 1.5"},
          {"--beam-dropout 0.2,", "--beam-dropout: expected FRACTION[,SECTORS], got '0.2,'"},
          {"--laser-offset abc", "--laser-offset: expected X, got 'abc'"},
          {"--odom-model book", "--odom-model: expected pgmcl or textbook, got 'book'"},
          {"--scale-bias -1", "--scale-bias: F must be in (-1, 10], got -1"},
          {"--bias-scale -1.5", "--bias-scale: F must be in (-1, 10], got -1.5"},
          {"--yaw-drift nan", "--yaw-drift: expected DEG_PER_M, got 'nan'"},
      },
      {"raw.log", "t.tum"});
}

}  // namespace
}  // namespace pgmcl::perturb_test
