// Progress output, the option-value parsers and the CLI error reporting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cli_errors.hpp"
#include "pgmcl/io/values.hpp"
#include "progress.hpp"

namespace pgmcl::app {
namespace {

using io::parse_key_value;
using io::parse_number;
using io::parse_number_list;
using io::UsageError;

TEST(CliReport, PlainProgressPrintsAboutEveryTenPercent) {
  std::ostringstream out;
  Progress p(out, Progress::Mode::kPlain, "localize", 200);
  for (std::size_t i = 1; i <= 200; ++i) p.update(i);
  p.finish("ATE 0.05 m");
  const std::string s = out.str();
  EXPECT_EQ(s.find('\r'), std::string::npos);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 11);  // 10 %, 20 %, ..., 100 % + done
  EXPECT_NE(s.find("localize: 100/200 (50%)"), std::string::npos);
  EXPECT_NE(s.find("done, 200/200"), std::string::npos);
  EXPECT_NE(s.find("ATE 0.05 m"), std::string::npos);
}

TEST(CliReport, TerminalProgressRedrawsInPlace) {
  std::ostringstream out;
  ProgressOptions o;
  o.redraw_s = 0.0;
  Progress p(out, Progress::Mode::kTerminal, "map", 4, o);
  for (std::size_t i = 1; i <= 4; ++i) p.update(i);
  p.finish();
  const std::string s = out.str();
  EXPECT_EQ(std::count(s.begin(), s.end(), '\r'), 5);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1);
  EXPECT_NE(s.find("[##############################]"), std::string::npos);
  std::ostringstream quiet;
  Progress q(quiet, Progress::Mode::kSilent, "x", 3);
  q.update(3);
  q.finish();
  EXPECT_TRUE(quiet.str().empty());
}

TEST(CliReport, OptionParsersNameTheOptionAndTheText) {
  EXPECT_DOUBLE_EQ(parse_number(" 2.5", "--x"), 2.5);
  EXPECT_DOUBLE_EQ(parse_number("+1e-3", "--x"), 1e-3);
  try {
    (void)parse_number("2.5m", "--resolution");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("--resolution"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("'2.5m'"), std::string::npos);
  }
  EXPECT_THROW((void)parse_number("nan", "--x"), UsageError);
  const auto v = parse_number_list("1,2,-0.5", "--init", {3, 6}, "X,Y,THETA[,SX,SY,STH]");
  EXPECT_EQ(v, (std::vector<double>{1.0, 2.0, -0.5}));
  try {
    (void)parse_number_list("1,2", "--init", {3, 6}, "X,Y,THETA[,SX,SY,STH]");
    FAIL();
  } catch (const UsageError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("--init"), std::string::npos);
    EXPECT_NE(w.find("X,Y,THETA"), std::string::npos);
    EXPECT_NE(w.find("2 values"), std::string::npos);
  }
  EXPECT_THROW((void)parse_number_list("1,,3", "--init", {3}, "X,Y,THETA"), UsageError);
  const auto kv = parse_key_value("filter.particles = 2000", "--set");
  EXPECT_EQ(kv.first, "filter.particles");
  EXPECT_EQ(kv.second, "2000");
  EXPECT_THROW((void)parse_key_value("=3", "--set"), UsageError);
  EXPECT_THROW((void)parse_key_value("novalue", "--set"), UsageError);
}

TEST(CliReport, ErrorsBecomeOneLineAndAnExitCode) {
  std::ostringstream err;
  EXPECT_EQ(run_reporting_errors([]() -> int { throw UsageError("--x: bad"); }, err), kExitUsage);
  EXPECT_EQ(run_reporting_errors([]() -> int { throw std::runtime_error("f.log:3: x: y"); }, err),
            kExitFailure);
  EXPECT_EQ(run_reporting_errors([]() -> int { throw 42; }, err), kExitFailure);
  EXPECT_EQ(run_reporting_errors([] { return 0; }, err), kExitOk);
  EXPECT_EQ(err.str(),
            "pgmcl: error: --x: bad\npgmcl: error: f.log:3: x: y\n"
            "pgmcl: error: unknown exception\n");
}

}  // namespace
}  // namespace pgmcl::app
