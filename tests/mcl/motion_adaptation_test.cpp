// Motion-noise adaptation (MotionAdaptationConfig, mcl/src/motion_noise_adaptation.hpp):
// the factor on the noise must follow how much noisier the odometry is than the model,
// ignore rare glitches, and, in a closed loop with odometry noisier than configured, keep
// the filter on the path where the fixed noise loses it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "closed_loop.hpp"
#include "motion_noise_adaptation.hpp"
#include "pgmcl/common/random.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/pose_estimate.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

MotionNoise scaled(const MotionNoise& n, double rotation, double translation) {
  MotionNoise s = n;
  s.a1 *= rotation;
  s.a2 *= rotation;
  s.a3 *= translation;
  s.a4 *= translation;
  return s;
}

struct Feed {
  double rotation_scale = 1.0;     // true rotation variances / the model's
  double translation_scale = 1.0;  // true translation variances / the model's
  double glitch_rate = 0.0;        // fraction of steps whose odometry turns by glitch_deg more
  double glitch_deg = 30.0;
  double estimate_var = 1e-8;  // variance of each estimate (all three axes)
  std::size_t steps = 200;
};

struct Adapted {
  detail::MotionNoiseAdaptation state;
  double mean_rotation = 0.0, mean_translation = 0.0;  // factors averaged once adapting
};

// Steps of 0.5 m and a 15 deg turn (sparse scans) whose estimates are the truth; the
// odometry draws Table 5.6 noise at the given scales of the model.
Adapted adapted(const MotionConfig& cfg, const Feed& f, std::uint64_t seed = 3) {
  Adapted out{detail::MotionNoiseAdaptation(cfg)};
  detail::MotionNoiseAdaptation& a = out.state;
  Rng rng(seed);
  const MotionNoise truth_noise = scaled(cfg.noise, f.rotation_scale, f.translation_scale);
  const Eigen::Matrix3d cov = Eigen::Matrix3d::Identity() * f.estimate_var;
  Pose2 pose{1.0, 2.0, 0.3};
  std::size_t averaged = 0;
  for (std::size_t k = 0; k < f.steps; ++k) {
    const Pose2 next = pose.compose({0.5, 0.0, (k % 2 == 0 ? 15.0 : -10.0) * kDeg});
    Pose2 odom = sample_noisy_increment(cfg.kind, truth_noise, pose, next, rng);
    if (rng.uniform() < f.glitch_rate) odom.theta = wrap_angle(odom.theta + f.glitch_deg * kDeg);
    a.observe(odom, 0.0, pose, cov, next, cov);
    pose = next;
    if (k >= cfg.adaptation.window) {
      out.mean_rotation += a.rotation_factor();
      out.mean_translation += a.translation_factor();
      ++averaged;
    }
  }
  if (averaged > 0) {
    out.mean_rotation /= static_cast<double>(averaged);
    out.mean_translation /= static_cast<double>(averaged);
  }
  return out;
}

MotionConfig margin_one() {
  MotionConfig cfg;
  cfg.adaptation.margin = 1.0;
  return cfg;
}

TEST(MotionNoiseAdaptation, FactorFollowsHowMuchNoisierTheOdometryIs) {
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Adapted a = adapted(
        margin_one(), {.rotation_scale = 5.0, .translation_scale = 2.0, .steps = 1500}, seed);
    std::printf("  seed %llu: mean factors rotation %.2f (true 5), translation %.2f (true 2)\n",
                static_cast<unsigned long long>(seed), a.mean_rotation, a.mean_translation);
    // One factor is the median of 30 draws (about 40 % spread); over a long run it is unbiased.
    EXPECT_NEAR(a.mean_rotation, 5.0, 1.0);  // 20 %
    EXPECT_NEAR(a.mean_translation, 2.0, 0.4);
    const MotionNoise n = a.state.noise();
    EXPECT_DOUBLE_EQ(n.a1, margin_one().noise.a1 * a.state.rotation_factor());
    EXPECT_DOUBLE_EQ(n.a3, margin_one().noise.a3 * a.state.translation_factor());
  }
}

TEST(MotionNoiseAdaptation, ARightModelStaysNearOneAndTheMarginScalesIt) {
  const Adapted right = adapted(margin_one(), {.steps = 400});
  EXPECT_LT(right.mean_rotation, 1.3);
  EXPECT_LT(right.mean_translation, 1.3);
  MotionConfig cfg;  // default margin 2
  const Adapted with_margin = adapted(cfg, {.rotation_scale = 5.0});
  const Adapted without = adapted(margin_one(), {.rotation_scale = 5.0});
  EXPECT_NEAR(with_margin.state.rotation_factor(), 2.0 * without.state.rotation_factor(), 1e-9);
}

TEST(MotionNoiseAdaptation, RareGlitchesDoNotCountAsNoise) {
  const Adapted clean = adapted(margin_one(), {.steps = 400});
  const Adapted glitched = adapted(margin_one(), {.glitch_rate = 0.03, .steps = 400});
  std::printf("  mean rotation factor %.2f clean, %.2f with 3 %% 30 deg glitches\n",
              clean.mean_rotation, glitched.mean_rotation);
  EXPECT_LT(glitched.mean_rotation, clean.mean_rotation + 0.2);
  // A mean would have been thrown far: (30 deg)^2 / var is ~ 10^3 per glitch.
  const Adapted every_step = adapted(margin_one(), {.glitch_rate = 1.0});
  EXPECT_EQ(every_step.state.rotation_factor(), margin_one().adaptation.max_inflation);
}

TEST(MotionNoiseAdaptation, HeadingSigmaIsTable56UnderTheAdaptedNoise) {
  const MotionConfig cfg = margin_one();
  const Pose2 delta{0.8, 0.3, 1.2};  // robot frame
  const OdometryIncrement inc = decompose_odometry(Pose2{}, delta);
  const double var = cfg.noise.a1 * (inc.rot1 * inc.rot1 + inc.rot2 * inc.rot2) +
                     2.0 * cfg.noise.a2 * inc.trans * inc.trans;
  EXPECT_NEAR(detail::MotionNoiseAdaptation(cfg).heading_sigma(delta, 0.0), std::sqrt(var), 1e-12);
  const Adapted a = adapted(cfg, {.rotation_scale = 5.0});
  ASSERT_GT(a.state.rotation_factor(), 2.0);
  EXPECT_NEAR(a.state.heading_sigma(delta, 0.0), std::sqrt(a.state.rotation_factor() * var), 1e-12);
}

TEST(SpanningReadings, AddsTheReadingsRotationMomentsToTheHeadingVariance) {
  const MotionNoise n{};
  const auto heading_var = [](const MotionNoise& a, const OdometryIncrement& inc) {
    return a.a1 * (inc.rot1 * inc.rot1 + inc.rot2 * inc.rot2) + 2.0 * a.a2 * inc.trans * inc.trans;
  };
  const auto trans_var = [](const MotionNoise& a, const OdometryIncrement& inc) {
    return a.a3 * inc.trans * inc.trans + a.a4 * (inc.rot1 * inc.rot1 + inc.rot2 * inc.rot2);
  };
  const OdometryIncrement step = decompose_odometry(Pose2{}, {0.5, 0.02, 0.05});
  const double own = rotation_moment(MotionModelKind::kDifferentialDrive, step);
  const double moment = own + 2.0;  // readings that turned back and forth
  const MotionNoise w =
      detail::spanning_readings(MotionModelKind::kDifferentialDrive, n, step, moment);
  EXPECT_NEAR(heading_var(w, step), heading_var(n, step) + n.a1 * 2.0, 1e-15);
  EXPECT_NEAR(trans_var(w, step), trans_var(n, step) + n.a4 * 2.0, 1e-15);
  // No more than the composite's own moment: nothing changes.
  const MotionNoise same =
      detail::spanning_readings(MotionModelKind::kDifferentialDrive, n, step, 0.5 * own);
  EXPECT_EQ(same.a1, n.a1);
  EXPECT_EQ(same.a2, n.a2);
  EXPECT_EQ(same.a3, n.a3);
  // A turn in place has no translation to carry it: the rotation terms scale.
  const OdometryIncrement turn = decompose_odometry(Pose2{}, {0.0, 0.0, 0.4});
  const MotionNoise t =
      detail::spanning_readings(MotionModelKind::kDifferentialDrive, n, turn, 3.0 * 0.4 * 0.4);
  EXPECT_NEAR(heading_var(t, turn), 3.0 * heading_var(n, turn), 1e-15);
}

TEST(SpanningReadings, PredictsTheHeadingSpreadOfReadingsTheGatingSkipped) {
  // Readings that jitter 2 cm sideways and back while turning a few degrees (each below the
  // gating's 0.1 m and 0.1 rad), then a straight 0.4 m: each reading's odometry draws Table
  // 5.6 noise on its own rot1 of about 90 deg, which the composite's decomposition (nearly
  // straight) does not have.
  const MotionConfig cfg = margin_one();
  const detail::MotionNoiseAdaptation a(cfg);
  const std::vector<Pose2> truth_steps{{0.0, 0.02, 0.05},  {0.0, -0.02, -0.04}, {0.0, 0.02, 0.06},
                                       {0.0, -0.02, 0.03}, {0.01, 0.0, -0.05},  {0.4, 0.0, 0.0}};
  Rng rng(11);
  double sum_on = 0.0, sum_off = 0.0;
  constexpr int kDraws = 4000;
  for (int k = 0; k < kDraws; ++k) {
    Pose2 truth{}, odom{};
    double moment = 0.0;
    for (const Pose2& s : truth_steps) {
      const Pose2 inc = sample_noisy_increment(cfg.kind, cfg.noise, truth, truth.compose(s), rng);
      moment += rotation_moment(cfg.kind, decompose_odometry(Pose2{}, inc));
      truth = truth.compose(s);
      odom = odom.compose(inc);
    }
    const double e = wrap_angle(odom.theta - truth.theta);
    sum_on += e * e / std::pow(a.heading_sigma(odom, moment), 2);
    sum_off += e * e / std::pow(a.heading_sigma(odom, 0.0), 2);
  }
  const double on = sum_on / kDraws, off = sum_off / kDraws;
  std::printf("  squared heading error / predicted variance: %.2f per reading, %.1f composite\n",
              on, off);
  // Seen: 0.76 per reading (the readings' own rot1 differ from the true ones), 40 composite.
  EXPECT_GT(on, 0.7);
  EXPECT_LT(on, 1.4);
  EXPECT_GT(off, 5.0);
}

// The particles' heading spread after one motion update that spans `readings` odometry
// readings (robot frame increments) the gating skipped but the last.
double heading_spread_after(const std::vector<Pose2>& readings, bool per_reading) {
  const test::World world = test::make_room(0.05);
  LocalizerConfig cfg;
  cfg.filter.particles = 4000;
  cfg.filter.kld.enabled = false;
  cfg.motion.per_reading_noise = per_reading;
  Localizer loc(world.grid, cfg);
  loc.set_pose({3.0, 4.5, 0.0}, Eigen::Matrix3d::Identity() * 1e-12);
  LaserScan blind = world.scan({3.0, 4.5, 0.0}, {});  // no valid reading: motion only
  std::fill(blind.ranges.begin(), blind.ranges.end(), std::numeric_limits<float>::quiet_NaN());
  Pose2 odom{};
  double t = 0.0;
  (void)loc.update(odom, blind, t);
  for (std::size_t k = 0; k < readings.size(); ++k) {
    odom = odom.compose(readings[k]);
    const UpdateResult r = loc.update(odom, blind, t += 0.25);
    EXPECT_EQ(r.skipped,
              k + 1 < readings.size() ? SkipReason::kNotMoved : SkipReason::kNoValidBeams)
        << "reading " << k;
  }
  const ParticlesView p = loc.particles();
  const std::vector<double> equal(p.size(), 1.0);
  return std::sqrt(estimate_pose(p.x, p.y, p.theta, equal, 1).covariance(2, 2));
}

TEST(SpanningReadings, TheParticlesDrawTheNoiseOfEveryReadingSinceTheLastUpdate) {
  const std::vector<Pose2> readings{{0.0, 0.02, 0.05},
                                    {0.0, -0.02, -0.04},
                                    {0.0, 0.02, 0.06},
                                    {0.0, -0.02, -0.03},
                                    {0.4, 0.0, 0.0}};
  const MotionNoise n{};
  double moment = 0.0;
  Pose2 odom{};
  for (const Pose2& d : readings) {
    moment += rotation_moment(MotionModelKind::kDifferentialDrive,
                              decompose_odometry(odom, odom.compose(d)));
    odom = odom.compose(d);
  }
  const OdometryIncrement whole = decompose_odometry(Pose2{}, odom);
  const double t2 = whole.trans * whole.trans;
  const double expected_on = std::sqrt(n.a1 * moment + 2.0 * n.a2 * t2);
  const double expected_off = std::sqrt(
      n.a1 * rotation_moment(MotionModelKind::kDifferentialDrive, whole) + 2.0 * n.a2 * t2);
  const double on = heading_spread_after(readings, true);
  const double off = heading_spread_after(readings, false);
  std::printf("  heading spread %.4f rad per reading (expected %.4f), %.4f composite (%.4f)\n", on,
              expected_on, off, expected_off);
  EXPECT_NEAR(on, expected_on, 0.1 * expected_on);
  EXPECT_NEAR(off, expected_off, 0.1 * expected_off);
  EXPECT_GT(on, 3.0 * off);
}

TEST(MotionNoiseAdaptation, UncertainEstimatesExplainTheResiduals) {
  // Estimates with 0.3 m / 0.3 rad of their own spread say nothing about 5x odometry noise.
  const Adapted a = adapted(margin_one(), {.rotation_scale = 5.0, .estimate_var = 0.09});
  EXPECT_EQ(a.state.rotation_factor(), 1.0);
}

TEST(MotionNoiseAdaptation, WaitsForAThirdOfTheWindowAndCanBeDisabled) {
  MotionConfig cfg = margin_one();
  const std::size_t third = cfg.adaptation.window / 3;
  EXPECT_EQ(adapted(cfg, {.rotation_scale = 10.0, .steps = third - 1}).state.rotation_factor(),
            1.0);
  EXPECT_GT(adapted(cfg, {.rotation_scale = 10.0, .steps = third}).state.rotation_factor(), 2.0);
  cfg.adaptation.enabled = false;
  const Adapted off = adapted(cfg, {.rotation_scale = 10.0});
  EXPECT_EQ(off.state.rotation_factor(), 1.0);
  EXPECT_EQ(off.state.noise().a1, cfg.noise.a1);
}

// The test room's loop with odometry whose rotation variances are 10x, and translation
// variances 4x, the filter's configured noise, and a thin cloud (300 particles, fixed):
// the adaptation must widen the proposal and keep the estimate on the path.
test::LoopErrors run_noisy_loop(bool adapt, std::uint64_t seed) {
  const test::World world = test::make_room(0.05);
  LocalizerConfig cfg;
  cfg.threads = 1;
  cfg.seed = seed;
  cfg.motion.adaptation.enabled = adapt;
  cfg.filter.kld.min_particles = 300;
  cfg.filter.kld.max_particles = 300;
  Localizer loc(world.grid, cfg);
  const std::vector<Pose2> truth = test::loop_trajectory(0.5, 15 * kDeg);
  std::vector<Pose2> path;
  for (int lap = 0; lap < 3; ++lap) path.insert(path.end(), truth.begin(), truth.end());
  const std::vector<Pose2> odom =
      test::noisy_odometry(path, scaled(MotionNoise{}, 10.0, 4.0), seed);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.diagonal() << 0.01, 0.01, 0.003;
  loc.set_pose(path[0], cov);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  return test::run_loop(loc, world, path, odom, spec, {.noise_seed = seed + 7, .end = path.size()});
}

TEST(MotionNoiseAdaptation, ClosedLoopWithOdometryNoisierThanTheModel) {
  for (const std::uint64_t seed : {1, 2, 3, 4}) {
    const test::LoopErrors on = run_noisy_loop(true, seed);
    const test::LoopErrors off = run_noisy_loop(false, seed);
    std::printf(
        "  seed %llu: RMSE %.3f m adapted (max %.3f m, final factor %.1f), %.3f m fixed "
        "(max %.3f m)\n",
        static_cast<unsigned long long>(seed), on.rmse_xy, on.max_xy, on.last_rotation_noise_factor,
        off.rmse_xy, off.max_xy);
    EXPECT_GE(on.last_rotation_noise_factor, 2.0);
    EXPECT_EQ(off.last_rotation_noise_factor, 1.0);
    EXPECT_LT(on.rmse_xy, 0.06);
    EXPECT_LT(on.max_xy, 0.3);
    // Seen: 0.071-0.074 m fixed, 1.6-1.9x the adapted RMSE.
    EXPECT_GT(off.rmse_xy, 1.4 * on.rmse_xy);
  }
}

}  // namespace
}  // namespace pgmcl
