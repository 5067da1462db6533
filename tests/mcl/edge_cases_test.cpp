// Edge cases at the API boundary and in the numerics.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "closed_loop.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Matrix3d small_cov() {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  c.diagonal() << 0.01, 0.01, 0.003;
  return c;
}

void expect_finite(const UpdateResult& r) {
  EXPECT_TRUE(std::isfinite(r.estimate.x) && std::isfinite(r.estimate.y) &&
              std::isfinite(r.estimate.theta));
  EXPECT_TRUE(std::isfinite(r.mean.x) && std::isfinite(r.mean.y) && std::isfinite(r.mean.theta));
  EXPECT_TRUE(r.covariance.allFinite());
  EXPECT_TRUE(r.mean_covariance.allFinite());
  EXPECT_TRUE(std::isfinite(r.n_eff));
}

TEST(EdgeCases, SingleParticle) {
  const test::World world = test::make_room(0.05);
  LocalizerConfig cfg;
  cfg.filter.particles = 1;
  cfg.filter.global_particles = 1;
  cfg.filter.kld.enabled = false;
  Localizer loc(world.grid, cfg);
  ASSERT_EQ(loc.particles().size(), 1u);
  loc.set_pose({3.0, 4.5, 0.0}, small_cov());
  const auto truth = test::loop_trajectory();
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 3);
  for (std::size_t k = 0; k < 20; ++k) {
    const UpdateResult r = loc.update(odom[k], world.scan(truth[k], {}), 0.1 * k);
    expect_finite(r);
    EXPECT_EQ(r.particles, 1u);
    if (r.measured()) {
      EXPECT_DOUBLE_EQ(r.n_eff, 1.0);
      EXPECT_DOUBLE_EQ(loc.particles().weight[0], 1.0);
    }
    EXPECT_TRUE(r.covariance.isZero(1e-12));  // one particle: zero spread, not NaN
  }
}

TEST(EdgeCases, AllBeamsInvalid) {
  const test::World world = test::make_room(0.05);
  Localizer loc(world.grid, LocalizerConfig{});
  loc.set_pose({3.0, 4.5, 0.0}, small_cov());
  const std::vector<double> before(loc.particles().weight.begin(), loc.particles().weight.end());
  LaserScan scan = world.scan({3.0, 4.5, 0.0}, {});
  for (std::size_t i = 0; i < scan.ranges.size(); ++i)
    scan.ranges[i] = (i % 3 == 0)   ? std::numeric_limits<float>::quiet_NaN()
                     : (i % 3 == 1) ? std::numeric_limits<float>::infinity()
                                    : 0.01f;  // below range_min
  const UpdateResult r = loc.update({}, scan, 0.0);
  EXPECT_EQ(r.skipped, SkipReason::kNoValidBeams);
  EXPECT_STREQ(to_string(r.skipped), "no_valid_beams");
  EXPECT_FALSE(r.measured());
  EXPECT_FALSE(r.resampled);
  EXPECT_EQ(r.beams_total, scan.ranges.size());
  EXPECT_EQ(r.beams_invalid, scan.ranges.size());
  EXPECT_EQ(r.beams_used, 0u);
  expect_finite(r);
  const ParticlesView pv = loc.particles();
  for (std::size_t i = 0; i < pv.size(); ++i) ASSERT_EQ(pv.weight[i], before[i]);
  // An empty scan is the same case, not an error.
  LaserScan empty = scan;
  empty.ranges.clear();
  loc.force_update();  // not moved: the gate would skip first
  EXPECT_EQ(loc.update({}, empty, 1.0).skipped, SkipReason::kNoValidBeams);
}

TEST(EdgeCases, WrongBeamCountIsRejectedWithAClearError) {
  const test::World world = test::make_room(0.05);
  LocalizerConfig cfg;
  cfg.likelihood.expected_beams = 1081;
  Localizer loc(world.grid, cfg);
  test::ScanSpec spec;
  spec.beams = 1080;
  const std::vector<float> x_before(loc.particles().x.begin(), loc.particles().x.end());
  try {
    (void)loc.update({}, world.scan({3.0, 4.5, 0.0}, spec), 0.0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("1080"), std::string::npos) << msg;
    EXPECT_NE(msg.find("1081"), std::string::npos) << msg;
    EXPECT_NE(msg.find("expected_beams"), std::string::npos) << msg;
  }
  // Nothing changed; the right count works.
  EXPECT_TRUE(std::equal(x_before.begin(), x_before.end(), loc.particles().x.begin()));
  spec.beams = 1081;
  EXPECT_TRUE(loc.update({}, world.scan({3.0, 4.5, 0.0}, spec), 0.0).measured());
  // Other malformed scans.
  LaserScan bad = world.scan({3.0, 4.5, 0.0}, {});
  bad.angle_increment = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(loc.update({}, bad, 1.0), std::invalid_argument);
  bad = world.scan({3.0, 4.5, 0.0}, {});
  bad.range_max = bad.range_min;
  EXPECT_THROW(loc.update({}, bad, 1.0), std::invalid_argument);
  EXPECT_THROW(loc.update({std::nan(""), 0, 0}, world.scan({3.0, 4.5, 0.0}, {}), 1.0),
               std::invalid_argument);
}

TEST(EdgeCases, TimeGoingBackwardsThrowsByDefault) {
  const test::World world = test::make_room(0.05);
  Localizer loc(world.grid, LocalizerConfig{});
  loc.set_pose({3.0, 4.5, 0.0}, small_cov());
  const LaserScan scan = world.scan({3.0, 4.5, 0.0}, {});
  ASSERT_TRUE(loc.update({}, scan, 10.0).measured());
  const std::vector<float> x_before(loc.particles().x.begin(), loc.particles().x.end());
  try {
    (void)loc.update({0.5, 0.0, 0.0}, scan, 9.5);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("earlier"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::equal(x_before.begin(), x_before.end(), loc.particles().x.begin()));
  // Equal stamps are fine (not backwards).
  EXPECT_NO_THROW((void)loc.update({}, scan, 10.0));
}

TEST(EdgeCases, TimeGoingBackwardsResetPolicyRestartsOdometry) {
  const test::World world = test::make_room(0.05);
  LocalizerConfig cfg;
  cfg.time_backwards = TimeBackwardsPolicy::kReset;
  Localizer loc(world.grid, cfg);
  const Pose2 truth{3.0, 4.5, 0.0};
  loc.set_pose(truth, small_cov());
  const LaserScan scan = world.scan(truth, {});
  ASSERT_TRUE(loc.update({5.0, 5.0, 0.0}, scan, 10.0).measured());
  const std::vector<float> x_before(loc.particles().x.begin(), loc.particles().x.end());
  UpdateResult r = loc.update({-7.0, 2.0, 1.0}, scan, 3.0);  // a log that looped around
  EXPECT_EQ(r.skipped, SkipReason::kTimeWentBackwards);
  EXPECT_STREQ(to_string(r.skipped), "time_went_backwards");
  EXPECT_TRUE(std::equal(x_before.begin(), x_before.end(), loc.particles().x.begin()));
  // The next update starts a new odometry chain: the 12 m odometry jump is not applied.
  r = loc.update({-7.0, 2.0, 1.0}, scan, 3.1);
  EXPECT_TRUE(r.measured());
  EXPECT_FALSE(r.motion_applied);
  EXPECT_LT(test::xy_error(r.estimate, truth), 0.1);
}

// Tracking across the +/-pi seam: headings near pi on both sides of the wrap.
TEST(EdgeCases, PosesNearPlusMinusPi) {
  const test::World world = test::make_room(0.05);
  // Drive west along y = 4.5 while weaving the heading across +/-pi.
  std::vector<Pose2> truth;
  for (int k = 0; k < 60; ++k)
    truth.push_back({8.5 - 0.1 * k, 4.5 + 0.05 * std::sin(0.3 * k),
                     wrap_angle(std::numbers::pi + 0.08 * std::sin(0.5 * k))});
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 8);
  Localizer loc(world.grid, LocalizerConfig{});
  loc.set_pose(truth[0], small_cov());
  const UpdateResult& first = loc.last_result();
  EXPECT_GT(std::abs(first.mean.theta), 3.0);  // circular mean, not ~0
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  const test::LoopErrors e = test::run_loop(
      loc, world, truth, odom, spec, {.noise_seed = 4, .end = truth.size(), .score_from = 3});
  RecordProperty("rmse_xy_m", std::to_string(e.rmse_xy));
  RecordProperty("max_theta_deg", std::to_string(e.max_theta / kDeg));
  // Seen: RMSE 2.1 cm, max heading error 1.8 deg.
  EXPECT_LT(e.max_theta, 3 * kDeg);
  EXPECT_LT(e.rmse_xy, 0.05);
  const ParticlesView pv = loc.particles();
  for (std::size_t i = 0; i < pv.size(); ++i) {
    ASSERT_GT(pv.theta[i], -std::numbers::pi_v<float>);
    ASSERT_LE(pv.theta[i], std::numbers::pi_v<float>);
  }
}

// A map at UTM scale must localise exactly like the same map at the origin: particles live
// in the grid frame, so the same seed gives the same filter run; only the final global
// conversion differs (double, ~1e-9 m at 5e6).
TEST(EdgeCases, UtmScaleOriginTracksLikeOriginAtZero) {
  const Pose2 utm{512345.25, 5412345.75, 0.3};
  const test::World w0 = test::make_room(0.05);
  const test::World wu = test::make_room(0.05, utm);
  const auto truth = test::loop_trajectory();
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 6);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  Localizer l0(w0.grid, LocalizerConfig{}), lu(wu.grid, LocalizerConfig{});
  l0.set_pose(truth[0], small_cov());
  lu.set_pose(utm.compose(truth[0]), small_cov());
  const auto e0 =
      test::run_loop(l0, w0, truth, odom, spec, {.noise_seed = 5, .end = 120, .score_from = 3});
  const auto eu =
      test::run_loop(lu, wu, truth, odom, spec, {.noise_seed = 5, .end = 120, .score_from = 3});
  RecordProperty("rmse_xy_zero_m", std::to_string(e0.rmse_xy));
  RecordProperty("rmse_xy_utm_m", std::to_string(eu.rmse_xy));
  RecordProperty("rmse_diff_m", std::to_string(eu.rmse_xy - e0.rmse_xy));
  // Seen: RMSE 2.2 cm in both, equal to the printed precision (1e-6 m).
  EXPECT_LT(e0.rmse_xy, 0.05);
  EXPECT_LT(eu.rmse_xy, 0.05);
  EXPECT_NEAR(eu.rmse_xy, e0.rmse_xy, 1e-3);
  EXPECT_NEAR(eu.max_theta, e0.max_theta, 1e-3);
  // The global estimate really is at UTM scale.
  EXPECT_GT(lu.last_result().estimate.y, 5.4e6);
  // Particle global poses too.
  EXPECT_GT(lu.particles().global_pose(0).x, 5.1e5);
}

}  // namespace
}  // namespace pgmcl
