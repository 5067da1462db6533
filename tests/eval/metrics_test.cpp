// metrics.yaml: the percentile and the documented keys.
#include "pgmcl/eval/metrics.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace pgmcl::io {
namespace {

TEST(Metrics, PercentileIsNearestRankAgainstSortedOracle) {
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

TEST(Metrics, MetricsYamlHasTheDocumentedKeys) {
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

}  // namespace
}  // namespace pgmcl::io
