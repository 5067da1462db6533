// Recovery: global localisation from several starts and the kidnapped robot (augmented
// MCL, Probabilistic Robotics Table 8.3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "closed_loop.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

LocalizerConfig global_config() {
  LocalizerConfig cfg;
  cfg.threads = 2;
  return cfg;
}

class GlobalLocalisation : public ::testing::TestWithParam<std::size_t> {};

// From a uniform start over the free space, the filter converges onto the true pose
// within a bounded number of updates, whichever part of the loop the robot starts on.
TEST_P(GlobalLocalisation, ConvergesFromAnywhere) {
  const std::size_t start = GetParam();
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory();
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 100 + start);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  Localizer loc(world.grid, global_config());  // starts uniform (global_localize)
  ASSERT_EQ(loc.particles().size(), loc.config().filter.global_particles);
  constexpr std::size_t kBudget = 40;  // updates
  const test::LoopErrors e =
      test::run_loop(loc, world, truth, odom, spec,
                     {.noise_seed = 7 + start, .begin = start, .end = start + kBudget});
  // Seen: converged after 3 / 2 / 5 / 2 updates (starts 0 / 60 / 110 / 170), final
  // error 0.4-3.6 cm, 1000 particles (KLD's minimum) at the end.
  ASSERT_NE(e.first_converged, static_cast<std::size_t>(-1)) << "never converged";
  RecordProperty("converged_after", std::to_string(e.first_converged - start));
  RecordProperty("final_xy_m", std::to_string(e.final_xy));
  RecordProperty("last_particles", std::to_string(e.last_particles));
  EXPECT_LT(e.first_converged - start, 25u);
  EXPECT_LT(e.final_xy, 0.1);
  EXPECT_LT(e.final_theta, 3 * kDeg);
  // KLD shrank the 20000-particle global set once the posterior was compact.
  EXPECT_LT(e.last_particles, 5000u);
}

INSTANTIATE_TEST_SUITE_P(Starts, GlobalLocalisation, ::testing::Values(0, 60, 110, 170));

// The robot is carried to another place without odometry noticing; the filter, confident
// at the old place, must notice (w_fast drops below w_slow, the scan stops fitting) and
// re-converge on the new place, whatever its own random draws: over 25 filter seeds.
TEST(Kidnapping, RecoversAfterBeingCarriedAway) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory();
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 17);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  // Kidnap: truth jumps from step 40 to step 150 (several metres, other heading), while
  // odometry continues from where it was as if the robot had driven on normally.
  std::vector<Pose2> truth2(truth.begin(), truth.begin() + 40);
  std::vector<Pose2> odom2(odom.begin(), odom.begin() + 40);
  for (std::size_t k = 150; k < truth.size(); ++k) {
    truth2.push_back(truth[k]);
    odom2.push_back(odom2.back().compose(odom[k - 1].between(odom[k])));
  }
  ASSERT_GT(test::xy_error(truth2[39], truth2[40]), 3.0);
  std::size_t slowest = 0;
  for (std::uint64_t seed = 1; seed <= 25; ++seed) {
    LocalizerConfig cfg = global_config();
    cfg.seed = seed;
    Localizer loc(world.grid, cfg);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    cov.diagonal() << 0.01, 0.01, 0.003;
    loc.set_pose(truth[0], cov);
    const test::LoopErrors before =
        test::run_loop(loc, world, truth, odom, spec, {.noise_seed = 1, .end = 40});
    ASSERT_LT(before.final_xy, 0.1) << "seed " << seed;
    ASSERT_TRUE(loc.last_result().converged) << "seed " << seed;
    const test::LoopErrors after =
        test::run_loop(loc, world, truth2, odom2, spec,
                       {.noise_seed = 2, .begin = 40, .end = truth2.size(), .t0 = 100.0});
    std::size_t recovered_at = 0;
    for (std::size_t k = 0; k < after.err_xy.size(); ++k)
      if (after.err_xy[k] > 0.1) recovered_at = k + 1;
    slowest = std::max(slowest, recovered_at);
    // Seen: back within 10 cm 14 updates after the kidnapping on every seed, the true
    // place (found by the map sweep) taking over as a kidnapping after ten lost scans.
    // Before a stronger competitor blocked weaker ones, 7 of 100 seeds switched first to
    // a place that fitted only two thirds of the beams, and stayed there 5 m off.
    EXPECT_LT(recovered_at, 30u) << "seed " << seed << ": still lost at update " << recovered_at;
    EXPECT_LT(after.final_xy, 0.1) << "seed " << seed;
    EXPECT_LT(after.final_theta, 3 * kDeg) << "seed " << seed;
  }
  RecordProperty("slowest_recovery", std::to_string(slowest));
}

// A glitch or a slip on the very update after global localisation converged. The tracker's
// running fit starts from the scan that converged, so the fall shows; and the places the
// global search seeded are held on probation, so none of them takes the set while the
// converged cluster misfits (on the robustness suite's noisier odometry one did, 17-42 m
// off). Seen before, over seeds 1-40: 60 deg unabsorbed on 28, 90 deg on 34, the slip on 37.
TEST(GlobalLocalisation, AGlitchRightAfterConvergingIsAbsorbed) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory(0.5, 15 * kDeg);
  struct Glitch {
    const char* name;
    Pose2 odometry_error;
    std::size_t allowed;  // updates more than 1 m off (issue 13: 5 for a heading glitch)
  };
  for (const Glitch& g :
       {Glitch{"60 deg", {0.0, 0.0, 60 * kDeg}, 5}, Glitch{"90 deg", {0.0, 0.0, 90 * kDeg}, 5},
        Glitch{"2 m slip", {1.4, -1.4, 0.0}, 10}}) {
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
      const auto odom = test::noisy_odometry(truth, MotionNoise{}, seed);
      LocalizerConfig cfg = global_config();
      cfg.threads = 1;
      cfg.seed = seed;
      Localizer loc(world.grid, cfg);
      test::ScanSpec spec;
      spec.noise_sigma = 0.01;
      Rng noise(seed + 3);
      std::size_t converged_at = 0, off = 0;
      double final_xy = 0.0;
      for (std::size_t k = 0; k < truth.size(); ++k) {
        // From the update after the first convergence on, odometry carries the error.
        Pose2 o = odom[k];
        if (converged_at > 0) {
          const Pose2& base = odom[converged_at];
          o = base.compose(g.odometry_error).compose(base.between(odom[k]));
        }
        const UpdateResult r = loc.update(o, world.scan(truth[k], spec, &noise), 2.0 * k);
        final_xy = test::xy_error(r.estimate, truth[k]);
        if (converged_at > 0 && final_xy > 1.0) ++off;
        if (converged_at == 0 && r.converged) {
          ASSERT_LT(final_xy, 1.0) << g.name << ", seed " << seed << ": converged off";
          converged_at = k;
        }
      }
      ASSERT_GT(converged_at, 0u) << g.name << ", seed " << seed << ": never converged";
      EXPECT_LE(off, g.allowed) << g.name << ", seed " << seed;
      EXPECT_LT(final_xy, 0.1) << g.name << ", seed " << seed;
    }
  }
}

// Global localisation with sparse scans (0.5 m / 15 deg apart): while the set still holds
// several places, the reported pose is the best one of its own place, not the middle of a
// cloud the tempering limit keeps broad.
TEST(GlobalLocalisation, EstimateBeforeConvergenceIsTheBestOfItsPlace) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory(0.5, 15 * kDeg);
  double sum = 0.0;
  std::size_t near = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const auto odom = test::noisy_odometry(truth, MotionNoise{}, seed);
    test::ScanSpec spec;
    spec.noise_sigma = 0.01;
    LocalizerConfig cfg = global_config();
    cfg.seed = seed;
    Localizer loc(world.grid, cfg);
    Rng noise(seed + 3);
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const UpdateResult r = loc.update(odom[k], world.scan(truth[k], spec, &noise), 2.0 * k);
      const double e = test::xy_error(r.estimate, truth[k]);
      if (!r.converged && e < 1.0) {
        sum += e;
        ++near;
      }
    }
  }
  std::printf("  %zu unconverged updates within 1 m, mean error %.3f m\n", near,
              near ? sum / near : 0.0);
  // Seen: 12 such updates, 0.022 m; reporting the cluster's mean under the tempered
  // weights instead: 0.318 m.
  ASSERT_GE(near, 6u) << "the scenario no longer has unconverged updates near the truth";
  EXPECT_LT(sum / near, 0.1);
}

}  // namespace
}  // namespace pgmcl
