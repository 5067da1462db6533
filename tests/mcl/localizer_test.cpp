// Localizer: closed-loop tracking, KLD, gating, selective resampling, set_pose, config.
#include "pgmcl/mcl/localizer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "closed_loop.hpp"
#include "pgmcl/mcl/beam_selection.hpp"
#include "pgmcl/mcl/clustering.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Matrix3d diag_cov(double sxy, double sth) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  c.diagonal() << sxy * sxy, sxy * sxy, sth * sth;
  return c;
}

bool is_psd_symmetric(const Eigen::Matrix3d& c) {
  if (!c.allFinite() || (c - c.transpose()).cwiseAbs().maxCoeff() > 1e-12) return false;
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues().minCoeff() >= -1e-12;
}

struct Scenario {
  test::World world = test::make_room(0.05);
  std::vector<Pose2> truth = test::loop_trajectory();
  std::vector<Pose2> odom = test::noisy_odometry(truth, MotionNoise{}, 11);
  test::ScanSpec spec = [] {
    test::ScanSpec s;
    s.noise_sigma = 0.01;
    return s;
  }();
};

TEST(Localizer, TracksTheLoopWithinBounds) {
  Scenario sc;
  LocalizerConfig cfg;
  Localizer loc(sc.world.grid, cfg);
  loc.set_pose(sc.truth[0], diag_cov(0.1, 5 * kDeg));
  const test::LoopErrors e =
      test::run_loop(loc, sc.world, sc.truth, sc.odom, sc.spec,
                     {.noise_seed = 21, .end = sc.truth.size(), .score_from = 5});
  RecordProperty("rmse_xy_m", std::to_string(e.rmse_xy));
  RecordProperty("max_xy_m", std::to_string(e.max_xy));
  RecordProperty("max_theta_deg", std::to_string(e.max_theta / kDeg));
  RecordProperty("last_particles", std::to_string(e.last_particles));
  // Seen: RMSE 2.1 cm, max 4.5 cm, max heading error 0.8 deg over the 183-step loop
  // (the tables are piecewise constant per 5 cm cell: ~cell / sqrt(12) = 1.4 cm alone).
  EXPECT_LT(e.rmse_xy, 0.05);
  EXPECT_LT(e.max_xy, 0.15);
  EXPECT_LT(e.max_theta, 3 * kDeg);
  EXPECT_NE(e.first_converged, static_cast<std::size_t>(-1));
  const UpdateResult& r = loc.last_result();
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(is_psd_symmetric(r.covariance));
  EXPECT_TRUE(is_psd_symmetric(r.mean_covariance));
  // KLD: fewer particles once converged than the 2000 set_pose started with.
  EXPECT_LT(e.last_particles, cfg.filter.particles);
  EXPECT_GE(e.min_particles, cfg.filter.kld.min_particles);
}

TEST(Localizer, FixedParticleCountWithoutKld) {
  Scenario sc;
  LocalizerConfig cfg;
  cfg.filter.kld.enabled = false;
  cfg.filter.particles = 700;
  Localizer loc(sc.world.grid, cfg);
  loc.set_pose(sc.truth[0], diag_cov(0.1, 5 * kDeg));
  const test::LoopErrors e = test::run_loop(loc, sc.world, sc.truth, sc.odom, sc.spec,
                                            {.noise_seed = 21, .end = 80, .score_from = 5});
  EXPECT_EQ(e.min_particles, 700u);
  EXPECT_EQ(e.last_particles, 700u);
  EXPECT_LT(e.rmse_xy, 0.05);
}

TEST(Localizer, GatingSkipsUntilMovedOrForced) {
  Scenario sc;
  LocalizerConfig cfg;
  cfg.gating.d_min = 0.2;
  cfg.gating.theta_min = 0.2;
  Localizer loc(sc.world.grid, cfg);
  loc.set_pose(sc.truth[0], diag_cov(0.05, 2 * kDeg));
  const LaserScan scan = sc.world.scan(sc.truth[0], sc.spec);
  const Pose2 odom0{1.0, 2.0, 0.5};
  UpdateResult r = loc.update(odom0, scan, 0.0);
  EXPECT_EQ(r.skipped, SkipReason::kNone);  // the first update always measures
  EXPECT_TRUE(r.measured());
  const Pose2 est0 = r.estimate;
  // 10 cm forward in the odometry frame: below d_min -> skipped, dead-reckoned estimate.
  const Pose2 odom1 = odom0.compose({0.1, 0.0, 0.0});
  r = loc.update(odom1, scan, 0.1);
  EXPECT_EQ(r.skipped, SkipReason::kNotMoved);
  EXPECT_FALSE(r.measured());
  EXPECT_FALSE(r.motion_applied);
  const Pose2 expect = est0.compose({0.1, 0.0, 0.0});
  EXPECT_NEAR(r.estimate.x, expect.x, 1e-12);
  EXPECT_NEAR(r.estimate.y, expect.y, 1e-12);
  EXPECT_NEAR(r.estimate.theta, expect.theta, 1e-12);
  // force_update() overrides the gate once.
  loc.force_update();
  r = loc.update(odom1, scan, 0.2);
  EXPECT_EQ(r.skipped, SkipReason::kNone);
  EXPECT_TRUE(r.measured() && r.motion_applied);
  r = loc.update(odom1, scan, 0.3);
  EXPECT_EQ(r.skipped, SkipReason::kNotMoved);
  // Rotation beyond theta_min passes the gate.
  r = loc.update(odom1.compose({0.0, 0.0, 0.25}), scan, 0.4);
  EXPECT_EQ(r.skipped, SkipReason::kNone);
  // With gating disabled every update measures.
  cfg.gating.enabled = false;
  Localizer ungated(sc.world.grid, cfg);
  ungated.update(odom0, scan, 0.0);
  EXPECT_TRUE(ungated.update(odom0, scan, 0.1).measured());
}

TEST(Localizer, SelectiveResamplingFollowsTheThreshold) {
  Scenario sc;
  LocalizerConfig cfg;
  cfg.filter.recovery.enabled = false;  // no injection-driven resampling
  cfg.filter.resample_threshold = 0.0;  // never
  Localizer never(sc.world.grid, cfg);
  never.set_pose(sc.truth[0], diag_cov(0.1, 5 * kDeg));
  cfg.filter.resample_threshold = 1.0;  // every update (N_eff < N unless weights are equal)
  Localizer always(sc.world.grid, cfg);
  always.set_pose(sc.truth[0], diag_cov(0.1, 5 * kDeg));
  for (std::size_t k = 0; k < 10; ++k) {
    const LaserScan scan = sc.world.scan(sc.truth[k], sc.spec);
    const double t = static_cast<double>(k);
    EXPECT_FALSE(never.update(sc.odom[k], scan, t).resampled);
    const UpdateResult r = always.update(sc.odom[k], scan, t);
    EXPECT_EQ(r.resampled, r.measured());
    EXPECT_LT(r.n_eff, static_cast<double>(r.particles) + 1e-9);
  }
}

// set_pose samples the requested Gaussian: mean and covariance in the global frame, also
// with a rotated map origin (the covariance is rotated into the grid frame and back).
TEST(Localizer, SetPoseSamplesTheRequestedGaussian) {
  const test::World world = test::make_room(0.05, Pose2{100.0, -50.0, 0.6});
  LocalizerConfig cfg;
  cfg.filter.particles = 20000;
  Localizer loc(world.grid, cfg);
  Eigen::Matrix3d cov;
  cov << 0.04, 0.015, 0.0, 0.015, 0.01, 0.002, 0.0, 0.002, 0.02;
  const Pose2 mean{104.0, -45.0, 3.1};  // heading near pi: samples wrap around
  loc.set_pose(mean, cov);
  const ParticlesView pv = loc.particles();
  ASSERT_EQ(pv.size(), 20000u);
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> d(pv.size());
  for (std::size_t i = 0; i < pv.size(); ++i) {
    const Pose2 g = pv.global_pose(i);
    ASSERT_GT(g.theta, -std::numbers::pi);
    ASSERT_LE(g.theta, std::numbers::pi);
    d[i] = Eigen::Vector3d(g.x - mean.x, g.y - mean.y, wrap_angle(g.theta - mean.theta));
    m += d[i];
  }
  m /= static_cast<double>(pv.size());
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (const auto& v : d) c += (v - m) * (v - m).transpose();
  c /= static_cast<double>(pv.size() - 1);
  // 20000 samples: standard errors ~1 % of each sigma.
  EXPECT_LT(m.cwiseAbs().maxCoeff(), 0.005);
  EXPECT_LT((c - cov).cwiseAbs().maxCoeff(), 0.0015);
  // The localizer's own estimate agrees.
  const UpdateResult& r = loc.last_result();
  EXPECT_NEAR(r.mean.x, mean.x, 0.01);
  EXPECT_NEAR(r.mean.y, mean.y, 0.01);
  EXPECT_NEAR(wrap_angle(r.mean.theta - mean.theta), 0.0, 0.01);
  EXPECT_LT((r.mean_covariance - cov).cwiseAbs().maxCoeff(), 0.002);
}

TEST(Localizer, SetPoseRejectsBadCovariance) {
  const test::World world = test::make_room(0.1);
  Localizer loc(world.grid, LocalizerConfig{});
  Eigen::Matrix3d asym = diag_cov(0.1, 0.1);
  asym(0, 1) = 0.001;
  EXPECT_THROW(loc.set_pose({2, 2, 0}, asym), std::invalid_argument);
  Eigen::Matrix3d neg = diag_cov(0.1, 0.1);
  neg(2, 2) = -0.01;
  EXPECT_THROW(loc.set_pose({2, 2, 0}, neg), std::invalid_argument);
  EXPECT_THROW(loc.set_pose({std::nan(""), 2, 0}, diag_cov(0.1, 0.1)), std::invalid_argument);
  // A singular (heading-only) covariance is fine.
  Eigen::Matrix3d heading_only = Eigen::Matrix3d::Zero();
  heading_only(2, 2) = 0.1;
  EXPECT_NO_THROW(loc.set_pose({2, 2, 0}, heading_only));
  EXPECT_FLOAT_EQ(loc.particles().x[0], loc.particles().x[1]);
}

// Beam bookkeeping: selection budget, invalid readings, and endpoints on background.
TEST(Localizer, CountsSelectedInvalidAndBackgroundBeams) {
  Scenario sc;
  LocalizerConfig cfg;  // default selection: at most 120 evenly spread valid beams
  Localizer loc(sc.world.grid, cfg);
  const Pose2 truth{3.0, 4.5, 0.3};
  loc.set_pose(truth, diag_cov(0.02, 1 * kDeg));
  LaserScan scan = sc.world.scan(truth, {});
  UpdateResult r = loc.update({}, scan, 0.0);
  EXPECT_EQ(r.beams_total, 1081u);
  EXPECT_EQ(r.beams_invalid, 0u);
  EXPECT_EQ(r.beams_used, 120u);
  EXPECT_EQ(r.beams_background, 0u);  // every endpoint lies on a mapped wall
  // 300 readings that end 15 m away, beyond the 11 m x 9 m map, and 100 NaN readings.
  for (std::size_t i = 0; i < 300; ++i) scan.ranges[i] = 15.0f;
  for (std::size_t i = 300; i < 400; ++i) scan.ranges[i] = std::nanf("");
  std::vector<std::uint32_t> valid, sel;
  valid_beam_indices(scan, cfg.likelihood.beam.max_range, valid);
  select_beams(valid, cfg.likelihood.selection, sel);
  const auto far = static_cast<std::size_t>(
      std::count_if(sel.begin(), sel.end(), [](std::uint32_t i) { return i < 300; }));
  ASSERT_GT(far, 10u);
  loc.force_update();
  r = loc.update({}, scan, 1.0);
  EXPECT_EQ(r.beams_invalid, 100u);
  EXPECT_EQ(r.beams_used, 120u);
  EXPECT_EQ(r.beams_background, far);
  EXPECT_LT(test::xy_error(r.estimate, truth), 0.05);
  // A fixed stride over the valid readings.
  cfg.likelihood.selection = {BeamSelectionMode::kStride, 10, 0};
  Localizer strided(sc.world.grid, cfg);
  EXPECT_EQ(strided.update({}, sc.world.scan(truth, {}), 0.0).beams_used, 109u);  // ceil(1081/10)
}

// Several localizers can share one table; the free-cell list is checked.
TEST(Localizer, SharedFieldConstructorAndGlobalLocalize) {
  Scenario sc;
  LocalizerConfig cfg;
  cfg.filter.global_particles = 5000;
  auto field = std::make_shared<const maps::LikelihoodField>(sc.world.grid, cfg.likelihood.beam,
                                                             cfg.likelihood.table);
  const std::vector<std::uint32_t> free = free_cell_indices(sc.world.grid);
  Localizer a(field, free, cfg), b(field, free, cfg);
  EXPECT_EQ(&a.field(), &b.field());
  EXPECT_THROW(Localizer(field, {}, cfg), std::invalid_argument);
  EXPECT_THROW(Localizer(field, {static_cast<std::uint32_t>(sc.world.grid.size())}, cfg),
               std::invalid_argument);
  EXPECT_THROW(Localizer(nullptr, free, cfg), std::invalid_argument);
  // global_localize(): global_particles poses, every one in a free cell, headings spread.
  a.set_pose({3.0, 4.5, 0.0}, diag_cov(0.02, 1 * kDeg));
  a.global_localize();
  const ParticlesView pv = a.particles();
  ASSERT_EQ(pv.size(), 5000u);
  double sum_cos = 0.0, sum_sin = 0.0;
  for (std::size_t i = 0; i < pv.size(); ++i) {
    const int col = static_cast<int>(pv.x[i] / sc.world.grid.resolution());
    const int row = static_cast<int>(pv.y[i] / sc.world.grid.resolution());
    ASSERT_TRUE(sc.world.grid.in_bounds(col, row));
    ASSERT_TRUE(sc.world.grid.free(col, row)) << col << ", " << row;
    sum_cos += std::cos(pv.theta[i]);
    sum_sin += std::sin(pv.theta[i]);
  }
  EXPECT_LT(std::hypot(sum_cos, sum_sin) / 5000.0, 0.05);  // uniform headings: R ~ 0.013
  EXPECT_FALSE(a.last_result().converged);
}

// Re-initialising right after an update that the tempering limit held back (a wide start):
// the new set's estimate is its own heaviest cluster's mean at uniform weights, with nothing
// of the previous scan's likelihoods (which belong to other particles, maybe fewer).
TEST(Localizer, ReinitialisingAfterATemperedUpdateForgetsTheScan) {
  Scenario sc;
  LocalizerConfig cfg;
  cfg.threads = 1;
  cfg.filter.global_particles = 5000;
  Localizer loc(sc.world.grid, cfg);
  loc.set_pose(sc.truth[0], diag_cov(2.0, 1.0));  // far from compact: the limit holds
  Rng noise(3);
  const UpdateResult r = loc.update(sc.odom[0], sc.world.scan(sc.truth[0], sc.spec, &noise), 0.0);
  ASSERT_LT(r.tempering, 1.0 / 6.0) << "the scenario no longer limits the tempering";
  for (const bool global : {true, false}) {
    if (global)
      loc.global_localize();  // more particles than the scan was scored on
    else
      loc.set_pose({3.0, 4.5, 0.0}, diag_cov(0.5, 0.3));
    const ParticlesView pv = loc.particles();
    const std::vector<double> uniform(pv.size(), 1.0);
    const Cluster best = cluster_particles(pv.x, pv.y, pv.theta, uniform).front();
    const Pose2 expected = pv.origin.compose(best.mean);
    const Pose2 got = loc.last_result().estimate;
    EXPECT_NEAR(got.x, expected.x, 1e-9) << (global ? "global_localize" : "set_pose");
    EXPECT_NEAR(got.y, expected.y, 1e-9);
    EXPECT_NEAR(wrap_angle(got.theta - expected.theta), 0.0, 1e-9);
  }
}

void expect_invalid(const LocalizerConfig& cfg, const std::string& field) {
  try {
    cfg.validate();
    ADD_FAILURE() << "no exception for " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(LocalizerConfig, ValidateNamesTheField) {
  EXPECT_NO_THROW(LocalizerConfig{}.validate());
  LocalizerConfig c;
  c.motion.noise.a3 = -1.0;
  expect_invalid(c, "motion.noise.a3");
  c = {};
  c.filter.kld.max_particles = 10;
  expect_invalid(c, "filter.kld.max_particles");
  c = {};
  c.filter.kld.delta = 1.0;
  expect_invalid(c, "filter.kld.delta");
  c = {};
  c.filter.recovery.alpha_fast = 0.0005;
  expect_invalid(c, "filter.recovery.alpha_fast");
  c = {};
  c = {};
  c.filter.recovery.probation = 256;  // stored per particle in 8 bits
  expect_invalid(c, "filter.recovery.probation");
  c = {};
  c.filter.recovery.probation_weight = 1.0;
  expect_invalid(c, "filter.recovery.probation_weight");
  c = {};
  c.filter.resample_threshold = 1.5;
  expect_invalid(c, "filter.resample_threshold");
  c = {};
  c.likelihood.effective_beams = 0.0;
  c.likelihood.tempering = 0.0;
  expect_invalid(c, "likelihood.tempering");
  c = {};
  c.likelihood.beam.sigma_along = 0.0;
  expect_invalid(c, "likelihood.beam.sigma_along");
  c = {};
  c.gating.d_min = std::nan("");
  expect_invalid(c, "gating.d_min");
  c = {};
  c.estimate.converged_weight = 0.0;
  expect_invalid(c, "estimate.converged_weight");
  c = {};
  c.threads = -2;
  expect_invalid(c, "threads");
  // The constructor validates too.
  const test::World world = test::make_room(0.1);
  c = {};
  c.filter.particles = 0;
  EXPECT_THROW(Localizer(world.grid, c), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl
