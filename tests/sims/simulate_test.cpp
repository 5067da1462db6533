#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "pgmcl/sims/scenario.hpp"
#include "scenes.hpp"

namespace pgmcl::sims {
namespace {

constexpr double kPi = std::numbers::pi;

Scenario small_scenario() {
  Scenario sc;
  sc.start = {1.0, 1.0, 0.2};
  sc.waypoints.waypoints = {{3.5, 1.2}, {3.5, 3.0}};
  sc.duration = 2.0;
  sc.scan_rate = 10.0;
  sc.seed = 5;
  return sc;
}

TEST(Simulate, RecordsAreTimeOrderedWithTheSensorGeometry) {
  const auto grid = test::square_room(100, 80, 0.05, {-0.5, -0.5, 0.1});
  Scenario sc = small_scenario();
  sc.sensor_mount = {0.15, 0.0, 0.0};
  const auto log = simulate(sc, grid);
  ASSERT_EQ(log.records.size(), 21u);  // t = 0, 0.1, ..., 2.0
  for (std::size_t i = 0; i < log.records.size(); ++i) {
    const auto& r = log.records[i];
    EXPECT_NEAR(r.stamp, 0.1 * static_cast<double>(i), 1e-12);
    EXPECT_EQ(r.stamp, r.stamp);
    EXPECT_EQ(r.scan.size(), 1081u);
    EXPECT_EQ(r.scan.sensor_pose.x, 0.15);
    for (const float x : r.scan.ranges) {
      EXPECT_GE(x, 0.0F);
      EXPECT_LE(x, 30.0F);
    }
  }
}

TEST(Simulate, NoiseFreeScansEqualTheRayCasterFromTheTruePose) {
  const auto grid = test::square_room(100, 80, 0.05, {-0.5, -0.5, 0.1});
  Scenario sc = small_scenario();
  sc.noise = BeamNoise::none();
  sc.sensor_mount = {0.15, 0.05, 0.3};
  const auto log = simulate(sc, grid);
  const RayCaster rc(grid);
  std::vector<float> expect(1081);
  for (const auto& r : log.records) {
    rc.cast_scan(r.truth.compose(sc.sensor_mount), sc.sensor.fan(), expect);
    for (std::size_t i = 0; i < expect.size(); ++i) {
      ASSERT_NEAR(r.scan.ranges[i], expect[i], 1e-4) << "t=" << r.stamp << " beam " << i;
    }
  }
}

TEST(Simulate, DeterministicForASeedAndAnyThreadCount) {
  const auto grid = test::square_room(100, 80, 0.05);
  Scenario sc = small_scenario();
  sc.noise.dropouts.enabled = true;
  sc.noise.short_returns.enabled = true;
  sc.discs.push_back({0.3, {{{2.0, 2.0}, {3.0, 2.5}}, 0.4, 0.0}, "fabric"});
  const auto a = simulate(sc, grid);
#ifdef _OPENMP
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
#endif
  const auto b = simulate(sc, grid);
#ifdef _OPENMP
  omp_set_num_threads(threads);
#endif
  // The thread count as a setting: 1 and 3 threads give the same log too.
  const auto c = simulate(sc, grid, 1), d = simulate(sc, grid, 3);
  ASSERT_EQ(a.records.size(), b.records.size());
  ASSERT_EQ(a.records.size(), c.records.size());
  ASSERT_EQ(a.records.size(), d.records.size());
  for (std::size_t k = 0; k < a.records.size(); ++k) {
    EXPECT_EQ(a.records[k].scan.ranges, b.records[k].scan.ranges);
    EXPECT_EQ(a.records[k].scan.ranges, c.records[k].scan.ranges);
    EXPECT_EQ(a.records[k].scan.ranges, d.records[k].scan.ranges);
    EXPECT_EQ(a.records[k].odometry.x, b.records[k].odometry.x);
  }
  sc.seed = 6;
  EXPECT_NE(simulate(sc, grid).records[3].scan.ranges, a.records[3].scan.ranges);
}

TEST(Simulate, MovingObstaclesOccludeBeamsButAreNotInTheMap) {
  const auto grid = test::square_room(100, 100, 0.05);
  Scenario sc;
  sc.motion = MotionMode::kStationary;
  sc.start = {1.0, 2.5, 0.0};
  sc.noise = BeamNoise::none();
  sc.duration = 4.0;
  sc.scan_rate = 1.0;
  // A disc crossing the x axis of the robot at x = 3, 0.5 m/s, from y = 1.5 to 3.5 and back.
  sc.discs.push_back({0.2, {{{3.0, 1.5}, {3.0, 3.5}}, 0.5, 0.0}, "average"});
  // A static box straight to the left: its lower face at y = 3.8 m, 1.3 m from the robot.
  sc.boxes.push_back({0.4, 0.2, 0.0, {{{1.0, 4.0}}, 0.0, 0.0}, "white_paper"});
  const auto log = simulate(sc, grid);
  EXPECT_NEAR(log.records[1].scan.ranges[900], 1.3, 1e-4);  // bearing +90 deg
  const std::size_t centre = 540;                           // the beam along +x
  // t = 2 s: the disc is centred on the beam, 2 m ahead: 1.8 m to its surface.
  EXPECT_NEAR(log.records[2].scan.ranges[centre], 1.8, 1e-4);
  // t = 0 s: it is 1 m to the side; the beam reaches the wall at x = 4.95.
  EXPECT_NEAR(log.records[0].scan.ranges[centre], 3.95, 1e-4);
  // The beam pointing at the disc at t = 0 (bearing atan2(-1, 2)) sees it there.
  const double bearing = std::atan2(-1.0, 2.0);
  const auto i = static_cast<std::size_t>(
      std::lround((bearing - sc.sensor.angle_min) / sc.sensor.angle_increment));
  EXPECT_NEAR(log.records[0].scan.ranges[i], std::hypot(2.0, 1.0) - 0.2, 0.01);
  EXPECT_FALSE(grid.occupied(60, 30));  // the map never contains it
  // Stationary: odometry and truth never move.
  EXPECT_EQ(log.records.back().truth.x, 1.0);
}

TEST(Simulate, KidnapMovesTruthNotOdometry) {
  const auto grid = test::square_room(100, 100, 0.05);
  Scenario sc;
  sc.motion = MotionMode::kStationary;
  sc.start = {1.0, 1.0, 0.0};
  sc.duration = 1.0;
  sc.scan_rate = 10.0;
  sc.odometry.random_noise = false;
  sc.kidnaps = {{0.55, {4.0, 4.0, kPi}}};
  const auto log = simulate(sc, grid);
  EXPECT_EQ(log.kidnap_times, std::vector<double>{0.55});
  EXPECT_EQ(log.records[5].truth.x, 1.0);
  EXPECT_EQ(log.records[6].truth.x, 4.0);
  EXPECT_EQ(log.records[6].odometry.x, 1.0);
  // The scan after the kidnap is taken from the new pose: facing -x from x = 4, the wall
  // at x = 0.05 is 3.95 m away.
  EXPECT_NEAR(log.records[6].scan.ranges[540], 3.95, 0.05);
}

TEST(Simulate, ValidationNamesTheField) {
  const auto grid = test::square_room(100, 100, 0.05);
  auto expect_field = [&](const Scenario& sc, const std::string& field) {
    try {
      (void)simulate(sc, grid);
      ADD_FAILURE() << "no exception for " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  Scenario sc = small_scenario();
  sc.start = {50.0, 1.0, 0.0};
  expect_field(sc, "start");
  sc = small_scenario();
  sc.motion = MotionMode::kRandomWalk;
  sc.start = {0.1, 0.1, 0.0};  // touches the wall
  expect_field(sc, "start");
  sc = small_scenario();
  sc.discs.push_back({0.2, {{{1, 1}}, 0.0, 0.0}, "velvet"});
  expect_field(sc, "discs[0].material");
  sc = small_scenario();
  sc.boxes.push_back({-1.0, 0.2, 0.0, {{{1, 1}}, 0.0, 0.0}, "average"});
  expect_field(sc, "boxes[0].half_length");
  sc = small_scenario();
  sc.control_rate = 0.0;
  expect_field(sc, "control_rate");
  sc = small_scenario();
  sc.kidnaps = {{1.0, {-20.0, 0.0, 0.0}}};
  expect_field(sc, "kidnaps[0].pose");
  sc = small_scenario();
  sc.noise.specular.rate = 2.0;
  expect_field(sc, "specular.rate");
}

}  // namespace
}  // namespace pgmcl::sims
