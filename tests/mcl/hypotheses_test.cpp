// Competing hypotheses (HypothesesConfig): motion that odometry cannot explain is absorbed
// by a scan-to-map search around the prediction, and the filter does not report
// `converged` while another place fits better. Each mechanism is checked on and off.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <vector>

#include "closed_loop.hpp"
#include "hypothesis_tracker.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The loop through the test room, 0.5 m / 15 deg steps (sparse scans, as on the SICK logs),
// with realistic odometry noise; from step `at` on, the odometry carries `glitch`, applied
// at the start of that step: Pose2{0, 0, heading} turns the rest of the path.
struct Glitched {
  std::vector<Pose2> truth, odom;
  std::size_t at;
};

Glitched glitched_path(std::size_t at, const Pose2& glitch, std::uint64_t seed,
                       const MotionNoise& noise = {}) {
  Glitched g{test::loop_trajectory(0.5, 15 * kDeg), {}, at};
  g.odom = test::noisy_odometry(g.truth, noise, seed);
  // Everything from `at` on is seen through the glitch: odom[k] = odom[at-1] ∘ glitch ∘ inc.
  const Pose2 base = g.odom[at - 1];
  for (std::size_t k = at; k < g.odom.size(); ++k)
    g.odom[k] = base.compose(glitch).compose(base.between(g.odom[k]));
  return g;
}

struct Recovery {
  std::size_t updates_to_recover = 1000;  // steps after the glitch until back within bounds
  double max_after = 0.0;                 // metres, from the recovery on
  double max_before = 0.0;                // metres, before the glitch
  // As the robustness benchmark scores it: steps after the glitch until first back within
  // 0.25 m, and the largest error from then on (clutter may add brief excursions later).
  std::size_t updates_to_first_return = 1000;
  double max_after_return = 0.0;
};

// How many updates after the glitch the error stays above 0.2 m, and the errors around it.
Recovery recovery_of(const std::vector<double>& err_xy, std::size_t at) {
  Recovery r;
  for (std::size_t k = 0; k < at; ++k) r.max_before = std::max(r.max_before, err_xy[k]);
  std::size_t k = err_xy.size();
  while (k > at && err_xy[k - 1] < 0.2) --k;
  if (k < err_xy.size()) {
    r.updates_to_recover = k - at;
    for (std::size_t i = k; i < err_xy.size(); ++i) r.max_after = std::max(r.max_after, err_xy[i]);
  }
  for (std::size_t i = at; i < err_xy.size(); ++i)
    if (err_xy[i] < 0.25) {
      r.updates_to_first_return = i - at;
      for (std::size_t j = i; j < err_xy.size(); ++j)
        r.max_after_return = std::max(r.max_after_return, err_xy[j]);
      break;
    }
  return r;
}

// One thread, `seed`, and a tight start on the loop's first pose. Without hypotheses the
// motion-noise adaptation is off too: its widened cloud absorbed the 35 deg glitch on one
// seed, and these tests measure what the search alone does.
LocalizerConfig loop_config(std::uint64_t seed, bool hypotheses) {
  LocalizerConfig cfg;
  cfg.threads = 1;
  cfg.seed = seed;
  cfg.hypotheses.enabled = hypotheses;
  cfg.motion.adaptation.enabled = hypotheses;
  return cfg;
}
// The contrasts without a mechanism run on a thinner set as well: a thousand particles
// sometimes stumble on what the mechanism finds, a few hundred do not.
constexpr std::size_t kThinSet = 300;
void start_tight(Localizer& loc, const Pose2& start) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.diagonal() << 0.01, 0.01, 0.003;
  loc.set_pose(start, cov);
}

Recovery run_glitched(const Glitched& g, bool hypotheses, std::uint64_t seed,
                      std::size_t min_particles = KldConfig{}.min_particles) {
  const test::World world = test::make_room(0.05);
  LocalizerConfig cfg = loop_config(seed, hypotheses);
  cfg.filter.kld.min_particles = min_particles;
  Localizer loc(world.grid, cfg);
  start_tight(loc, g.truth[0]);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  const test::LoopErrors e = test::run_loop(loc, world, g.truth, g.odom, spec,
                                            {.noise_seed = seed + 7, .end = g.truth.size()});
  return recovery_of(e.err_xy, g.at);
}

// The same loop in a crowd the map does not show: eight 40 cm "people" stand 0.9-1.7 m
// around the robot wherever it is from step `crowd_from` on, and hide most of the walls.
Recovery run_crowded(const Glitched& g, std::uint64_t seed, std::size_t crowd_from = 0,
                     bool free_space_weights = true,
                     std::size_t min_particles = KldConfig{}.min_particles) {
  const test::World map_world = test::make_room(0.05);
  LocalizerConfig cfg = loop_config(seed, true);
  cfg.hypotheses.free_space_weights = free_space_weights;
  cfg.filter.kld.min_particles = min_particles;
  Localizer loc(map_world.grid, cfg);
  start_tight(loc, g.truth[0]);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  Rng noise(seed + 7), crowd(seed + 11);
  std::vector<double> err;
  for (std::size_t k = 0; k < g.truth.size(); ++k) {
    test::World scene = map_world;
    const Pose2& p = g.truth[k];
    if (k >= crowd_from) test::add_crowd(scene, p, crowd);
    const UpdateResult r = loc.update(g.odom[k], scene.scan(p, spec, &noise), 0.1 * k);
    err.push_back(test::xy_error(r.estimate, p));
  }
  return recovery_of(err, g.at);
}

TEST(Hypotheses, HeadingGlitchOf35DegreesIsAbsorbedWithinFiveUpdates) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Glitched g = glitched_path(30, {0.0, 0.0, 35 * kDeg}, seed);
    const Recovery on = run_glitched(g, true, seed);
    const Recovery thin = run_glitched(g, true, seed, kThinSet);
    const Recovery off = run_glitched(g, false, seed, kThinSet);
    std::printf(
        "  seed %llu: recovered after %zu updates (%zu particles: %zu, and %zu without the "
        "search), max error after %.3f m\n",
        static_cast<unsigned long long>(seed), on.updates_to_recover, kThinSet,
        thin.updates_to_recover, off.updates_to_recover, on.max_after);
    for (const Recovery& r : {on, thin}) {
      EXPECT_LT(r.max_before, 0.1);
      EXPECT_LE(r.updates_to_recover, 5u);
      EXPECT_LT(r.max_after, 0.2);
    }
    // Without the search the particles do not see the right heading in time (seen: back
    // after 11 updates on seed 2, never on the others).
    EXPECT_GT(off.updates_to_recover, 5u);
  }
}

TEST(Hypotheses, TwoMetreSlipIsAbsorbedWithinTenUpdates) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Glitched g = glitched_path(40, {1.4, -1.4, 0.0}, seed);
    const Recovery on = run_glitched(g, true, seed);
    const Recovery off = run_glitched(g, false, seed);
    std::printf("  seed %llu: recovered after %zu updates (off: %zu), max error after %.3f m\n",
                static_cast<unsigned long long>(seed), on.updates_to_recover,
                off.updates_to_recover, on.max_after);
    EXPECT_LE(on.updates_to_recover, 10u);
    EXPECT_LT(on.max_after, 0.2);
    EXPECT_GT(off.updates_to_recover, 10u);
  }
}

// A crowd that gathers after a long clear stretch keeps every pose's fit below what the map
// usually gives, the corrected one's too, so after a slip only the free space tells it
// apart: its readings cross far fewer walls than the prediction's (seen without that
// confirmation for slips: seed 1 never back, the others after 3-8 updates).
TEST(Hypotheses, TwoMetreSlipAmidACrowdIsAbsorbedWithinTenUpdates) {
  for (const std::uint64_t seed : {1, 2, 3, 4, 5, 6}) {
    const Recovery r = run_crowded(glitched_path(40, {1.4, -1.4, 0.0}, seed), seed, 36);
    std::printf("  seed %llu: back after %zu updates, max error before %.3f m, after %.3f m\n",
                static_cast<unsigned long long>(seed), r.updates_to_first_return, r.max_before,
                r.max_after_return);
    EXPECT_LT(r.max_before, 0.2);
    EXPECT_LE(r.updates_to_first_return, 10u);
    EXPECT_LT(r.max_after_return, 1.0);
  }
}

// Table 5.6 on a short reversal can turn the odometry by more than the rescue search's first
// window (40 deg), and a crowd keeps the fit from falling at once: the corrected pose is then
// often found by the map sweep, and must win as a glitch correction whichever search found
// it (seen without: 70 deg back after 9 updates, 90 deg after 17-18).
TEST(Hypotheses, HeadingGlitchBeyondTheRescueWindowAmidACrowdIsAbsorbed) {
  for (const double deg : {70.0, 90.0}) {
    for (const std::uint64_t seed : {1, 2, 3, 4}) {
      const Recovery r = run_crowded(glitched_path(34, {0.0, 0.0, deg * kDeg}, seed), seed);
      std::printf("  %.0f deg, seed %llu: recovered after %zu updates, max error after %.3f m\n",
                  deg, static_cast<unsigned long long>(seed), r.updates_to_recover, r.max_after);
      EXPECT_LE(r.updates_to_recover, 5u);
      EXPECT_LT(r.max_after, 0.2);
    }
  }
}

// A crowd hides most walls, and the fit falls for it as well as for a glitch.
TEST(Hypotheses, HeadingGlitchAmidACrowdIsAbsorbedWithinFiveUpdates) {
  for (const std::uint64_t seed : {1, 2, 3, 4}) {
    const Glitched g = glitched_path(34, {0.0, 0.0, 30 * kDeg}, seed);
    const Recovery r = run_crowded(g, seed);
    std::printf("  seed %llu: recovered after %zu updates, max error before %.3f m, after %.3f m\n",
                static_cast<unsigned long long>(seed), r.updates_to_recover, r.max_before,
                r.max_after);
    EXPECT_LT(r.max_before, 0.2);
    EXPECT_LE(r.updates_to_recover, 5u);
    EXPECT_LT(r.max_after, 0.2);
  }
}

// Odometry ten times noisier in heading than the model, amid the crowd all along: the
// learnt motion noise widens the heading proposal, and a particle turned so that the
// people's readings land on walls can outfit the true heading, its rays passing through
// walls to get there. While the scan does not fit, the particles that carry the weight
// lose those readings' credit (HypothesesConfig::free_space_weights).
TEST(Hypotheses, NoisyOdometryAmidACrowdDoesNotTurnTheEstimate) {
  MotionNoise noisier;  // the robustness benchmark's "noisier" condition
  noisier.a1 = 0.05;
  noisier.a2 = 0.005;
  noisier.a3 = 0.02;
  noisier.a4 = 0.002;
  int lost_without = 0;
  for (const std::uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8}) {
    const Glitched g = glitched_path(1, {}, seed, noisier);
    const Recovery on = run_crowded(g, seed, 0, true);
    const Recovery thin = run_crowded(g, seed, 0, true, kThinSet);
    const Recovery off = run_crowded(g, seed, 0, false, kThinSet);
    std::printf(
        "  seed %llu: max error %.3f m; %zu particles: %.3f m, without the discount %.3f m\n",
        static_cast<unsigned long long>(seed), on.max_after_return, kThinSet, thin.max_after_return,
        off.max_after_return);
    EXPECT_LT(on.max_after_return, 0.5);
    EXPECT_LT(thin.max_after_return, 0.5);
    lost_without += off.max_after_return >= 0.5 ? 1 : 0;
  }
  EXPECT_GT(lost_without, 0) << "the scene no longer tests the discount";
}

// The filter is put, tightly, on a wrong place (as a global localisation that settled on the
// wrong corridor would leave it). The map sweep finds the true place, which fits every scan
// better: from then on the filter must not report `converged`.
TEST(Hypotheses, AWrongPlaceIsNotReportedConvergedForLong) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory(0.5, 15 * kDeg);
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 5);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  for (const bool on : {true, false}) {
    LocalizerConfig cfg;
    cfg.threads = 1;
    cfg.hypotheses.enabled = on;
    cfg.filter.recovery.enabled = false;  // the flag alone, not augmented MCL's recovery
    Localizer loc(world.grid, cfg);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    cov.diagonal() << 0.0025, 0.0025, 0.001;
    loc.set_pose({truth[0].x + 4.0, truth[0].y, truth[0].theta}, cov);  // 4 m off
    Rng noise(9);
    std::size_t wrong_converged = 0, longest = 0, run = 0;
    for (std::size_t k = 0; k < 60; ++k) {
      const UpdateResult r = loc.update(odom[k], world.scan(truth[k], spec, &noise), 0.1 * k);
      const bool wrong = r.converged && test::xy_error(r.estimate, truth[k]) > 1.0;
      wrong_converged += wrong ? 1 : 0;
      run = wrong ? run + 1 : 0;
      longest = std::max(longest, run);
    }
    std::printf(
        "  hypotheses %s: converged on the wrong place on %zu of 60 updates (longest %zu)\n",
        on ? "on" : "off", wrong_converged, longest);
    if (on) {
      // How soon depends on the map sweep's pace (HypothesesConfig::sweep_share): seen 3
      // updates at a share of 0.25, 4 at 0.15, the default.
      EXPECT_LE(longest, 5u);
    } else {
      EXPECT_GT(longest, 3u) << "the scenario no longer leaves the filter on a wrong place";
    }
  }
}

// A switch goes to no place that another, no farther from the prediction, fits this scan
// clearly better (maybe_switch). Seen on intel with odometry noisier than the model: during
// a turn in place three rescue candidates beat a prediction left 18 deg behind by 52-71
// nats; the one 2.4 m off, older and so allowed to switch, took the set, while the true pose
// 0.2 m off (71 nats) was one scan too young. On aces the reverse: a 30 deg glitch's true
// pose 1 m off (109 nats) must still win over an alias 2 m along the corridor (135 nats).
TEST(Hypotheses, ASwitchDoesNotGoWhereAnotherPlaceFitsThisScanBetter) {
  struct Candidate {
    Pose2 pose;   // map-local
    double last;  // this scan's evidence, tempered nats
  };
  constexpr double kMargin = HypothesesConfig{}.switch_evidence;  // 8 nats
  const Pose2 prediction{19.66, 4.62, -45.8 * kDeg};
  const std::vector<Candidate> intel{{{19.80, 4.65, -27.8 * kDeg}, 71.3},
                                     {{22.26, 4.74, -28.8 * kDeg}, 56.6},
                                     {{17.30, 4.60, -33.3 * kDeg}, 51.6}};
  const std::span<const Candidate> all(intel);
  EXPECT_FALSE(detail::outscored_on_this_scan(all, intel[0], prediction, kMargin));
  EXPECT_TRUE(detail::outscored_on_this_scan(all, intel[1], prediction, kMargin));
  EXPECT_TRUE(detail::outscored_on_this_scan(all, intel[2], prediction, kMargin));
  // The alias is farther off than the true pose: its better fit does not hold the glitch
  // correction back, and the true pose outscores the alias by nothing.
  const Pose2 glitched{6.75, 35.09, 116.8 * kDeg};
  const std::vector<Candidate> aces{{{7.80, 37.10, 86.0 * kDeg}, 135.1},
                                    {{7.75, 35.14, 86.2 * kDeg}, 109.4}};
  const std::span<const Candidate> both(aces);
  EXPECT_FALSE(detail::outscored_on_this_scan(both, aces[1], glitched, kMargin));
  EXPECT_FALSE(detail::outscored_on_this_scan(both, aces[0], glitched, kMargin));
  // Within the margin, places are about even and the older one may still switch.
  const std::vector<Candidate> even{{{1.0, 0.0, 0.0}, 60.0}, {{2.0, 0.0, 0.0}, 53.0}};
  EXPECT_FALSE(
      detail::outscored_on_this_scan(std::span<const Candidate>(even), even[1], Pose2{}, kMargin));
}

}  // namespace
}  // namespace pgmcl
