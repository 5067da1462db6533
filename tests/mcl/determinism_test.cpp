// Determinism: the serial reference and the OpenMP path give bitwise the same weights, and
// a seed fixes the whole trajectory whatever the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "closed_loop.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "pgmcl/mcl/measurement_model.hpp"
#include "synthetic_world.hpp"

namespace pgmcl {
namespace {

class SerialVsParallel : public ::testing::TestWithParam<maps::TableKind> {};

TEST_P(SerialVsParallel, SumsAreBitwiseEqual) {
  const test::World world = test::make_room(0.02);
  maps::LikelihoodFieldOptions opt;
  opt.kind = GetParam();
  sensor_model::BeamLikelihoodParams params;
  params.model_mismatch = 0.02;
  auto field = std::make_shared<const maps::LikelihoodField>(world.grid, params, opt);
  MeasurementModel model(field);
  const LaserScan scan = world.scan({5.0, 5.0, 1.0}, test::ScanSpec{});
  std::vector<std::uint32_t> valid, sel;
  valid_beam_indices(scan, params.max_range, valid);
  select_beams(valid, {BeamSelectionMode::kAll, 1, 1}, sel);
  model.prepare(scan, sel);

  // 3001 particles: not a multiple of the 256-particle block, spread over the whole map.
  Rng rng(7);
  std::vector<float> x(3001), y(3001), th(3001);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<float>(rng.uniform(-1.0, 12.0));
    y[i] = static_cast<float>(rng.uniform(-1.0, 10.0));
    th[i] = static_cast<float>(rng.uniform(-std::numbers::pi, std::numbers::pi));
  }
  std::vector<std::uint32_t> serial(x.size()), parallel(x.size(), 0xFFFFFFFFu);
  model.score_serial(x, y, th, serial);
  model.score_parallel(x, y, th, parallel, 2);
  EXPECT_EQ(serial, parallel);
  // The sums are not trivially equal (e.g. all background).
  EXPECT_NE(*std::min_element(serial.begin(), serial.end()),
            *std::max_element(serial.begin(), serial.end()));
}

INSTANTIATE_TEST_SUITE_P(AllKinds, SerialVsParallel,
                         ::testing::Values(maps::TableKind::kIsotropic,
                                           maps::TableKind::kOrientedBins,
                                           maps::TableKind::kOffsetField),
                         [](const auto& info) { return std::string(maps::to_string(info.param)); });

LocalizerConfig tracking_config(int threads) {
  LocalizerConfig cfg;
  cfg.threads = threads;
  cfg.adaptive_threads = false;  // the team on every update, whatever the machine's load
  cfg.seed = 1234;
  cfg.filter.particles = 1500;  // several blocks, not a multiple of 256
  cfg.gating.d_min = 0.05;
  return cfg;
}

bool same_bits(std::span<const float> a, std::span<const float> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// The serial reference and a team of two, both set tightly on `start`.
struct SerialAndTeam {
  Localizer serial, team;
  SerialAndTeam(const maps::OccupancyGrid& grid, const Pose2& start)
      : serial(grid, tracking_config(1)), team(grid, tracking_config(2)) {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    cov.diagonal() << 0.01, 0.01, 0.003;
    serial.set_pose(start, cov);
    team.set_pose(start, cov);
  }
  void expect_same_particles() const {
    const ParticlesView pa = serial.particles(), pb = team.particles();
    EXPECT_TRUE(same_bits(pa.x, pb.x));
    ASSERT_EQ(pa.weight.size(), pb.weight.size());
    EXPECT_EQ(0,
              std::memcmp(pa.weight.data(), pb.weight.data(), pa.weight.size() * sizeof(double)));
  }
};

// Same seed -> same trajectory and particles, bit for bit, for 1 and 2 threads.
TEST(Determinism, SameSeedSameTrajectoryForOneAndTwoThreads) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory();
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 5);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  cov.diagonal() << 0.01, 0.01, 0.01;

  // A fixed team of two, and an adaptive one that switches between two threads and one as
  // the machine's load says (ThreadPolicy): both give the serial reference's bits. The fixed
  // team proves it for every update; how often the adaptive one ran the team depends on the
  // load (beside busy cores it never does), so it is printed, not asserted.
  LocalizerConfig adaptive = tracking_config(2);
  adaptive.adaptive_threads = true;
  Localizer a(world.grid, tracking_config(1)), b(world.grid, tracking_config(2));
  Localizer c(world.grid, adaptive);
  a.set_pose(truth[0], cov);
  b.set_pose(truth[0], cov);
  c.set_pose(truth[0], cov);
  Rng noise_a(9), noise_b(9), noise_c(9);
  std::size_t resampled = 0, team = 0;
  for (std::size_t k = 0; k < 60; ++k) {
    const double t = 0.1 * static_cast<double>(k);
    const UpdateResult ra = a.update(odom[k], world.scan(truth[k], spec, &noise_a), t);
    const UpdateResult rb = b.update(odom[k], world.scan(truth[k], spec, &noise_b), t);
    const UpdateResult rc = c.update(odom[k], world.scan(truth[k], spec, &noise_c), t);
    ASSERT_EQ(rb.threads, 2);
    ASSERT_TRUE(rc.threads == 1 || rc.threads == 2);
    team += rc.threads == 2 ? 1 : 0;
    ASSERT_EQ(ra.estimate.x, rc.estimate.x) << "step " << k;
    ASSERT_EQ(ra.n_eff, rc.n_eff) << "step " << k;
    ASSERT_EQ(ra.estimate.x, rb.estimate.x) << "step " << k;
    ASSERT_EQ(ra.estimate.y, rb.estimate.y) << "step " << k;
    ASSERT_EQ(ra.estimate.theta, rb.estimate.theta) << "step " << k;
    ASSERT_EQ(ra.n_eff, rb.n_eff) << "step " << k;
    ASSERT_EQ(ra.particles, rb.particles) << "step " << k;
    resampled += ra.resampled ? 1 : 0;
  }
  const ParticlesView pa = a.particles(), pb = b.particles();
  EXPECT_TRUE(same_bits(pa.x, pb.x));
  EXPECT_TRUE(same_bits(pa.y, pb.y));
  EXPECT_TRUE(same_bits(pa.theta, pb.theta));
  ASSERT_EQ(pa.weight.size(), pb.weight.size());
  EXPECT_EQ(0, std::memcmp(pa.weight.data(), pb.weight.data(), pa.weight.size() * sizeof(double)));
  EXPECT_GT(resampled, 0u);  // the comparison covered resampling too
  EXPECT_TRUE(same_bits(pa.x, c.particles().x));
  std::printf("  adaptive: %zu of 60 updates on the team\n", team);
}

// The free-space discount works its particles out in parallel with a team (Localizer::
// discount_blocked_readings): people the map does not show gather around the robot, the
// scan stops fitting and the discount runs, and the weights stay the serial reference's bits.
TEST(Determinism, FreeSpaceDiscountSameBitsForOneAndTwoThreads) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory(0.5, 15 * std::numbers::pi / 180.0);
  const auto odom = test::noisy_odometry(truth, MotionNoise{}, 3);
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  SerialAndTeam both(world.grid, truth[0]);
  Localizer &a = both.serial, &b = both.team;
  Rng noise_a(9), noise_b(9), crowd(11);
  std::size_t discounted = 0;
  const std::size_t steps = std::min<std::size_t>(60, truth.size());
  for (std::size_t k = 0; k < steps; ++k) {
    // From step 20 on, eight 40 cm "people" stand 0.9-1.7 m around the robot.
    test::World scene = world;
    const Pose2& p = truth[k];
    if (k >= 20) test::add_crowd(scene, p, crowd);
    const double t = 0.1 * static_cast<double>(k);
    const UpdateResult ra = a.update(odom[k], scene.scan(p, spec, &noise_a), t);
    const UpdateResult rb = b.update(odom[k], scene.scan(p, spec, &noise_b), t);
    discounted += ra.timings.free_space_ms > 0.0 && rb.timings.free_space_ms > 0.0 ? 1 : 0;
    ASSERT_EQ(ra.estimate.x, rb.estimate.x) << "step " << k;
    ASSERT_EQ(ra.estimate.theta, rb.estimate.theta) << "step " << k;
    ASSERT_EQ(ra.n_eff, rb.n_eff) << "step " << k;
  }
  EXPECT_GT(discounted, 0u) << "the crowd no longer makes the discount run";
  both.expect_same_particles();
  std::printf("  the discount ran on %zu of %zu updates\n", discounted, steps);
}

// With a team the particles are scored while the hypotheses' search runs, and those a
// switch redraws are scored again (Localizer::measurement_update): an odometry glitch that
// the tracker absorbs by a switch leaves the serial reference's bits.
TEST(Determinism, SwitchSameBitsForOneAndTwoThreads) {
  const test::World world = test::make_room(0.05);
  const auto truth = test::loop_trajectory(0.5, 15 * std::numbers::pi / 180.0);
  auto odom = test::noisy_odometry(truth, MotionNoise{}, 3);
  // From step 20 on, the odometry is seen through a 1 m, 40 deg glitch.
  const std::size_t at = 20;
  const Pose2 base = odom[at - 1], glitch{1.0, 0.0, 40 * std::numbers::pi / 180.0};
  for (std::size_t k = at; k < odom.size(); ++k)
    odom[k] = base.compose(glitch).compose(base.between(odom[k]));
  test::ScanSpec spec;
  spec.noise_sigma = 0.01;
  SerialAndTeam both(world.grid, truth[0]);
  Localizer &a = both.serial, &b = both.team;
  Rng noise_a(9), noise_b(9);
  std::size_t switched = 0;
  double last_error = 0.0;
  const std::size_t steps = std::min<std::size_t>(40, truth.size());
  for (std::size_t k = 0; k < steps; ++k) {
    const double t = 0.1 * static_cast<double>(k);
    const UpdateResult ra = a.update(odom[k], world.scan(truth[k], spec, &noise_a), t);
    const UpdateResult rb = b.update(odom[k], world.scan(truth[k], spec, &noise_b), t);
    switched += ra.switched && rb.switched ? 1 : 0;
    last_error = std::hypot(ra.estimate.x - truth[k].x, ra.estimate.y - truth[k].y);
    ASSERT_EQ(ra.estimate.x, rb.estimate.x) << "step " << k;
    ASSERT_EQ(ra.estimate.theta, rb.estimate.theta) << "step " << k;
    ASSERT_EQ(ra.n_eff, rb.n_eff) << "step " << k;
  }
  EXPECT_GT(switched, 0u) << "the glitch no longer makes the tracker switch";
  EXPECT_LT(last_error, 0.2) << "the glitch was not absorbed";
  both.expect_same_particles();
  std::printf("  the tracker switched on %zu of %zu updates\n", switched, steps);
}

// A different seed gives a different particle set (the seed is really used).
TEST(Determinism, DifferentSeedDifferentParticles) {
  const test::World world = test::make_room(0.05);
  LocalizerConfig c1 = tracking_config(1), c2 = tracking_config(1);
  c2.seed = 99;
  Localizer a(world.grid, c1), b(world.grid, c2);
  EXPECT_FALSE(same_bits(a.particles().x, b.particles().x));
}

}  // namespace
}  // namespace pgmcl
