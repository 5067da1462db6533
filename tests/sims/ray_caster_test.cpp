#include "pgmcl/sims/ray_caster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "pgmcl/common/random.hpp"
#include "scenes.hpp"

namespace pgmcl::sims {
namespace {

constexpr double kPi = std::numbers::pi;

// Axis-aligned scenes are represented exactly by the grid, so the DDA must reproduce the
// analytic range up to float rounding (1e-4 m over a few metres).
constexpr double kExactTol = 1e-4;

TEST(RayCaster, SquareRoomFromSubCellStartsMatchesAnalyticRanges) {
  const double res = 0.05;
  const auto grid = test::square_room(80, 60, res);
  const RayCaster rc(grid);
  const double x0 = res, y0 = res, x1 = 79 * res, y1 = 59 * res;
  Rng rng(7);
  std::vector<double> angles;
  for (int k = 0; k < 8; ++k) angles.push_back(k * kPi / 4);  // exact axes and diagonals
  for (int k = 0; k < 200; ++k) angles.push_back(rng.uniform(-kPi, kPi));
  // Starts at cell corners, on cell edges and at arbitrary sub-cell positions.
  const double starts[][2] = {{1.0, 1.0},       {1.025, 1.5},     {2.0, 1.0125},
                              {0.0513, 0.0771}, {3.9499, 2.9499}, {1.2345, 2.3456}};
  for (const auto& s : starts) {
    for (const double a : angles) {
      const double dx = std::cos(a), dy = std::sin(a);
      const auto hit = rc.cast_local(static_cast<float>(s[0]), static_cast<float>(s[1]),
                                     static_cast<float>(a), 30.0F);
      ASSERT_TRUE(hit.hit);
      const double expect = test::range_to_box_wall(s[0], s[1], dx, dy, x0, y0, x1, y1);
      EXPECT_NEAR(hit.range, expect, kExactTol) << "start " << s[0] << "," << s[1] << " a=" << a;
      EXPECT_NEAR(hit.x, s[0] + expect * dx, kExactTol);
      EXPECT_NEAR(hit.y, s[1] + expect * dy, kExactTol);
      EXPECT_TRUE(grid.occupied(hit.col, hit.row));
    }
  }
}

TEST(RayCaster, MatchesBruteForceOracleOnRandomClutter) {
  maps::OccupancyGrid grid(40, 30, 0.1, {}, maps::kFree);
  Rng rng(11);
  for (int k = 0; k < 120; ++k) {
    grid.set(static_cast<int>(rng.below(40)), static_cast<int>(rng.below(30)), maps::kOccupied);
  }
  const RayCaster rc(grid);
  int hits = 0;
  for (int k = 0; k < 3000; ++k) {
    const double x = rng.uniform(-0.5, 4.5), y = rng.uniform(-0.5, 3.5);  // also outside
    double a = rng.uniform(-kPi, kPi);
    if (k % 10 == 0) a = (k / 10 % 8) * kPi / 4;
    const float fx = static_cast<float>(x), fy = static_cast<float>(y);
    const auto fa = static_cast<float>(a);
    const double dx = std::cos(fa), dy = std::sin(fa);
    const double oracle = test::brute_force_range(grid, fx, fy, dx, dy);
    const auto hit = rc.cast_local(fx, fy, fa, 10.0F);
    if (oracle <= 10.0 - 1e-3) {
      ASSERT_TRUE(hit.hit) << x << "," << y << " a=" << a << " oracle " << oracle;
      EXPECT_NEAR(hit.range, oracle, kExactTol) << x << "," << y << " a=" << a;
      ++hits;
    } else if (oracle > 10.0 + 1e-3) {
      EXPECT_FALSE(hit.hit);
      EXPECT_FLOAT_EQ(hit.range, 10.0F);
    }
  }
  EXPECT_GT(hits, 1500);
}

TEST(RayCaster, CircularRoomHitsWithinHalfACellOfTheCircle) {
  // Free disc of radius 1.5 m rasterised by cell centres inside an occupied grid.
  // Tolerance stated: the DDA hit point lies within half a cell, in the max norm, of the
  // true circle. Proof: the crossed face separates a free cell (centre inside the circle)
  // from an occupied one (centre outside), so the circle crosses the segment joining the two
  // centres, and every point of the shared face is within 0.5 cell of that crossing in x
  // and in y. Along a near-radial ray that bounds the range error by sqrt(2)/2 cell.
  const double res = 0.05, cx = 2.0, cy = 2.0, radius = 1.5;
  maps::OccupancyGrid grid(80, 80, res, {}, maps::kOccupied);
  test::fill_disc(grid, cx, cy, radius, maps::kFree);
  const RayCaster rc(grid);
  Rng rng(3);
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const double x = cx + rng.uniform(-0.1, 0.1), y = cy + rng.uniform(-0.1, 0.1);
    double a = rng.uniform(-kPi, kPi);
    if (k < 16) a = k * kPi / 8;
    const double dx = std::cos(a), dy = std::sin(a);
    // Analytic: |p + t d - c| = R.
    const double px = x - cx, py = y - cy, b = px * dx + py * dy;
    const double t = -b + std::sqrt(b * b - (px * px + py * py - radius * radius));
    const auto hit =
        rc.cast_local(static_cast<float>(x), static_cast<float>(y), static_cast<float>(a), 30.0F);
    ASSERT_TRUE(hit.hit);
    EXPECT_LE(test::max_norm_distance_to_circle(hit.x, hit.y, cx, cy, radius), 0.5 * res + 1e-6);
    worst = std::max(worst, std::abs(hit.range - t));
  }
  // Along a near-radial ray the range error is at most the Euclidean bound sqrt(2)/2 cell.
  EXPECT_LE(worst, std::sqrt(0.5) * res);
  std::printf("circular room: worst range error %.3f cells\n", worst / res);
}

TEST(RayCaster, DiscObstacleSeenFromOutsideWithinHalfACell) {
  const double res = 0.05, cx = 3.0, cy = 2.0, radius = 0.6;
  maps::OccupancyGrid grid(100, 80, res, {}, maps::kFree);
  test::fill_disc(grid, cx, cy, radius, maps::kOccupied);
  const RayCaster rc(grid);
  Rng rng(5);
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    // Aim at the disc from a distance, within +-0.6 of the radius, so the incidence stays
    // below ~37 degrees; same half-cell (max-norm) bound as the circular room.
    const double x = rng.uniform(0.3, 1.0), y = rng.uniform(0.5, 3.5);
    const double to_c = std::atan2(cy - y, cx - x), dist = std::hypot(cy - y, cx - x);
    const double a = to_c + std::asin(rng.uniform(-0.6, 0.6) * radius / dist);
    const double dx = std::cos(a), dy = std::sin(a);
    const double px = x - cx, py = y - cy, b = px * dx + py * dy;
    const double t = -b - std::sqrt(b * b - (px * px + py * py - radius * radius));
    const auto hit =
        rc.cast_local(static_cast<float>(x), static_cast<float>(y), static_cast<float>(a), 30.0F);
    ASSERT_TRUE(hit.hit);
    EXPECT_LE(test::max_norm_distance_to_circle(hit.x, hit.y, cx, cy, radius), 0.5 * res + 1e-6);
    worst = std::max(worst, std::abs(hit.range - t));
  }
  EXPECT_LE(worst, std::sqrt(0.5) * res / std::cos(std::asin(0.6)));
  std::printf("disc: worst range error %.3f cells\n", worst / res);
}

TEST(RayCaster, CornerAlongAxesAndDiagonalsIsExact) {
  // An inside corner: walls on the top (rows >= 30) and right (cols >= 30) of the free area.
  const double res = 0.1;
  maps::OccupancyGrid grid(40, 40, res, {}, maps::kFree);
  test::fill_cells(grid, 0, 30, 39, 39, maps::kOccupied);
  test::fill_cells(grid, 30, 0, 39, 39, maps::kOccupied);
  const RayCaster rc(grid);
  // Exactly into the corner vertex (3, 3) along the diagonal, from a cell corner and from
  // a sub-cell start on the diagonal.
  for (const double s : {1.0, 1.37, 2.95}) {
    const auto hit = rc.cast_local(static_cast<float>(s), static_cast<float>(s),
                                   static_cast<float>(kPi / 4), 10.0F);
    ASSERT_TRUE(hit.hit);
    EXPECT_NEAR(hit.range, std::sqrt(2.0) * (3.0 - s), kExactTol);
    EXPECT_NEAR(hit.x, 3.0, kExactTol);
    EXPECT_NEAR(hit.y, 3.0, kExactTol);
  }
  // Along the axes, from a start lying exactly on a cell boundary.
  auto east = rc.cast_local(1.0F, 2.0F, 0.0F, 10.0F);
  EXPECT_NEAR(east.range, 2.0, kExactTol);
  EXPECT_EQ(east.face, HitFace::kMinX);
  EXPECT_EQ(east.col, 30);
  auto north = rc.cast_local(2.05F, 1.0F, static_cast<float>(kPi / 2), 10.0F);
  EXPECT_NEAR(north.range, 2.0, kExactTol);
  EXPECT_EQ(north.face, HitFace::kMinY);
  EXPECT_EQ(north.row, 30);
  // West and south leave the grid: no hit, range = max_range.
  auto west = rc.cast_local(1.0F, 2.0F, static_cast<float>(kPi), 10.0F);
  EXPECT_FALSE(west.hit);
  EXPECT_FLOAT_EQ(west.range, 10.0F);
  // A shallow ray along the top wall at 1e-3 m below it still hits the right wall.
  auto skim = rc.cast_local(0.5F, 2.999F, 0.0F, 10.0F);
  EXPECT_NEAR(skim.range, 2.5, kExactTol);
  // max_range shorter than the wall.
  auto short_ray = rc.cast_local(1.0F, 2.0F, 0.0F, 1.5F);
  EXPECT_FALSE(short_ray.hit);
  EXPECT_FLOAT_EQ(short_ray.range, 1.5F);
}

TEST(RayCaster, GlobalFrameHonoursRotatedAndShiftedOrigin) {
  const double res = 0.05;
  const Pose2 origin{-3.2, 1.7, 0.7};
  const auto grid = test::square_room(80, 60, res, origin);
  const RayCaster rc(grid);
  Rng rng(9);
  for (int k = 0; k < 500; ++k) {
    const double lx = rng.uniform(0.2, 3.8), ly = rng.uniform(0.2, 2.8);
    const double la = rng.uniform(-kPi, kPi);
    const Pose2 ray = origin.compose({lx, ly, la});  // the same ray in the global frame
    const auto hit = rc.cast(ray, 30.0);
    ASSERT_TRUE(hit.hit);
    const double expect =
        test::range_to_box_wall(lx, ly, std::cos(la), std::sin(la), res, res, 79 * res, 59 * res);
    EXPECT_NEAR(hit.range, expect, kExactTol);
    EXPECT_NEAR(hit.x, ray.x + expect * std::cos(ray.theta), 2 * kExactTol);
    EXPECT_NEAR(hit.y, ray.y + expect * std::sin(ray.theta), 2 * kExactTol);
    double col = 0, row = 0;
    grid.global_to_cell(hit.x, hit.y, col, row);
    EXPECT_NEAR(col, std::clamp(col, double(hit.col), hit.col + 1.0), 1e-3);
    EXPECT_NEAR(row, std::clamp(row, double(hit.row), hit.row + 1.0), 1e-3);
  }
  const auto same = cast_ray(grid, origin.compose({2.0, 1.5, 0.0}), 30.0);
  EXPECT_NEAR(same.range, 79 * res - 2.0, kExactTol);
}

TEST(RayCaster, UnknownCellPolicies) {
  maps::OccupancyGrid grid(50, 10, 0.1, {}, maps::kFree);
  test::fill_cells(grid, 20, 0, 24, 9, maps::kUnknown);
  grid.set(40, 5, maps::kOccupied);
  const auto through = RayCaster(grid).cast_local(0.55F, 0.55F, 0.0F, 20.0F);
  EXPECT_TRUE(through.hit);
  EXPECT_NEAR(through.range, 4.0 - 0.55, kExactTol);
  const auto block =
      RayCaster(grid, {UnknownCellPolicy::kBlock}).cast_local(0.55F, 0.55F, 0.0F, 20.0F);
  EXPECT_TRUE(block.hit);
  EXPECT_NEAR(block.range, 2.0 - 0.55, kExactTol);
  EXPECT_EQ(block.col, 20);
  const auto absorb =
      RayCaster(grid, {UnknownCellPolicy::kAbsorb}).cast_local(0.55F, 0.55F, 0.0F, 20.0F);
  EXPECT_FALSE(absorb.hit);
  EXPECT_FLOAT_EQ(absorb.range, 20.0F);
}

TEST(RayCaster, StartInsideAnOccupiedCellGivesZeroRange) {
  maps::OccupancyGrid grid(10, 10, 0.1, {}, maps::kFree);
  grid.set(3, 3, maps::kOccupied);
  const auto hit = RayCaster(grid).cast_local(0.35F, 0.35F, 1.0F, 5.0F);
  EXPECT_TRUE(hit.hit);
  EXPECT_EQ(hit.face, HitFace::kStart);
  EXPECT_FLOAT_EQ(hit.range, 0.0F);
}

TEST(RayCaster, FullScanAgreesWithSingleRays) {
  const auto grid = test::square_room(100, 100, 0.05, {1.0, -2.0, -0.4});
  const RayCaster rc(grid);
  const BeamFan fan{-3 * kPi / 4, kPi / 720, 1081, 30.0};
  const Pose2 sensor = grid.origin().compose({2.3, 2.6, 0.3});
  std::vector<float> ranges(1081);
  rc.cast_scan(sensor, fan, ranges);
  ScanHits hits;
  rc.cast_scan(sensor, fan, hits);
  for (int i = 0; i < fan.count; i += 7) {
    const double a = fan.angle_min + i * fan.angle_increment;
    const auto one = rc.cast({sensor.x, sensor.y, sensor.theta + a}, 30.0);
    EXPECT_NEAR(ranges[static_cast<std::size_t>(i)], one.range, 1e-4);
    EXPECT_EQ(hits.range[static_cast<std::size_t>(i)], ranges[static_cast<std::size_t>(i)]);
    EXPECT_TRUE(grid.occupied(hits.col[static_cast<std::size_t>(i)],
                              hits.row[static_cast<std::size_t>(i)]));
  }
  std::vector<float> wrong(10);
  EXPECT_THROW(rc.cast_scan(sensor, fan, wrong), std::invalid_argument);
}

}  // namespace
}  // namespace pgmcl::sims
