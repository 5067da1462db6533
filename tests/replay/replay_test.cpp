// pgmcl::replay: a simulated log replayed in memory tracks its ground truth, reports what it
// skipped, and stops early on request with what it has done.
#include "pgmcl/replay/replay.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "pgmcl/config/scenario_yaml.hpp"
#include "pgmcl/io/sim_log_io.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/sims/scenario.hpp"
#include "replay_case.hpp"

namespace pgmcl::replay {
namespace {

using test::Case;

const Case& lab() {  // the UTM-30LX lab scene, shortened
  static const Case c = [] {
    Case k;
    io::ScenarioFile f =
        io::read_scenario_file(PGMCL_SOURCE_DIR "/configs/scenarios/lab.yaml", k.map);
    f.scenario.duration = std::min(f.scenario.duration, 20.0);
    const sims::SimulationLog sim = sims::simulate(f.scenario, k.map);
    k.log = io::to_carmen_log(sim);
    k.truth = io::sim_truth_trajectory(sim);
    return k;
  }();
  return c;
}

ReplayJob job_from_truth() {
  return test::job_from_truth(lab(), "lab (simulated)");
}

TEST(Replay, TracksTheSimulatedLabAndReportsEveryUpdate) {
  std::size_t announced = 0, calls = 0;
  ReplayHooks hooks;
  hooks.on_start = [&](const std::string& start, std::size_t updates) {
    EXPECT_NE(start.find("ground truth at the first scan"), std::string::npos) << start;
    announced = updates;
  };
  hooks.on_update = [&](std::size_t done, std::size_t all, const UpdateResult&) {
    EXPECT_EQ(done, ++calls);
    EXPECT_EQ(all, announced);
  };
  const ReplayResult r = run(job_from_truth(), hooks);
  EXPECT_TRUE(r.complete);
  ASSERT_GT(announced, 10u);
  EXPECT_EQ(calls, announced);
  EXPECT_EQ(r.trajectory.size(), announced);
  EXPECT_EQ(r.rows.size(), announced);
  EXPECT_TRUE(r.warnings.empty());
  ASSERT_TRUE(r.metrics.accuracy.has_value());
  EXPECT_LT(r.metrics.accuracy->ate_rmse_m, 0.05);
  EXPECT_EQ(r.metrics.updates + r.metrics.skipped_updates, announced);
  ASSERT_EQ(r.particles.size(), r.weights.size());
  double sum = 0.0;
  for (double w : r.weights) sum += w;
  EXPECT_NEAR(sum, 1.0, 1e-9);
}

TEST(Replay, StopsWhenAskedAndKeepsWhatIsDone) {
  std::atomic<bool> stop{false};
  ReplayHooks hooks;
  hooks.stop = &stop;
  hooks.on_update = [&](std::size_t done, std::size_t, const UpdateResult&) {
    if (done == 5) stop = true;
  };
  const ReplayResult r = run(job_from_truth(), hooks);
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.trajectory.size(), 5u);
  ASSERT_TRUE(r.metrics.accuracy.has_value());
  EXPECT_EQ(r.metrics.accuracy->matched, 5u);
}

TEST(Replay, WarnsWhenTheTruthDoesNotCoverTheFirstScanAndStartsGlobally) {
  ReplayJob job = job_from_truth();
  io::Trajectory late;
  for (const auto& t : *job.truth)
    if (t.stamp > job.truth->front().stamp + 10.0) late.push_back(t);
  job.truth = late;
  job.config.filter.global_particles = 2000;
  const ReplayResult r = run(job);
  EXPECT_EQ(r.start, "global localisation");
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("no ground-truth pose at the first scan"), std::string::npos);
  // The first 10 s are not scored, and the figures say so.
  EXPECT_NE(r.warnings[1].find("against the ground truth: only "), std::string::npos)
      << r.warnings[1];
  ASSERT_TRUE(r.metrics.accuracy.has_value());
  const auto& a = *r.metrics.accuracy;
  EXPECT_LT(a.matched, r.trajectory.size());
  EXPECT_DOUBLE_EQ(a.matched_fraction, static_cast<double>(a.matched) / r.trajectory.size());
}

TEST(Replay, ALogWithoutOdometryIsAUsageError) {
  io::CarmenLog empty;
  ReplayJob job;
  job.map = &lab().map;
  job.log = &empty;
  job.log_name = "empty.log";
  EXPECT_THROW((void)run(job), io::UsageError);
  job.map = nullptr;
  EXPECT_THROW((void)run(job), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::replay
