// metrics.yaml, progress output and the CLI error helpers.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "pgmcl/io/cli_errors.hpp"
#include "pgmcl/io/metrics.hpp"
#include "pgmcl/io/progress.hpp"

namespace pgmcl::io {
namespace {

TEST(CliReport, PercentileIsNearestRankAgainstSortedOracle) {
  std::vector<double> v;
  for (int i = 0; i < 37; ++i) v.push_back(std::fmod(i * 7.31, 11.0));
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  for (const double p : {1.0, 50.0, 95.0, 100.0}) {
    const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * 37));
    EXPECT_EQ(percentile(v, p), sorted[rank - 1]) << p;
  }
  EXPECT_EQ(percentile(v, 0.0), sorted.front());
  EXPECT_EQ(percentile({}, 95.0), 0.0);
}

TEST(CliReport, MetricsYamlHasTheDocumentedKeys) {
  MetricsAccumulator acc;
  for (int i = 1; i <= 20; ++i) acc.add_update(static_cast<double>(i), 1000 + 10 * i, 90);
  acc.add_skipped();
  acc.add_skipped();
  RunMetrics m = acc.summarise(12.5);
  EXPECT_EQ(m.updates, 20u);
  EXPECT_EQ(m.skipped_updates, 2u);
  EXPECT_DOUBLE_EQ(m.update_ms_mean, 10.5);
  EXPECT_DOUBLE_EQ(m.update_ms_p95, 19.0);
  EXPECT_DOUBLE_EQ(m.particles_mean, 1105.0);

  YAML::Node plain = YAML::Load(metrics_yaml(m));
  for (const char* key : {"updates", "skipped_updates", "update_ms_mean", "update_ms_p95", "wall_s",
                          "particles_mean", "beams_used_mean"}) {
    EXPECT_TRUE(plain[key]) << key;
  }
  EXPECT_FALSE(plain["ate_rmse_m"]);
  EXPECT_FALSE(plain["relations_trans_m"]);

  AccuracyMetrics a;
  a.ate_rmse_m = 0.042;
  a.ate_max_m = 0.31;
  a.heading_rmse_deg = 1.7;
  a.matched = 19;
  a.lock_on_s = 4.5;
  a.lock_on_travel_m = 2.25;
  a.post_lock_ate_rmse_m = 0.04;
  a.false_converged = 3;
  a.false_converged_run = 2;
  m.accuracy = a;
  m.relations = RelationsMetrics{0.021, 0.8, 140, 0.013, 0.45};
  YAML::Node full = YAML::Load(metrics_yaml(m));
  EXPECT_DOUBLE_EQ(full["ate_rmse_m"].as<double>(), 0.042);
  EXPECT_DOUBLE_EQ(full["ate_max_m"].as<double>(), 0.31);
  EXPECT_DOUBLE_EQ(full["heading_rmse_deg"].as<double>(), 1.7);
  EXPECT_TRUE(full["converged_after_s"].IsNull());
  EXPECT_DOUBLE_EQ(full["lock_on_s"].as<double>(), 4.5);
  EXPECT_DOUBLE_EQ(full["lock_on_travel_m"].as<double>(), 2.25);
  EXPECT_DOUBLE_EQ(full["post_lock_ate_rmse_m"].as<double>(), 0.04);
  EXPECT_EQ(full["false_converged"].as<int>(), 3);
  EXPECT_EQ(full["false_converged_run"].as<int>(), 2);
  EXPECT_DOUBLE_EQ(full["relations_trans_m"].as<double>(), 0.021);
  EXPECT_DOUBLE_EQ(full["relations_rot_deg"].as<double>(), 0.8);
  EXPECT_DOUBLE_EQ(full["relations_trans_std_m"].as<double>(), 0.013);
  EXPECT_DOUBLE_EQ(full["relations_rot_std_deg"].as<double>(), 0.45);
  EXPECT_EQ(full["relations_used"].as<int>(), 140);
  EXPECT_DOUBLE_EQ(full["wall_s"].as<double>(), 12.5);
  m.accuracy->converged_after_s = 3.25;
  EXPECT_DOUBLE_EQ(YAML::Load(metrics_yaml(m))["converged_after_s"].as<double>(), 3.25);
  EXPECT_NE(metrics_table(m).find("ate_rmse_m"), std::string::npos);
}

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
  EXPECT_EQ(run_reporting_errors([]() -> int { throw NotAvailableError("later"); }, err),
            kExitNotAvailable);
  EXPECT_EQ(run_reporting_errors([]() -> int { throw 42; }, err), kExitFailure);
  EXPECT_EQ(run_reporting_errors([] { return 0; }, err), kExitOk);
  EXPECT_EQ(err.str(),
            "pgmcl: error: --x: bad\npgmcl: error: f.log:3: x: y\npgmcl: error: later\n"
            "pgmcl: error: unknown exception\n");
}

}  // namespace
}  // namespace pgmcl::io
