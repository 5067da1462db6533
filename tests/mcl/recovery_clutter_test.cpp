// Recovery must not hijack tracking (issue 3): with augmented-MCL injection enabled, a
// stretch of scans that fit the map badly at the true pose (unmapped clutter: people,
// furniture moved in after mapping) makes the filter inject random poses; none of them may
// take over. On the SICK logs the textbook scheme let a random pose win (intel 1.6 m,
// fr079 9.1 m ATE; configs/experiments/README.md); injected lineages are now on probation
// (RecoveryConfig).
#include <gtest/gtest.h>

#include <cstdio>

#include "closed_loop.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

struct Cluttered {
  test::LoopErrors before, during, after;
  std::size_t injected = 0;
};

// The room's map; the scans of steps [40, 160) also see unmapped boxes all around the path.
Cluttered run_with_clutter(const LocalizerConfig& cfg, std::uint64_t seed) {
  const test::World world = test::make_room(0.05);
  test::World cluttered = world;  // same grid (the map), more rectangles (what the laser sees)
  for (double x = 2.5; x < 9.0; x += 0.9) {
    cluttered.rects.push_back({x, 3.8, x + 0.3, 4.1});  // along the lower leg of the loop
    cluttered.rects.push_back({x + 0.4, 5.0, x + 0.6, 5.2});
    cluttered.rects.push_back({x, 6.9, x + 0.4, 7.1});  // along the upper leg
  }
  for (double y = 5.0; y < 7.2; y += 0.7) {
    cluttered.rects.push_back({8.3, y, 8.5, y + 0.3});
    cluttered.rects.push_back({2.0, y, 2.2, y + 0.2});
  }
  const auto truth = test::loop_trajectory();
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, seed);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  Localizer loc(world.grid, cfg);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.diagonal() << 0.01, 0.01, 0.003;
  loc.set_pose(truth[0], cov);
  Cluttered c;
  const std::size_t a = 40, b = 160, end = truth.size();
  c.before = test::run_loop(loc, world, truth, odom, spec, {.noise_seed = seed + 1, .end = a});
  // run_loop does not report injections; count them per step on the cluttered stretch.
  for (std::size_t k = a; k < b; ++k) {
    const test::LoopErrors e = test::run_loop(
        loc, cluttered, truth, odom, spec, {.noise_seed = seed + 2 + k, .begin = k, .end = k + 1});
    c.injected += loc.last_result().injected;
    c.during.err_xy.push_back(e.final_xy);
    c.during.max_xy = std::max(c.during.max_xy, e.final_xy);
    if (e.final_xy > 0.3) ++c.during.measured;  // reused: steps more than 0.3 m off
  }
  c.after = test::run_loop(loc, world, truth, odom, spec,
                           {.noise_seed = seed + 3, .begin = b, .end = end});
  return c;
}

TEST(RecoveryWithClutter, InjectionDoesNotHijackTracking) {
  for (const std::uint64_t seed : {1, 2}) {
    LocalizerConfig cfg;  // engine defaults: recovery enabled, probation 15 / 2 %
    cfg.threads = 1;
    const Cluttered c = run_with_clutter(cfg, seed);
    std::printf(
        "  seed %llu: injected %zu, max error before %.3f m, in the clutter %.3f m "
        "(%zu steps > 0.3 m), after %.3f m, final %.3f m\n",
        static_cast<unsigned long long>(seed), c.injected, c.before.max_xy, c.during.max_xy,
        c.during.measured, c.after.max_xy, c.after.final_xy);
    EXPECT_LT(c.before.max_xy, 0.1);
    // The clutter does trigger augmented MCL (tens of thousands of injected poses)...
    EXPECT_GT(c.injected, 1000u) << "the scenario no longer exercises injection";
    // ...but no random pose takes over. Seen (seeds 1-4): max error in the clutter 0.15-0.51
    // m (recovery off: 0.09-0.12 m); with probation 0 (textbook Table 8.3) 7.1-10.0 m, a
    // random pose winning.
    EXPECT_LT(c.during.max_xy, 1.0) << "an injected pose took over";
    // Seen: 0.07-0.11 m max after the clutter, 9-27 mm at the end.
    EXPECT_LT(c.after.max_xy, 0.2);
    EXPECT_LT(c.after.final_xy, 0.05);
  }
}

}  // namespace
}  // namespace pgmcl
