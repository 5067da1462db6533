// The pgmcl command line: subcommands, usage errors, `pgmcl kernel` against the generator.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "pgmcl/sensor_model/kernel_table.hpp"

namespace pgmcl {
namespace {

using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

TEST(CliCommands, AllSubcommandsAreRegistered) {
  TempDir dir("cli_commands_help");
  const RunResult r = run_pgmcl("--help", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* c : {"localize", "run", "simulate", "map", "perturb", "perturb-map", "eval",
                        "kernel", "calibrate"}) {
    EXPECT_NE(r.out.find(std::string("  ") + c + " "), std::string::npos) << c;
  }
  const RunResult none = run_pgmcl("", dir);
  EXPECT_EQ(none.code, 2);
  EXPECT_EQ(none.err.rfind("pgmcl: error: ", 0), 0u) << none.err;
  const RunResult bogus = run_pgmcl("frobnicate", dir);
  EXPECT_EQ(bogus.code, 2);
  EXPECT_NE(bogus.err.find("frobnicate"), std::string::npos) << bogus.err;
  const RunResult sub_help = run_pgmcl("map --help", dir);
  EXPECT_EQ(sub_help.code, 0);
  EXPECT_NE(sub_help.out.find("--resolution"), std::string::npos) << sub_help.out;
}

TEST(CliCommands, MissingRequiredOptionsNameTheOption) {
  TempDir dir("cli_commands_required");
  RunResult r = run_pgmcl("map --out m.yaml", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--log"), std::string::npos) << r.err;
  r = run_pgmcl("kernel --cell abc", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--cell"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'abc'"), std::string::npos) << r.err;
}

/// Parses the kernel rows printed by `pgmcl kernel` (lines of tab-separated numbers).
std::vector<std::vector<double>> kernel_rows(const std::string& out) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || !(std::isdigit(static_cast<unsigned char>(line[0])))) continue;
    std::istringstream ls(line);
    std::vector<double> row;
    double v = 0;
    while (ls >> v) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

TEST(CliCommands, KernelPrintsTheGeneratorsTableInPaperLayout) {
  TempDir dir("cli_commands_kernel");
  for (const bool integrated : {false, true}) {
    const RunResult r = run_pgmcl(std::string("kernel --sigma-x 5.6894 --sigma-y 3 --cell 5") +
                                      (integrated ? " --integrated" : ""),
                                  dir);
    ASSERT_EQ(r.code, 0) << r.err;
    sensor_model::KernelSpec spec;
    spec.discretisation = integrated ? sensor_model::Discretisation::kCellIntegrated
                                     : sensor_model::Discretisation::kPointwise;
    const auto t = sensor_model::make_kernel_table(spec);
    const auto rows = kernel_rows(r.out);
    ASSERT_EQ(rows.size(), 3u) << r.out;
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(rows[i].size(), 3u);
      // Paper layout (Table 5): row = offset along the beam at 0 deg (map x).
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(rows[i][j], t.at(i - 1, j - 1), 0.5e-4);
    }
    // Along-beam neighbours are above and below the centre, as in Table 5.
    EXPECT_GT(rows[0][1], rows[1][0]);
    EXPECT_NE(r.out.find("sum 1.0000"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(integrated ? "cell-integrated" : "pointwise"), std::string::npos);
  }
}

TEST(CliCommands, KernelAtNinetyDegreesIsTheTranspose) {
  TempDir dir("cli_commands_kernel90");
  const RunResult a = run_pgmcl("kernel --integrated", dir);
  const RunResult b = run_pgmcl("kernel --integrated --angle 90", dir);
  ASSERT_EQ(a.code, 0);
  ASSERT_EQ(b.code, 0);
  const auto ra = kernel_rows(a.out), rb = kernel_rows(b.out);
  ASSERT_EQ(ra.size(), 3u);
  ASSERT_EQ(rb.size(), 3u);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(ra[i][j], rb[j][i], 1e-4);
}

}  // namespace
}  // namespace pgmcl
