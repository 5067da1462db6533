// NavLocalizer: the adapter around the filter, driven through a synthetic room without any
// middleware; frames checked against hand-computed compositions.
#include "pgmcl/nav/nav_localizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "../mcl/synthetic_world.hpp"

namespace pgmcl::nav {
namespace {

constexpr double kPi = std::numbers::pi;

NavConfig small_config() {
  NavConfig c;
  c.filter.filter.particles = 400;
  c.filter.filter.global_particles = 3000;
  c.filter.filter.kld.enabled = false;
  c.filter.seed = 3;
  return c;
}

Eigen::Matrix3d diag(double sxy, double sth) {
  return Eigen::Vector3d(sxy * sxy, sxy * sxy, sth * sth).asDiagonal();
}

/// The room, a loop through it, noisy odometry, and the scans a laser sees there.
struct Drive {
  test::World world = test::make_room(0.05);
  std::vector<Pose2> truth = test::loop_trajectory();
  std::vector<Pose2> odom = test::noisy_odometry(truth, MotionNoise{}, 7);
  test::ScanSpec spec;
  std::vector<LaserScan> scans;
  Drive() {
    spec.beams = 361;
    spec.fov = 1.5 * kPi;
    Rng rng(11);
    for (const Pose2& t : truth) scans.push_back(world.scan(t, spec, &rng));
  }
  [[nodiscard]] double stamp(std::size_t k) const { return 100.0 + 0.1 * static_cast<double>(k); }
  /// Step k as an upright laser at spec.sensor_pose reports it.
  [[nodiscard]] ScanInput upright(std::size_t k) const {
    const LaserScan& s = scans[k];
    return {{s.angle_min, s.angle_increment, s.range_min, s.range_max, s.ranges},
            to_isometry(spec.sensor_pose),
            odom[k],
            stamp(k)};
  }
};

/// An adapter started at the first true pose with `sxy` / `sth` standard deviations.
NavLocalizer started(const Drive& d, double sxy, double sth,
                     const NavConfig& cfg = small_config()) {
  NavLocalizer nav(d.world.grid, cfg);
  nav.set_initial_pose(d.truth[0], diag(sxy, sth));
  return nav;
}

Eigen::Isometry3d upside_down_mount(const Pose2& p) {
  Eigen::Isometry3d t = to_isometry(p);
  t.translation().z() = 0.4;
  t.linear() = t.linear() * Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).matrix();
  return t;
}

TEST(NavLocalizer, TracksAndPublishesAConsistentMapToOdom) {
  const Drive d;
  NavConfig cfg = small_config();
  cfg.transform_tolerance = 0.25;
  NavLocalizer nav = started(d, 0.1, 0.05, cfg);
  double worst = 0.0;
  std::size_t poses = 0;
  for (std::size_t k = 0; k < d.truth.size(); ++k) {
    const ScanOutcome o = nav.process_scan(d.upright(k));
    ASSERT_FALSE(o.rejected) << o.error;
    ASSERT_TRUE(o.transform_ready);
    const TransformOutput tf = *nav.map_to_odom();
    EXPECT_DOUBLE_EQ(tf.stamp, d.stamp(k) + 0.25);
    if (!o.pose_ready) continue;
    ++poses;
    const PoseOutput p = nav.pose();
    EXPECT_EQ(p.stamp, d.stamp(k));
    // map -> odom -> base is the published pose.
    const Pose2 chained = tf.map_T_odom.compose(d.odom[k]);
    EXPECT_NEAR(chained.x, p.pose.x, 1e-9);
    EXPECT_NEAR(chained.y, p.pose.y, 1e-9);
    EXPECT_NEAR(wrap_angle(chained.theta - p.pose.theta), 0.0, 1e-9);
    EXPECT_EQ(p.ros_covariance[35], p.covariance(2, 2));
    if (k > 20)
      worst = std::max(worst, std::hypot(p.pose.x - d.truth[k].x, p.pose.y - d.truth[k].y));
  }
  EXPECT_GT(poses, d.truth.size() / 3);
  EXPECT_LT(worst, 0.15);
  const Diagnostics& g = nav.diagnostics();
  EXPECT_EQ(g.scans, d.truth.size());
  EXPECT_EQ(g.filtered, d.truth.size());
  EXPECT_EQ(g.measured, poses);
  EXPECT_EQ(g.measured + g.not_moved + g.no_valid_beams, g.filtered);
  EXPECT_EQ(g.beams_total, 361u);
  EXPECT_GT(g.beams_used, 0u);
  EXPECT_EQ(g.particles, 400u);
}

// The same physical beams from a laser mounted upside down, which reports them in the
// opposite angular order, reach the engine as the same scan: identical results.
TEST(NavLocalizer, UpsideDownLaserGivesTheSameResultsAsUpright) {
  const Drive d;
  NavLocalizer upright = started(d, 0.1, 0.05), flipped = started(d, 0.1, 0.05);
  for (std::size_t k = 0; k < 80; ++k) {
    const ScanOutcome a = upright.process_scan(d.upright(k));
    ScanInput in = d.upright(k);
    in.scan.angle_min = -in.scan.angle_min;  // in the rolled laser frame, a -> -a
    in.scan.angle_increment = -in.scan.angle_increment;
    in.base_T_laser = upside_down_mount(d.spec.sensor_pose);
    const ScanOutcome b = flipped.process_scan(in);
    ASSERT_FALSE(b.rejected) << b.error;
    ASSERT_EQ(a.pose_ready, b.pose_ready);
    EXPECT_EQ(a.result.estimate.x, b.result.estimate.x);
    EXPECT_EQ(a.result.estimate.y, b.result.estimate.y);
    EXPECT_EQ(a.result.estimate.theta, b.result.estimate.theta);
  }
}

TEST(NavLocalizer, ReversedScanOrderTracksTheSame) {
  const Drive d;
  NavLocalizer forward = started(d, 0.05, 0.03), reversed = started(d, 0.05, 0.03);
  for (std::size_t k = 0; k < 60; ++k) {
    (void)forward.process_scan(d.upright(k));
    ScanInput in = d.upright(k);
    const LaserScan& s = d.scans[k];
    std::vector<float> back(s.ranges.rbegin(), s.ranges.rend());
    in.scan.angle_min = s.angle_min + static_cast<double>(s.size() - 1) * s.angle_increment;
    in.scan.angle_increment = -s.angle_increment;
    in.scan.ranges = back;
    const ScanOutcome o = reversed.process_scan(in);
    ASSERT_FALSE(o.rejected) << o.error;
  }
  const Pose2 a = forward.pose().pose, b = reversed.pose().pose, t = d.truth[59];
  EXPECT_LT(std::hypot(b.x - t.x, b.y - t.y), 0.1);
  EXPECT_LT(std::hypot(a.x - b.x, a.y - b.y), 0.05);
}

TEST(NavLocalizer, InitialPoseIsMovedByTheOdometrySinceItsStamp) {
  const Drive d;
  NavConfig cfg = small_config();
  cfg.filter.gating.enabled = false;  // every scan updates: the reference is the last scan
  NavLocalizer nav = started(d, 0.05, 0.02, cfg);
  for (std::size_t k = 0; k <= 30; ++k) (void)nav.process_scan(d.upright(k));
  // A pose given for step 20's stamp, with the odometry at that stamp: the filter's pose
  // now (step 30) is (pose ∘ odom_20^-1) ∘ odom_30.
  const Pose2 given{d.truth[20].x + 0.3, d.truth[20].y - 0.2, d.truth[20].theta + 0.1};
  nav.set_initial_pose(given, diag(1e-4, 1e-4), d.odom[20]);
  const Pose2 expected = given.compose(d.odom[20].inverse()).compose(d.odom[30]);
  const Pose2 got = nav.localizer().last_result().mean;
  EXPECT_NEAR(got.x, expected.x, 0.005);
  EXPECT_NEAR(got.y, expected.y, 0.005);
  EXPECT_NEAR(wrap_angle(got.theta - expected.theta), 0.0, 0.005);
  const Pose2 c = nav.map_to_odom()->map_T_odom.compose(d.odom[20]);
  EXPECT_NEAR(c.x, given.x, 1e-9);
  EXPECT_NEAR(c.y, given.y, 1e-9);
  // Without the odometry at its stamp, the pose is the robot's at the last scan.
  nav.set_initial_pose(given, diag(1e-4, 1e-4));
  const Pose2 now = nav.localizer().last_result().mean;
  EXPECT_NEAR(now.x, given.x, 0.005);
  EXPECT_NEAR(now.y, given.y, 0.005);
}

TEST(NavLocalizer, InitialPoseBeforeTheFirstScanIsAppliedAtItsOdometry) {
  const Drive d;
  NavLocalizer nav(d.world.grid, small_config());
  // Given at step 0 with its odometry; the first scan arrives at step 10.
  nav.set_initial_pose(d.truth[0], diag(1e-3, 1e-3), d.odom[0]);
  const ScanOutcome o = nav.process_scan(d.upright(10));
  ASSERT_TRUE(o.pose_ready);
  const Pose2 expected = d.truth[0].compose(d.odom[0].inverse()).compose(d.odom[10]);
  EXPECT_NEAR(o.result.estimate.x, expected.x, 0.02);
  EXPECT_NEAR(o.result.estimate.y, expected.y, 0.02);
}

TEST(NavLocalizer, NoMotionUpdateOnRequest) {
  const Drive d;
  NavLocalizer nav = started(d, 0.05, 0.02);
  ScanInput in = d.upright(0);
  EXPECT_TRUE(nav.process_scan(in).pose_ready);  // the first scan always updates
  in.stamp += 1.0;
  const ScanOutcome still = nav.process_scan(in);  // same odometry: gated
  EXPECT_TRUE(still.filtered);
  EXPECT_FALSE(still.pose_ready);
  EXPECT_EQ(still.result.skipped, SkipReason::kNotMoved);
  nav.request_nomotion_update();
  in.stamp += 1.0;
  EXPECT_TRUE(nav.process_scan(in).pose_ready);
  in.stamp += 1.0;
  EXPECT_FALSE(nav.process_scan(in).pose_ready);
  EXPECT_EQ(nav.diagnostics().not_moved, 2u);
  EXPECT_EQ(nav.diagnostics().measured, 2u);
}

TEST(NavLocalizer, EveryNthScanAndForcedUpdatesBypassTheStride) {
  const Drive d;
  NavConfig cfg = small_config();
  cfg.scan_stride = 3;
  cfg.filter.gating.enabled = false;
  NavLocalizer nav = started(d, 0.05, 0.02, cfg);
  std::vector<bool> filtered;
  for (std::size_t k = 0; k < 9; ++k) filtered.push_back(nav.process_scan(d.upright(k)).filtered);
  EXPECT_EQ(filtered,
            (std::vector<bool>{true, false, false, true, false, false, true, false, false}));
  nav.request_nomotion_update();
  EXPECT_TRUE(nav.process_scan(d.upright(9)).filtered);  // forced, out of turn
  EXPECT_FALSE(nav.process_scan(d.upright(10)).filtered);
  EXPECT_EQ(nav.diagnostics().stride_skipped, 7u);
  EXPECT_EQ(nav.diagnostics().filtered, 4u);
  // A skipped scan still refreshes the transform's stamp.
  EXPECT_DOUBLE_EQ(nav.map_to_odom()->stamp, d.stamp(10) + cfg.transform_tolerance);
}

TEST(NavLocalizer, GlobalLocalisationOnRequestSpreadsTheParticles) {
  const Drive d;
  NavLocalizer nav = started(d, 0.05, 0.02);
  (void)nav.process_scan(d.upright(0));
  nav.global_localize();
  std::vector<WeightedPose> cloud;
  nav.particles(cloud);
  ASSERT_EQ(cloud.size(), 3000u);
  double sx = 0, sxx = 0, w = 0;
  for (const WeightedPose& p : cloud) {
    sx += p.pose.x;
    sxx += p.pose.x * p.pose.x;
    w += p.weight;
  }
  const double mean = sx / 3000.0, sd = std::sqrt(sxx / 3000.0 - mean * mean);
  EXPECT_GT(sd, 2.0);  // spread over the 10 m room
  EXPECT_NEAR(w, 1.0, 1e-9);
  EXPECT_TRUE(nav.process_scan(d.upright(1)).pose_ready);  // and the next scan updates
}

TEST(NavLocalizer, BadScansAreCountedNotThrown) {
  const Drive d;
  NavLocalizer nav(d.world.grid, small_config());
  ScanInput in = d.upright(0);
  in.base_T_laser.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()).matrix();
  ScanOutcome o = nav.process_scan(in);
  EXPECT_TRUE(o.rejected);
  EXPECT_FALSE(o.filtered);
  EXPECT_NE(o.error.find("tilted"), std::string::npos) << o.error;
  in = d.upright(0);
  in.scan.angle_increment = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(nav.process_scan(in).rejected);
  EXPECT_TRUE(nav.process_scan(d.upright(5)).filtered);
  in = d.upright(4);  // earlier stamp: the filter's kThrow policy refuses it
  o = nav.process_scan(in);
  EXPECT_TRUE(o.rejected);
  EXPECT_NE(o.error.find("earlier"), std::string::npos) << o.error;
  EXPECT_EQ(nav.diagnostics().rejected, 3u);
  EXPECT_EQ(nav.diagnostics().last_error, o.error);
  EXPECT_EQ(nav.diagnostics().scans, 4u);
}

TEST(NavLocalizer, NewMapInTheSameFrameKeepsTheParticles) {
  const Drive d;
  NavLocalizer nav = started(d, 0.1, 0.05);
  for (std::size_t k = 0; k < 20; ++k) (void)nav.process_scan(d.upright(k));
  std::vector<WeightedPose> before, after;
  nav.particles(before);
  // The same room on a larger grid (20 cells more on the left, 10 below), so its origin is
  // elsewhere in the same map frame.
  const maps::OccupancyGrid& g = d.world.grid;
  maps::OccupancyGrid bigger(g.width() + 20, g.height() + 10, g.resolution(), {-1.0, -0.5, 0.0});
  for (int r = 0; r < g.height(); ++r)
    for (int c = 0; c < g.width(); ++c) bigger.set(c + 20, r + 10, g.at(c, r));
  const MapChange change = nav.replace_map(bigger, true);
  EXPECT_TRUE(change.kept_particles);
  nav.particles(after);
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    ASSERT_NEAR(after[i].pose.x, before[i].pose.x, 1e-5);
    ASSERT_NEAR(after[i].pose.y, before[i].pose.y, 1e-5);
    ASSERT_NEAR(wrap_angle(after[i].pose.theta - before[i].pose.theta), 0.0, 1e-6);
    ASSERT_EQ(after[i].weight, before[i].weight);
  }
  EXPECT_EQ(nav.localizer().origin().x, -1.0);
  // The next scans are measured against the new map and the filter keeps tracking.
  for (std::size_t k = 20; k < 40; ++k) (void)nav.process_scan(d.upright(k));
  const Pose2 p = nav.pose().pose;
  EXPECT_LT(std::hypot(p.x - d.truth[39].x, p.y - d.truth[39].y), 0.1);
  // Another frame: the particles mean nothing there, global localisation.
  nav.replace_map(bigger, false);
  nav.particles(after);
  EXPECT_EQ(after.size(), 3000u);
  EXPECT_FALSE(nav.map_to_odom().has_value());
  maps::OccupancyGrid walls(20, 20, 0.05, {}, maps::kOccupied);
  EXPECT_THROW(nav.replace_map(walls, true), std::invalid_argument);
  EXPECT_EQ(nav.localizer().origin().x, -1.0);  // unchanged by the refused map
}

TEST(NavLocalizer, StoresTheLastPoseAtTheConfiguredPeriod) {
  const Drive d;
  NavConfig cfg = small_config();
  cfg.save_pose_period = 2.0;
  NavLocalizer nav = started(d, 0.1, 0.05, cfg);
  EXPECT_FALSE(nav.pose_to_store(0.0));  // nothing measured yet
  (void)nav.process_scan(d.upright(0));
  const auto first = nav.pose_to_store(10.0);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->pose.x, nav.pose().pose.x);
  EXPECT_EQ(first->cov_yy, nav.pose().covariance(1, 1));
  EXPECT_FALSE(nav.pose_to_store(11.0));
  EXPECT_TRUE(nav.pose_to_store(12.0));
  EXPECT_TRUE(nav.pose_to_store(5.0));  // the clock went back (a replayed bag): store
}

TEST(NavLocalizer, ConfigIsValidated) {
  const Drive d;
  NavConfig cfg = small_config();
  cfg.scan_stride = 0;
  EXPECT_THROW(NavLocalizer(d.world.grid, cfg), std::invalid_argument);
  cfg = small_config();
  cfg.transform_tolerance = -1.0;
  EXPECT_THROW(NavLocalizer(d.world.grid, cfg), std::invalid_argument);
  cfg = small_config();
  cfg.ranges = {5.0, 2.0};
  EXPECT_THROW(NavLocalizer(d.world.grid, cfg), std::invalid_argument);
  cfg = small_config();
  cfg.filter.filter.kld.epsilon = -1.0;
  EXPECT_THROW(NavLocalizer(d.world.grid, cfg), InvalidConfigField);
}

}  // namespace
}  // namespace pgmcl::nav
