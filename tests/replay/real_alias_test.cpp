// A global start on a real log whose odometry glitches, drifts and comes a scan per 1.2 m
// or 35 deg (data/README.md: aces, the robustness suite's heldout case of seed 20, 0-200 s).
// The estimate is within 1 m from 3 s on. At 92 s a place the global search had proposed,
// 12.4 m away and turned 88 deg, has gained 12.9 nats over the prediction over 8.5 m of
// view. But neither explains the scan as the map usually does there: 0.925 and 0.90 of the
// probe beams fit, against a usual 0.97. A place from the global search wins only where it
// does (HypothesisTracker::may_switch). Before that rule the set moved there under all
// three filter seeds below and stayed 12-16 m off until the end of the excerpt.
#include <gtest/gtest.h>

#include <cstdio>

#include "pgmcl/io/trajectory.hpp"
#include "pgmcl/replay/replay.hpp"
#include "replay_case.hpp"

namespace pgmcl::replay {
namespace {

const test::Case& aces_heldout() {
  static const test::Case e =
      test::load_case(PGMCL_SOURCE_DIR "/data/maps/aces/aces-0.05.yaml",
                      PGMCL_SOURCE_DIR "/data/logs/aces-heldout-s20-0-200s");
  return e;
}

TEST(RealAlias, AGlobalSearchPlaceThatFitsWorseThanUsualDoesNotTakeTheSet) {
  for (const std::uint64_t seed : {20, 1020, 2020}) {
    ReplayJob job = test::job_from_truth(aces_heldout(), "aces heldout excerpt");
    job.init.kind = InitialBelief::Kind::kGlobal;
    job.config.seed = seed;
    const ReplayResult r = run(job);
    ASSERT_TRUE(r.metrics.accuracy.has_value());
    const io::AccuracyMetrics& a = *r.metrics.accuracy;
    std::printf("  seed %llu: locked on after %.1f s, then ATE %.3f m (max %.3f)\n",
                static_cast<unsigned long long>(seed), a.lock_on_s.value_or(-1.0),
                a.post_lock_ate_rmse_m, a.post_lock_ate_max_m);
    // Seen: locked on at 2.8 s, then 0.05 m (max 0.11-0.15 m), on all three seeds.
    ASSERT_TRUE(a.lock_on_s.has_value()) << "seed " << seed << ": lost at the end";
    EXPECT_LT(*a.lock_on_s, 60.0) << "seed " << seed;
    EXPECT_LT(a.post_lock_ate_max_m, 1.0) << "seed " << seed;
    EXPECT_LT(a.post_lock_ate_rmse_m, 0.1) << "seed " << seed;
  }
}

}  // namespace
}  // namespace pgmcl::replay
