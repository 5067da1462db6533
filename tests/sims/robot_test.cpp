#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pgmcl/sims/scenario.hpp"
#include "scenes.hpp"

namespace pgmcl::sims {
namespace {

constexpr double kPi = std::numbers::pi;

double seg_dist(const Point2& p, const Point2& a, const Point2& b) {
  const double ex = b.x - a.x, ey = b.y - a.y, l2 = ex * ex + ey * ey;
  const double u = std::clamp(((p.x - a.x) * ex + (p.y - a.y) * ey) / l2, 0.0, 1.0);
  return std::hypot(p.x - a.x - u * ex, p.y - a.y - u * ey);
}

// Distance from p to the polyline through pts.
double polyline_dist(const Point2& p, const std::vector<Point2>& pts) {
  double d = 1e9;
  for (std::size_t k = 0; k + 1 < pts.size(); ++k) d = std::min(d, seg_dist(p, pts[k], pts[k + 1]));
  return d;
}

TEST(DiffDrive, ArcsAreExactAndComposeOverSubsteps) {
  const Pose2 p{1.0, 2.0, 0.3};
  const VelocityCommand straight{0.5, 0.0};
  const Pose2 s = integrate_diff_drive(p, straight, 2.0);
  EXPECT_NEAR(s.x, 1.0 + std::cos(0.3), 1e-12);
  EXPECT_NEAR(s.y, 2.0 + std::sin(0.3), 1e-12);
  // Quarter circle of radius 1 from the origin heading +x ends at (1, 1) heading +y.
  const Pose2 q = integrate_diff_drive({}, {kPi / 2, kPi / 2}, 1.0);
  EXPECT_NEAR(q.x, 1.0, 1e-12);
  EXPECT_NEAR(q.y, 1.0, 1e-12);
  EXPECT_NEAR(q.theta, kPi / 2, 1e-12);
  Pose2 r = p;
  for (int i = 0; i < 100; ++i) r = integrate_diff_drive(r, {0.4, -0.7}, 0.013);
  const Pose2 once = integrate_diff_drive(p, {0.4, -0.7}, 1.3);
  EXPECT_NEAR(r.x, once.x, 1e-12);
  EXPECT_NEAR(r.y, once.y, 1e-12);
  EXPECT_NEAR(r.theta, once.theta, 1e-12);
}

Scenario path_scenario(Controller c) {
  Scenario sc;
  sc.start = {1.0, 1.0, 0.0};
  sc.waypoints.waypoints = {{4.0, 1.0}, {4.0, 4.0}, {1.0, 4.0}};
  sc.waypoints.controller = c;
  sc.duration = 40.0;
  sc.scan_rate = 10.0;
  sc.odometry.random_noise = false;
  return sc;
}

TEST(WaypointFollowing, PurePursuitTracksThePathAndStopsAtTheGoal) {
  const auto grid = test::square_room(100, 100, 0.05);
  const Scenario sc = path_scenario(Controller::kPurePursuit);
  const auto m = simulate_motion(sc, grid);
  const std::vector<Point2> pts = {{1, 1}, {4, 1}, {4, 4}, {1, 4}};
  double worst = 0.0;
  for (std::size_t i = 1; i < m.size(); ++i) {
    const Point2 p{m[i].truth.x, m[i].truth.y};
    worst = std::max(worst, polyline_dist(p, pts));
    // Speed limit: 0.5 m/s over 0.1 s between scans.
    EXPECT_LE(std::hypot(m[i].truth.x - m[i - 1].truth.x, m[i].truth.y - m[i - 1].truth.y),
              0.05 + 1e-9);
  }
  // Corner cutting of pure pursuit is bounded by the lookahead (0.5 m).
  EXPECT_LT(worst, 0.5 * sc.waypoints.lookahead);
  EXPECT_NEAR(m.back().truth.x, 1.0, sc.waypoints.goal_tolerance);
  EXPECT_NEAR(m.back().truth.y, 4.0, sc.waypoints.goal_tolerance);
}

TEST(WaypointFollowing, LoopingPurePursuitKeepsCirculating) {
  const auto grid = test::square_room(100, 100, 0.05);
  Scenario sc = path_scenario(Controller::kPurePursuit);
  sc.waypoints.loop = true;
  sc.duration = 60.0;  // the loop closes from the last waypoint back to the first:
  const auto m = simulate_motion(sc, grid);  // a triangle with a 135 deg corner at (1, 4)
  const std::vector<Point2> pts = {{1, 1}, {4, 1}, {4, 4}, {1, 4}, {4, 1}};
  double worst = 0.0, late = 0.0;
  for (std::size_t i = 1; i < m.size(); ++i) {
    const Point2 p{m[i].truth.x, m[i].truth.y};
    worst = std::max(worst, polyline_dist(p, pts));
    if (m[i].stamp > 50.0) late += std::hypot(p.x - m[i - 1].truth.x, p.y - m[i - 1].truth.y);
  }
  EXPECT_LT(worst, 0.5 * sc.waypoints.lookahead);
  EXPECT_GT(late, 4.0);  // still driving (near 0.5 m/s) in the last 10 s
}

TEST(WaypointFollowing, TurnThenDriveVisitsEveryWaypointOnStraightLegs) {
  const auto grid = test::square_room(100, 100, 0.05);
  const Scenario sc = path_scenario(Controller::kTurnThenDrive);
  const auto m = simulate_motion(sc, grid);
  const std::vector<Point2> pts = {{1, 1}, {4, 1}, {4, 4}, {1, 4}};
  std::vector<double> closest(pts.size(), 1e9);
  double worst = 0.0;
  for (const auto& s : m) {
    const Point2 p{s.truth.x, s.truth.y};
    double d = 1e9;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k)
      d = std::min(d, seg_dist(p, pts[k], pts[k + 1]));
    worst = std::max(worst, d);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      closest[k] = std::min(closest[k], std::hypot(p.x - pts[k].x, p.y - pts[k].y));
    }
  }
  // Straight legs; a leg ends within goal_tolerance of its waypoint, so the next one
  // starts at most that far off the polyline.
  EXPECT_LT(worst, sc.waypoints.goal_tolerance);
  for (const double c : closest) EXPECT_LT(c, 0.05);
}

TEST(RandomWalk, StaysInFreeSpaceAndIsSeeded) {
  auto grid = test::square_room(120, 100, 0.05, {-1.0, -2.0, 0.4});
  test::fill_cells(grid, 40, 0, 44, 60, maps::kOccupied);  // an internal wall
  test::fill_disc(grid, 4.0, 3.5, 0.5, maps::kOccupied);   // a pillar (map-local)
  test::fill_cells(grid, 80, 70, 90, 80, maps::kUnknown);  // an unknown patch
  Scenario sc;
  sc.motion = MotionMode::kRandomWalk;
  sc.start = grid.origin().compose({1.0, 1.0, 0.0});
  sc.duration = 120.0;
  sc.scan_rate = 10.0;
  sc.seed = 42;
  const auto m = simulate_motion(sc, grid);
  const FreeSpace free(grid, sc.random_walk.clearance);
  double travelled = 0.0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    ASSERT_TRUE(free.admissible(m[i].truth.x, m[i].truth.y)) << "t=" << m[i].stamp;
    if (i)
      travelled += std::hypot(m[i].truth.x - m[i - 1].truth.x, m[i].truth.y - m[i - 1].truth.y);
  }
  EXPECT_GT(travelled, 20.0);  // it explores rather than spinning in place
  const auto again = simulate_motion(sc, grid);
  EXPECT_EQ(again.back().truth.x, m.back().truth.x);
  sc.seed = 43;
  EXPECT_NE(simulate_motion(sc, grid).back().truth.x, m.back().truth.x);
}

TEST(Odometry, NoiseFreeOdometryEqualsTruthAndKidnapIsInvisible) {
  const auto grid = test::square_room(100, 100, 0.05);
  Scenario sc = path_scenario(Controller::kPurePursuit);
  sc.kidnaps = {{12.0, {2.0, 3.0, -1.0}}};
  const auto m = simulate_motion(sc, grid);
  const auto odom = simulate_odometry(sc, m);
  bool jumped = false;
  for (std::size_t i = 1; i < m.size(); ++i) {
    const double step =
        std::hypot(m[i].truth.x - m[i - 1].truth.x, m[i].truth.y - m[i - 1].truth.y);
    if (m[i].stamp < 12.0) {
      EXPECT_NEAR(odom[i].x, m[i].truth.x, 1e-9);
      EXPECT_NEAR(odom[i].theta, m[i].truth.theta, 1e-9);
    }
    if (m[i - 1].stamp < 12.0 && m[i].stamp >= 12.0) {
      jumped = true;
      EXPECT_GT(step, 0.5);  // the truth teleports
      EXPECT_NEAR(m[i].truth.x, 2.0, 0.06);
    }
    // Odometry moves no more than the robot could in 0.1 s.
    EXPECT_LE(std::hypot(odom[i].x - odom[i - 1].x, odom[i].y - odom[i - 1].y), 0.05 + 1e-9);
  }
  EXPECT_TRUE(jumped);
}

// A 5 m turn-then-drive run east from (1, 1), odometry in the world frame.
Scenario eastward_drive(double duration, double scan_rate) {
  Scenario sc;
  sc.start = {1.0, 1.0, 0.0};
  sc.waypoints.waypoints = {{6.0, 1.0}};
  sc.waypoints.controller = Controller::kTurnThenDrive;
  sc.duration = duration;
  sc.scan_rate = scan_rate;
  sc.odometry.origin = Pose2{};
  return sc;
}

TEST(Odometry, SystematicErrorsScaleDistanceAndBendHeading) {
  const auto grid = test::square_room(200, 40, 0.05);
  Scenario sc = eastward_drive(15.0, 10.0);
  sc.odometry.random_noise = false;
  sc.odometry.wheel_radius_bias = 0.02;
  auto m = simulate_motion(sc, grid);
  auto odom = simulate_odometry(sc, m);
  const double driven = m.back().truth.x - 1.0;  // stops within goal_tolerance of 6.0
  EXPECT_NEAR(driven, 5.0, sc.waypoints.goal_tolerance);
  EXPECT_NEAR(odom.back().x, driven * 1.02, 1e-9);
  EXPECT_NEAR(odom.back().theta, 0.0, 1e-9);
  sc.odometry.wheel_radius_bias = 0.0;
  sc.odometry.yaw_drift_per_metre = 0.01;
  odom = simulate_odometry(sc, m);
  EXPECT_NEAR(odom.back().theta, 0.01 * driven, 1e-9);  // 0.01 rad/m
  // Rotations: a 90 deg turn reported as 90 / 1.05 deg with a 5 % wheelbase bias.
  OdometrySettings wheelbase;
  wheelbase.wheelbase_bias = 0.05;
  const Pose2 inc = apply_systematic_error({0.0, 0.0, kPi / 2}, wheelbase);
  EXPECT_NEAR(inc.theta, kPi / 2 / 1.05, 1e-12);
}

TEST(Odometry, RandomNoiseFollowsTheAlphas) {
  // Straight 5 m drive in 50 intervals: var(trans) = a3 trans^2 per interval, so the
  // odometry distance error has sd sqrt(50 a3) * 0.1 m. Checked over 400 seeds.
  const auto grid = test::square_room(200, 40, 0.05);
  Scenario sc = eastward_drive(12.0, 5.0);  // 0.1 m per interval at 0.5 m/s
  sc.odometry.alphas = {0.0, 0.0, 0.01, 0.0, 0.0};
  const auto m = simulate_motion(sc, grid);
  double s = 0.0, ss = 0.0;
  const int n = 400;
  for (int k = 0; k < n; ++k) {
    sc.seed = 100 + static_cast<std::uint64_t>(k);
    const double e = simulate_odometry(sc, m).back().x - 5.0;
    s += e;
    ss += e * e;
  }
  const double sd = std::sqrt((ss - s * s / n) / (n - 1));
  const double expect = std::sqrt(50 * 0.01) * 0.1;
  EXPECT_NEAR(sd, expect, 0.1 * expect);
}

}  // namespace
}  // namespace pgmcl::sims
